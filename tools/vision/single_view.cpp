// The 2-D single-view mode's run and its files (see single_view.hpp).
#include "vision/single_view.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <map>
#include <opencv2/imgproc.hpp>
#include <opencv2/videoio.hpp>
#include <sstream>

#include "core/atomic_file.hpp"
#include "core/error.hpp"
#include "core/hdf5_file.hpp"
#include "core/log.hpp"
#include "core/provenance.hpp"

namespace fs = std::filesystem;

namespace finverse::vision {
namespace {

// Refuses a clip in which the 2-D mode cannot work at all: no fish in any frame, or a fish that
// fills the frame (more than kFillsTheFrame of the image in the median frame with a fish), so
// that neither its outline nor a background is seen.
void check_the_fish_is_seen(const std::vector<cv::Mat>& masks, const std::string& source) {
  std::vector<double> cover;
  for (const auto& m : masks)
    if (const int n = cv::countNonZero(m); n > 0)
      cover.push_back(static_cast<double>(n) / static_cast<double>(m.total()));
  if (cover.empty())
    throw Error(source + ": no fish found in any of the " + std::to_string(masks.size()) +
                " frames (nothing darker than the background by --min-contrast)");
  std::nth_element(cover.begin(), cover.begin() + cover.size() / 2, cover.end());
  const double median = cover[cover.size() / 2];
  if (median > kFillsTheFrame) {
    char line[160];
    std::snprintf(line, sizeof line,
                  "the fish fills the frame (%.0f %% of the image in the median frame); expected the "
                  "whole fish in view with background around it",
                  100 * median);
    throw Error(source + ": " + line);
  }
}

// The frames not measured, and the reason given most often.
std::size_t count_invalid(const std::vector<MidlineFrame>& midlines, std::string& commonest) {
  std::map<std::string, std::size_t> reasons;
  std::size_t invalid = 0;
  for (const auto& m : midlines)
    if (!m.valid) ++invalid, ++reasons[m.reason];
  std::size_t most = 0;
  for (const auto& [reason, n] : reasons)
    if (n > most) most = n, commonest = reason;
  return invalid;
}

}  // namespace

SingleViewResult track_single_view(const std::vector<long>& frames, const std::function<cv::Mat(long)>& load,
                                   const SingleViewOptions& o, const std::string& source) {
  const std::size_t nf = frames.size();
  if (nf < 8) throw Error(source + ": the 2-D mode needs at least 8 frames for a tail beat, got " + std::to_string(nf));
  SegmentationContext ctx;
  ctx.fin_region = o.region;
  const auto mode = o.segmentation.background;
  if ((mode == BackgroundModel::median && nf >= 3) || (mode == BackgroundModel::automatic && nf >= kMedianMinFrames)) {
    const std::size_t k = std::min<std::size_t>(nf, 31);
    std::vector<cv::Mat> sample;
    for (std::size_t j = 0; j < k; ++j) sample.push_back(load(frames[k > 1 ? j * (nf - 1) / (k - 1) : 0]));
    ctx.median = temporal_median(sample, mode == BackgroundModel::median ? 0.5 : kStaticQuantile);
  }
  SingleViewResult r;
  r.frames = frames;
  r.segmentation_doubt.assign(nf, 0);
  std::vector<char> seg_lost(nf, 0);
  std::vector<cv::Mat> masks(nf);
  std::vector<TipEvidence> tips(nf);  // the darkening around the fish, for the sub-pixel tail tip
  for (std::size_t i = 0; i < nf; ++i) {
    const cv::Mat frame = load(frames[i]);
    const auto seg = segment_fin(frame, o.segmentation, ctx);
    masks[i] = seg.mask;
    if (cv::countNonZero(seg.mask) > 0) {
      const int pad = static_cast<int>(std::ceil(kTipReachPx)) + 2;
      cv::Rect box = cv::boundingRect(seg.mask);
      box = cv::Rect(box.x - pad, box.y - pad, box.width + 2 * pad, box.height + 2 * pad) & cv::Rect(0, 0, frame.cols, frame.rows);
      cv::Mat grey;
      frame(box).convertTo(grey, CV_32F);
      tips[i].darkening = seg.background(box) - grey;
      tips[i].origin = box.tl();
      tips[i].threshold = seg.threshold;
      tips[i].blur_sigma = o.segmentation.blur_sigma_px;
    }
    r.segmentation_doubt[i] = seg.touches_border || seg.lost;
    seg_lost[i] = seg.lost;
    if (cv::countNonZero(seg.mask) > 0) ctx.previous = seg.mask;
  }
  check_the_fish_is_seen(masks, source);
  cv::Point2d axis;
  r.midlines = extract_midlines(masks, o.stations, &axis, &tips);
  // A frame is measured only when the fish is whole in view and its segmentation not in doubt.
  for (std::size_t i = 0; i < nf; ++i) {
    auto& m = r.midlines[i];
    if (!m.valid || !r.segmentation_doubt[i]) continue;
    m.valid = false;
    m.reason = seg_lost[i] ? "no fish near the previous frame's (segmentation in doubt)"
                           : "the fish touches the image border (not whole in view)";
  }
  r.invalid = count_invalid(r.midlines, r.commonest_reason);
  if (r.invalid > 0)
    log::warn(source + ": " + std::to_string(r.invalid) + " of " + std::to_string(nf) +
              " frames not measured (valid 0); the commonest reason: " + r.commonest_reason);
  if (nf - r.invalid >= kMinBeatFrames) {
    r.beat = tail_beat(r.midlines, axis, o.fps);
  } else {
    constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
    r.beat.frequency_hz = r.beat.amplitude_px = r.beat.wavelength_px = kNaN;
    r.beat.tip_lateral_px.assign(nf, kNaN);
    r.beat.axis = axis;
  }
  return r;
}

void write_single_view_csv(const fs::path& csv, const SingleViewResult& r, const SingleViewOptions& o) {
  std::ostringstream out;
  out.precision(9);
  out << "frame,time_s,valid,tip_x_px,tip_y_px,tip_lateral_px";
  if (o.mm_per_px) out << ",tip_x_mm,tip_y_mm,tip_lateral_mm";
  out << ",segmentation_doubt,reason\n";
  for (std::size_t i = 0; i < r.frames.size(); ++i) {
    const auto& m = r.midlines[i];
    out << r.frames[i] << ',' << r.frames[i] / o.fps << ',' << int(m.valid) << ',' << m.tip.x << ',' << m.tip.y << ','
        << r.beat.tip_lateral_px[i];
    if (o.mm_per_px) out << ',' << m.tip.x * *o.mm_per_px << ',' << m.tip.y * *o.mm_per_px << ',' << r.beat.tip_lateral_px[i] * *o.mm_per_px;
    out << ',' << int(r.segmentation_doubt[i]) << ",\"" << m.reason << "\"\n";
  }
  write_text_atomic(csv, out.str());
}

void write_single_view_h5(const fs::path& h5, const SingleViewResult& r, const SingleViewOptions& o, const nlohmann::json& config,
                          const std::vector<fs::path>& inputs) {
  const std::size_t nf = r.frames.size(), ns = static_cast<std::size_t>(o.stations);
  auto f = h5::File::create(h5);
  write_provenance(f, "finverse/midline", 1, Provenance{"fin-track midline", config, inputs});
  NdArray<double> time({nf}), mid({nf, ns, 2}), tip({nf, 2}), lat({nf});
  NdArray<std::uint8_t> valid({nf}), doubt({nf});
  for (std::size_t i = 0; i < nf; ++i) {
    const auto& m = r.midlines[i];
    time(i) = r.frames[i] / o.fps;
    valid(i) = m.valid, doubt(i) = r.segmentation_doubt[i];
    tip(i, 0) = m.valid ? m.tip.x : NAN, tip(i, 1) = m.valid ? m.tip.y : NAN;
    lat(i) = r.beat.tip_lateral_px[i];
    for (std::size_t s = 0; s < ns; ++s)
      mid(i, s, 0) = m.valid ? m.points[s].x : NAN, mid(i, s, 1) = m.valid ? m.points[s].y : NAN;
  }
  f.write("time", time);
  f.write("valid", valid);
  f.write("segmentation_doubt", doubt);
  std::vector<std::string> reasons;
  for (const auto& m : r.midlines) reasons.push_back(m.reason);
  f.write("invalid_reason", reasons);
  f.write("px/midline", mid);
  f.write("px/tip", tip);
  f.write("px/tip_lateral", lat);
  f.set_attr(".", "tail_beat_frequency_hz", r.beat.frequency_hz);
  f.set_attr(".", "tail_beat_amplitude_px", r.beat.amplitude_px);
  f.set_attr(".", "body_wavelength_px", r.beat.wavelength_px);
  f.set_attr(".", "beats", static_cast<std::int64_t>(r.beat.beats));
  f.set_attr(".", "fps", o.fps);
  f.set_attr(".", "frames_invalid", static_cast<std::int64_t>(r.invalid));
  f.set_attr(".", "flagged", static_cast<std::int64_t>(r.mostly_invalid() ? 1 : 0));
  if (o.mm_per_px) {
    const double k = *o.mm_per_px;
    for (auto& v : mid.data) v *= k;
    for (auto& v : tip.data) v *= k;
    for (auto& v : lat.data) v *= k;
    f.write("mm/midline", mid);
    f.write("mm/tip", tip);
    f.write("mm/tip_lateral", lat);
    f.set_attr(".", "mm_per_px", k);
    f.set_attr(".", "tail_beat_amplitude_mm", r.beat.amplitude_px * k);
    f.set_attr(".", "body_wavelength_mm", r.beat.wavelength_px * k);
  }
  f.commit();
}

void write_overlay_video(const fs::path& avi, const std::vector<long>& frames, const std::function<cv::Mat(long)>& load,
                         const SingleViewResult& r, double fps) {
  const fs::path tmp = temporary_for(avi).replace_extension(".avi");
  cv::VideoWriter out;
  std::vector<cv::Point> track;
  for (std::size_t i = 0; i < frames.size(); ++i) {
    cv::Mat grey = load(frames[i]), img;
    cv::cvtColor(grey, img, cv::COLOR_GRAY2BGR);
    if (!out.isOpened() && !out.open(tmp.string(), cv::VideoWriter::fourcc('M', 'J', 'P', 'G'), fps, img.size(), true))
      throw Error(avi.string() + ": cannot write an MJPG AVI here");
    const auto& m = r.midlines[i];
    if (m.valid) {
      std::vector<cv::Point> line;
      for (const auto& p : m.points)
        if (!std::isnan(p.x)) line.emplace_back(cvRound(p.x), cvRound(p.y));
      cv::polylines(img, line, false, cv::Scalar(0, 200, 0), 1, cv::LINE_AA);
      track.emplace_back(cvRound(m.tip.x), cvRound(m.tip.y));
      cv::circle(img, track.back(), 3, cv::Scalar(0, 0, 255), 1, cv::LINE_AA);
    }
    if (track.size() > 1) cv::polylines(img, track, false, cv::Scalar(255, 128, 0), 1, cv::LINE_AA);
    char label[64];
    std::snprintf(label, sizeof label, "frame %ld", frames[i]);
    cv::putText(img, label, {4, 14}, cv::FONT_HERSHEY_PLAIN, 0.9, cv::Scalar(0, 0, 255));
    if (!m.valid)  // why this frame was not measured, as midline.h5 and the CSV say
      cv::putText(img, "not measured: " + m.reason, {4, 28}, cv::FONT_HERSHEY_PLAIN, 0.9, cv::Scalar(0, 0, 255));
    out.write(img);
  }
  out.release();
  commit_temporary(tmp, avi);
}

}  // namespace finverse::vision
