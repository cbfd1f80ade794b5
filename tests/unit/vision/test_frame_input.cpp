// fin-track's inputs as labs have them (issue 35, items 1 and 2): frame numbers from any image
// name in natural order, MJPG AVI clips written here with cv::VideoWriter read back with their
// frame rate, clips of different rates or lengths and an undecodable clip refused, view roles
// from the camera geometry whatever the views are called, and fin-track run on renamed views
// and on AVI clips giving the same fit, with --help and kinematics.h5 showing the defaults it runs.
#include <gtest/gtest.h>

#include <sys/wait.h>
#include <unistd.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <regex>
#include <string>

#include <nlohmann/json.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/videoio.hpp>

#include "core/error.hpp"
#include "core/hdf5_file.hpp"
#include "core/stage_files.hpp"
#include "vision/camera.hpp"
#include "vision/frame_files.hpp"
#include "vision/tracker.hpp"
#include "vision/video_clip.hpp"
#include "vision/view_roles.hpp"

using namespace finverse;
using namespace finverse::vision;
namespace fs = std::filesystem;

namespace {

struct TempDir {
  fs::path dir;
  explicit TempDir(const std::string& tag) : dir(fs::temp_directory_path() / (tag + "_" + std::to_string(::getpid()))) {
    fs::remove_all(dir);
    fs::create_directories(dir);
  }
  ~TempDir() { fs::remove_all(dir); }
};

// A frame with a dark disc whose place encodes the frame index (checks the order read back).
cv::Mat test_frame(long k, int w = 96, int h = 64) {
  cv::Mat img(h, w, CV_8UC3, cv::Scalar(200, 200, 200));
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      if (std::hypot(x - (10.0 + 6 * k), y - 32.0) < 6) img.at<cv::Vec3b>(y, x) = {40, 40, 40};
  return img;
}

// The mean column of the dark pixels: where test_frame put its disc.
int disc_column(const cv::Mat& grey) {
  double sx = 0, n = 0;
  for (int y = 0; y < grey.rows; ++y)
    for (int x = 0; x < grey.cols; ++x)
      if (grey.at<std::uint8_t>(y, x) < 120) sx += x, n += 1;
  return n > 0 ? static_cast<int>(std::lround(sx / n)) : -1;
}

void write_avi(const fs::path& file, int frames, double fps, int w = 96, int h = 64) {
  cv::VideoWriter out(file.string(), cv::VideoWriter::fourcc('M', 'J', 'P', 'G'), fps, cv::Size(w, h), true);
  ASSERT_TRUE(out.isOpened()) << "OpenCV cannot write MJPG AVI here";
  for (int k = 0; k < frames; ++k) out.write(test_frame(k, w, h));
}

std::vector<Camera> rig(const std::vector<std::string>& names) {
  auto cams = default_rig({"side", "back", "ventral"}, 0.01, 96, 64);
  for (std::size_t v = 0; v < cams.size() && v < names.size(); ++v) cams[v].name = names[v];
  cams.resize(names.size());
  return cams;
}

}  // namespace

TEST(FrameInput, FrameNumbersAreTheLastNumberOfAnyName) {
  EXPECT_EQ(frame_number("frame_0001.png"), 1);
  EXPECT_EQ(frame_number("img12.jpg"), 12);
  EXPECT_EQ(frame_number("cam2_000010.tif"), 10);
  EXPECT_EQ(frame_number("000003.png"), 3);
  EXPECT_EQ(frame_number("12_take3_b.png"), 3);
  EXPECT_FALSE(frame_number("background.png"));
}

TEST(FrameInput, ImageSequencesInNaturalOrderWhateverTheirNames) {
  TempDir t("frame_input_images");
  fs::create_directories(t.dir / "dorsal");
  for (long k : {2, 10, 1}) cv::imwrite((t.dir / "dorsal" / ("frame_" + std::to_string(k) + ".png")).string(), test_frame(k));
  cv::imwrite((t.dir / "dorsal" / "background.png").string(), test_frame(0));  // no number: skipped
  const auto files = list_frame_files(t.dir, rig({"dorsal"}), {}, "cams.yml");
  EXPECT_EQ(files.frames, (std::vector<long>{1, 2, 10}));  // a string sort would give 1, 10, 2
  EXPECT_EQ(disc_column(files.load(0, 10)), 10 + 6 * 10);
  EXPECT_FALSE(files.container_fps);
  // view=path names the folder directly.
  const auto same = list_frame_files(std::vector<std::string>{"dorsal=" + (t.dir / "dorsal").string()}, rig({"dorsal"}), {}, "c");
  EXPECT_EQ(same.frames, files.frames);
  // Two images with one number: which is frame 2 is unknowable.
  cv::imwrite((t.dir / "dorsal" / "img_2.jpg").string(), test_frame(2));
  EXPECT_THROW(list_frame_files(t.dir, rig({"dorsal"}), {}, "c"), Error);
}

TEST(FrameInput, MjpgAviClipsReadBackWithTheirFrameRate) {
  TempDir t("frame_input_avi");
  write_avi(t.dir / "lateral.avi", 6, 250);
  const VideoClip clip(t.dir / "lateral.avi");
  EXPECT_EQ(clip.frames(), 6);
  EXPECT_NEAR(clip.fps(), 250, 1e-6);
  EXPECT_EQ(clip.width(), 96);
  // In order, then backwards (reopens): every frame is the one written.
  for (long k : {0, 1, 2, 5, 3, 0}) {
    const auto g = clip.grey(k);
    ASSERT_EQ(g.type(), CV_8UC1);
    EXPECT_EQ(disc_column(g), 10 + 6 * k) << k;
  }
  EXPECT_THROW(clip.grey(6), Error);
  // A folder with <view>.avi is a record, as is view=clip.
  write_avi(t.dir / "top.avi", 6, 250);
  const auto files = list_frame_files(t.dir, rig({"lateral", "top"}), {}, "c");
  EXPECT_EQ(files.frames.size(), 6u);
  ASSERT_TRUE(files.container_fps);
  EXPECT_NEAR(*files.container_fps, 250, 1e-6);
  const auto one = list_frame_files(std::vector<std::string>{"top=" + (t.dir / "top.avi").string()}, rig({"lateral", "top"}), {}, "c");
  EXPECT_FALSE(one.clips[0]);
  EXPECT_TRUE(one.clips[1]);
}

TEST(FrameInput, ClipsOfOtherRatesOrLengthsAndUndecodableClipsAreRefused) {
  TempDir t("frame_input_bad");
  write_avi(t.dir / "a.avi", 4, 250);
  write_avi(t.dir / "b.avi", 4, 200);
  write_avi(t.dir / "c.avi", 5, 250);
  std::ofstream(t.dir / "d.avi") << "not a video";
  const auto cams = rig({"x", "y"});
  auto message = [&](const std::string& x, const std::string& y) {
    try {
      list_frame_files(std::vector<std::string>{"x=" + (t.dir / x).string(), "y=" + (t.dir / y).string()}, cams, {}, "c");
    } catch (const Error& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_NE(message("a.avi", "b.avi").find("fps"), std::string::npos) << message("a.avi", "b.avi");
  EXPECT_NE(message("a.avi", "c.avi").find("5 frames"), std::string::npos) << message("a.avi", "c.avi");
  EXPECT_NE(message("a.avi", "d.avi").find("d.avi: cannot decode"), std::string::npos) << message("a.avi", "d.avi");
  EXPECT_NE(message("a.avi", "e.avi").find("no such file"), std::string::npos);
  // A view the calibration does not define.
  EXPECT_THROW(list_frame_files(std::vector<std::string>{"z=" + (t.dir / "a.avi").string()}, cams, {}, "c"), Error);
}

TEST(ViewRoles, RolesFollowTheCamerasNotTheNames) {
  const auto named = default_rig({"side", "back", "ventral"}, 0.01, 96, 64);
  const auto renamed = rig({"lateral", "dorsal", "cam3"});
  for (std::size_t v = 0; v < named.size(); ++v) {
    EXPECT_EQ(view_role(named[v]), v == 0 ? ViewRole::face_on : ViewRole::edge_on) << named[v].name;
    EXPECT_EQ(view_role(renamed[v]), view_role(named[v])) << renamed[v].name;
    EXPECT_EQ(fits_rays({"auto"}, renamed[v]), v == 0);
    EXPECT_EQ(fits_coverage({"auto"}, renamed[v]), v != 0);
  }
  EXPECT_TRUE(fits_rays({}, renamed[1]));
  EXPECT_TRUE(fits_rays({"all"}, renamed[1]));
  EXPECT_FALSE(fits_coverage({"none"}, renamed[1]));
  EXPECT_TRUE(fits_coverage({"dorsal"}, renamed[1]));
  EXPECT_FALSE(fits_coverage({"dorsal"}, renamed[2]));
  // A camera looking straight down the fin's normal is face-on, one at 60 degrees from it edge-on.
  EXPECT_EQ(view_role(look_at("a", 64, 64, 100, {0, -1, 0}, {0, 0, 0}, {0, 0, 1})), ViewRole::face_on);
  EXPECT_EQ(view_role(look_at("b", 64, 64, 100, {0, -0.5, 0.866}, {0, 0, 0}, {1, 0, 0})), ViewRole::edge_on);
}

#ifdef FIN_TRACK_EXE
namespace {

int run(const std::string& cmd, std::string* err = nullptr) {
  const auto log = fs::temp_directory_path() / ("fin_track_input_" + std::to_string(::getpid()) + ".err");
  const int rc = std::system((cmd + " 2> " + log.string()).c_str());
  if (err) {
    std::ifstream in(log);
    *err = {std::istreambuf_iterator<char>(in), {}};
  }
  fs::remove(log);
  return WIFEXITED(rc) ? WEXITSTATUS(rc) : -1;
}

nlohmann::json stored_config(const fs::path& h5) {
  const auto f = h5::File::open_read(h5);
  return nlohmann::json::parse(f.attr_string(".", "config").value_or("{}"));
}

}  // namespace

TEST(FinTrackInput, RenamedViewsAndAviClipsGiveTheSameFit) {
  TempDir t("fin_track_input");
  ASSERT_EQ(run(std::string(FIN_SYNTH_EXE) + " --out-dir " + t.dir.string() +
                " --width 128 --height 128 --periods 0.02 --vtk false --log-level error"),
            0);
  const std::string fast = " --first-iterations 2 --iterations 2 --threads 1";
  auto track = [&](const std::string& frames, const fs::path& cams, const fs::path& out, const std::string& extra,
                   std::string* err) {
    return run(std::string(FIN_TRACK_EXE) + " --frames " + frames + " --cameras " + cams.string() + " --out " + out.string() +
                   fast + extra,
               err);
  };
  std::string err;
  ASSERT_EQ(track((t.dir / "frames").string(), t.dir / "cameras.yml", t.dir / "ref.h5", "", &err), 0) << err;

  // The same rig with the views called lateral, dorsal and belly, given view by view: every
  // term follows the geometry, so the fit is the same to the bit.
  {
    std::ifstream in(t.dir / "cameras.yml");
    std::string yml{std::istreambuf_iterator<char>(in), {}};
    yml = std::regex_replace(yml, std::regex("\\bside\\b"), "lateral");
    yml = std::regex_replace(yml, std::regex("\\bback\\b"), "dorsal");
    yml = std::regex_replace(yml, std::regex("\\bventral\\b"), "belly");
    std::ofstream(t.dir / "renamed.yml") << yml;
  }
  const std::string renamed = "lateral=" + (t.dir / "frames" / "side").string() + ",dorsal=" +
                              (t.dir / "frames" / "back").string() + ",belly=" + (t.dir / "frames" / "ventral").string();
  ASSERT_EQ(track(renamed, t.dir / "renamed.yml", t.dir / "renamed.h5", " --log-level info", &err), 0) << err;
  EXPECT_NE(err.find("view 'lateral' (face-on): silhouette, rays"), std::string::npos) << err;
  EXPECT_NE(err.find("view 'dorsal' (edge-on): silhouette, coverage"), std::string::npos) << err;
  const auto ref = stage::read<stage::Kinematics>(t.dir / "ref.h5");
  const auto ren = stage::read<stage::Kinematics>(t.dir / "renamed.h5");
  EXPECT_EQ(ren.points.data, ref.points.data);
  EXPECT_EQ(ren.views, (std::vector<std::string>{"lateral", "dorsal", "belly"}));

  // The frames as MJPG AVI clips at 250 fps: the clip's rate is the record's, --fps overrides it.
  fs::create_directories(t.dir / "clips");
  for (const char* view : {"side", "back", "ventral"}) {
    cv::VideoWriter w((t.dir / "clips" / (std::string(view) + ".avi")).string(), cv::VideoWriter::fourcc('M', 'J', 'P', 'G'),
                      250, cv::Size(128, 128), false);
    ASSERT_TRUE(w.isOpened());
    std::vector<fs::path> pngs;
    for (const auto& e : fs::directory_iterator(t.dir / "frames" / view)) pngs.push_back(e.path());
    std::sort(pngs.begin(), pngs.end());
    for (const auto& p : pngs) w.write(cv::imread(p.string(), cv::IMREAD_GRAYSCALE));
  }
  ASSERT_EQ(track((t.dir / "clips").string(), t.dir / "cameras.yml", t.dir / "avi.h5", "", &err), 0) << err;
  const auto avi = stage::read<stage::Kinematics>(t.dir / "avi.h5");
  ASSERT_TRUE(avi.fps);
  EXPECT_NEAR(*avi.fps, 250, 1e-6);
  EXPECT_EQ(avi.points.shape, ref.points.shape);
  EXPECT_EQ(stored_config(t.dir / "avi.h5")["fps"], std::to_string(250.0));
  ASSERT_EQ(track((t.dir / "clips").string(), t.dir / "cameras.yml", t.dir / "avi2.h5", " --fps 1000", &err), 0) << err;
  EXPECT_NEAR(*stage::read<stage::Kinematics>(t.dir / "avi2.h5").fps, 1000, 1e-6);
  // A single video file as --frames: told to name its view.
  EXPECT_EQ(track((t.dir / "clips" / "side.avi").string(), t.dir / "cameras.yml", t.dir / "x.h5", "", &err), 2);
  EXPECT_NE(err.find("name its view: --frames side="), std::string::npos) << err;

  // Bad --fin-region: one line naming the flag, exit 2.
  EXPECT_EQ(track((t.dir / "frames").string(), t.dir / "cameras.yml", t.dir / "x.h5", " --fin-region side=1,2,3", &err), 2);
  EXPECT_NE(err.find("--fin-region: expected view=x0,y0,x1,y1"), std::string::npos) << err;
  EXPECT_EQ(track((t.dir / "frames").string(), t.dir / "cameras.yml", t.dir / "x.h5", " --fin-region top=0,0,9,9", &err), 2);
  EXPECT_NE(err.find("--fin-region: no view 'top'"), std::string::npos) << err;
  EXPECT_FALSE(fs::exists(t.dir / "x.h5"));

  // The defaults --help shows and kinematics.h5 stores are the ones the tracker runs.
  const auto fo = tracking_fit_options();
  const auto config = stored_config(t.dir / "ref.h5");
  EXPECT_EQ(config["first-iterations"], "2");  // given on the command line
  EXPECT_EQ(config["max-rejections"], std::to_string(fo.max_rejections));  // not given: the default run
  EXPECT_EQ(config["segments"], std::to_string(TrackerOptions{}.segments));
  const auto help = t.dir / "help.txt";
  ASSERT_EQ(run(std::string(FIN_TRACK_EXE) + " --help > " + help.string()), 0);
  std::ifstream in(help);
  const std::string text{std::istreambuf_iterator<char>(in), {}};
  EXPECT_NE(text.find("--iterations INT=" + std::to_string(fo.iterations) + " "), std::string::npos) << text;
  EXPECT_NE(text.find("--max-rejections INT=" + std::to_string(fo.max_rejections) + " "), std::string::npos) << text;
  EXPECT_NE(text.find("--first-iterations INT=" + std::to_string(fo.first_iterations) + " "), std::string::npos) << text;
}
#endif
