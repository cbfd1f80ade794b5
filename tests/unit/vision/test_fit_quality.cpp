// 3-D fits that know when they fail (issue 35, item 5): the verdict on hand-made per-frame
// qualities (one view, a template of the wrong size, a fit that covers nothing, a root that
// drifts away, a doubtful segmentation that is only flagged), and fin-track given a single view
// of fin-synth's frames: exit 1 with its reason, the record written and flagged.
#include <gtest/gtest.h>

#include <sys/wait.h>
#include <unistd.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

#include "core/stage_files.hpp"
#include "vision/fit_quality.hpp"

using namespace finverse;
using namespace finverse::vision;
namespace fs = std::filesystem;

namespace {

// `nf` frames of three views, all good: IoU 0.95, areas matched, root still.
std::vector<FrameQuality> good(std::size_t nf) {
  std::vector<FrameQuality> q(nf);
  for (std::size_t i = 0; i < nf; ++i) {
    q[i].iou = {0.95, 0.93, 0.9};
    q[i].area_ratio = {1.0, 1.05, 0.97};
    q[i].valid = {1, 1, 1};
    q[i].doubt = {0, 0, 0};
    q[i].root_drift = 0.3 * std::sin(0.5 * i);  // heave: well under a chord
    q[i].frame = static_cast<long>(i);
  }
  return q;
}
const std::vector<std::string> kViews{"lateral", "dorsal", "cam3"};

}  // namespace

TEST(FitQuality, AGoodFitPassesUnflagged) {
  const auto v = judge_fit(good(10), kViews, {});
  EXPECT_TRUE(v.failure.empty()) << v.failure;
  EXPECT_FALSE(v.flagged());
}

TEST(FitQuality, EachWayOfFailingHasItsReason) {
  auto one = good(10);  // one view: the others never show the fin
  for (auto& f : one) f.valid = {1, 0, 0}, f.iou[1] = f.iou[2] = NAN;
  const auto v1 = judge_fit(one, kViews, {});
  EXPECT_NE(v1.failure.find("fewer than 2 views show the fin (views with the fin: 'lateral')"), std::string::npos) << v1.failure;
  EXPECT_EQ(v1.flags[3] & kFewViews, kFewViews);
  // A view missing in a few frames only: flagged, not failed.
  auto some = good(10);
  some[4].valid = {1, 0, 0}, some[5].valid = {0, 0, 1};
  const auto v2 = judge_fit(some, kViews, {});
  EXPECT_TRUE(v2.failure.empty()) << v2.failure;
  EXPECT_EQ(v2.flags[4], kFewViews);
  EXPECT_EQ(v2.flags[3], 0);

  auto big = good(10);  // the template twice and a half the fish's size in one view
  for (auto& f : big) f.area_ratio[1] = 2.5, f.iou[1] = 0.4;
  const auto v3 = judge_fit(big, kViews, {});
  EXPECT_NE(v3.failure.find("in view 'dorsal' the fitted fin's area is 2.50 times"), std::string::npos) << v3.failure;

  auto none = good(10);  // the fit covers nothing
  for (auto& f : none) f.iou[0] = 0.0, f.area_ratio[0] = 1.0;
  const auto v4 = judge_fit(none, kViews, {});
  EXPECT_NE(v4.failure.find("IoU is 0.000"), std::string::npos) << v4.failure;
  EXPECT_EQ(v4.flags[0] & kLowIoU, kLowIoU);

  auto drift = good(10);  // sliding away: 0.5 chord per frame
  for (std::size_t i = 0; i < drift.size(); ++i) drift[i].root_drift = 0.5 * i;
  const auto v5 = judge_fit(drift, kViews, {});
  EXPECT_NE(v5.failure.find("root drifted 4.50 chords from the first frame's (frame 9"), std::string::npos) << v5.failure;
  FitQualityOptions off;
  off.max_root_drift = 0;
  EXPECT_TRUE(judge_fit(drift, kViews, off).failure.empty());

  auto doubt = good(10);  // a blob at the border: flagged only
  doubt[2].doubt[1] = 1;
  const auto v6 = judge_fit(doubt, kViews, {});
  EXPECT_TRUE(v6.failure.empty());
  EXPECT_EQ(v6.flags[2], kSegmentationDoubt);
}

#ifdef FIN_TRACK_EXE
TEST(FinTrackFitQuality, ASingleViewExitsOneWithItsReasonAndAFlaggedRecord) {
  const fs::path dir = fs::temp_directory_path() / ("fin_track_quality_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  ASSERT_EQ(std::system((std::string(FIN_SYNTH_EXE) + " --out-dir " + dir.string() +
                         " --width 128 --height 128 --periods 0.03 --vtk false --log-level error")
                            .c_str()),
            0);
  auto track = [&](const std::string& extra, std::string& err) {
    const auto log = dir / "err.txt";
    const int rc = std::system((std::string(FIN_TRACK_EXE) + " --frames " + (dir / "frames").string() + " --cameras " +
                                (dir / "cameras.yml").string() + " --out " + (dir / "kin.h5").string() +
                                " --threads 1 --log-level warn " + extra + " 2> " + log.string())
                                   .c_str());
    std::ifstream in(log);
    err = {std::istreambuf_iterator<char>(in), {}};
    return WIFEXITED(rc) ? WEXITSTATUS(rc) : -1;
  };
  std::string err;
  ASSERT_EQ(track("", err), 0) << err;  // three views: trusted
  EXPECT_FALSE(stage::read<stage::Kinematics>(dir / "kin.h5").fit_status);
  for (const std::string view : {"side", "back"}) {
    const std::string others = view == "side" ? "back,ventral" : "side,ventral";
    fs::remove(dir / "kin.h5");
    EXPECT_EQ(track("--ignore-view " + others, err), 1) << err;
    EXPECT_NE(err.find("error: fit failed: the views cannot constrain the 3-D fit"), std::string::npos) << err;
    EXPECT_NE(err.find("(views with the fin: '" + view + "')"), std::string::npos) << err;
    const auto k = stage::read<stage::Kinematics>(dir / "kin.h5");  // written, flagged
    ASSERT_TRUE(k.fit_status);
    EXPECT_NE(k.fit_status->find("cannot constrain"), std::string::npos);
    ASSERT_EQ(k.frame_flags.size(), k.time.size());
    for (auto f : k.frame_flags.data) EXPECT_EQ(f & kFewViews, kFewViews);
  }
  // A template twice the fin's size.
  EXPECT_EQ(track("--chord 0.02", err), 1) << err;
  EXPECT_NE(err.find("the template's scale cannot match the silhouettes"), std::string::npos) << err;
  fs::remove_all(dir);
}
#endif
