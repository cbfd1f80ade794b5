// fin-cfd fin's log lines; see fin_run_log.hpp.
#include "cfd/io/fin_run_log.hpp"

#include <cstdio>
#include <string>

namespace finverse::cfd::io {

namespace {
std::string fmt(const char* f, double v) {
  char b[64];
  std::snprintf(b, sizeof b, f, v);
  return b;
}
}  // namespace

void log_fin_input(const FinInput& in, const std::filesystem::path& mesh, const std::filesystem::path& motion) {
  const auto& body = in.motion->body();
  log::info(mesh.string() + ": " + std::to_string(in.rest.size()) + " nodes, " +
            std::to_string(in.mid_triangles.size()) + " shell triangles; closed thin body " +
            std::to_string(body.source_node.size()) + " vertices, " + std::to_string(body.triangles.size()) +
            " triangles, thickness " + fmt("%.4g m", body.thickness) + " (rest surface reproduced to " +
            fmt("%.1e m", in.rest_mismatch) + ")");
  log::info(motion.string() + ": " + std::to_string(in.frame_time.size()) + " frames, " +
            (in.layout.wrap ? "periodic, spline period " + fmt("%.6g s", *in.layout.wrap)
                            : "not periodic" + (in.layout.note.empty() ? std::string() : " (" + in.layout.note + ")")));
}

void FinProgress::operator()(long n, long total, const StepStats& s) {
  if (!progress_) {
    first_ = n - 1;
    progress_ =
        std::make_unique<log::Progress>(first_ ? "fin-cfd fin steps since the restart at step " + std::to_string(first_)
                                               : std::string("fin-cfd fin step"),
                                        static_cast<std::size_t>(total - first_));
  }
  progress_->update(static_cast<std::size_t>(n - first_),
                    (first_ ? "step " + std::to_string(n) + "/" + std::to_string(total) + "  " : std::string()) + "t " +
                        fmt("%.5f s", s.time) + "  CFL " + fmt("%.3f", s.cfl) + "  Poisson " +
                        std::to_string(s.poisson_iterations) + " it  div " + fmt("%.1e", s.max_divergence));
}

void FinProgress::finish(double t_end) {
  if (progress_) progress_->finish("t " + fmt("%.5f s", t_end));
}

void log_fin_run(const FinInput& in, const FinFlowStats& st, const std::filesystem::path& checkpoint) {
  const double thickness = in.motion->body().thickness;
  if (st.checkpoints > 0)
    log::info("wrote " + std::to_string(st.checkpoints) + " checkpoints to " + checkpoint.string() + " (" +
              fmt("%.2f s", st.checkpoint_seconds) + " in all)");
  const auto& g = st.grid;
  log::info("grid " + std::to_string(g.nx()) + " x " + std::to_string(g.ny()) + " x " + std::to_string(g.nz()) +
            " (h = c/" + fmt("%.3g", st.chord / st.h) + ", body thickness " + fmt("%.2f", thickness / st.h) +
            " h), U " + fmt("%.4g m/s", st.U) + ", nu " + fmt("%.4g m2/s", st.nu) + ", dt " + fmt("%.4g s", st.dt) +
            ", " + std::to_string(st.steps) + " steps, max CFL " + fmt("%.3f", st.max_cfl) +
            ", mean Poisson iterations " +
            fmt("%.2f", st.steps ? static_cast<double>(st.poisson_iterations) / st.steps : 0.0) + ", " +
            fmt("%.1f s", st.wall_seconds));
  if (thickness < 2 * st.h)
    log::warn("the closed thin body is " + fmt("%.2f", thickness / st.h) +
              " cells thick (fewer than 2): raise --cells-per-chord or mesh.h5's ibm_thickness");
}

}  // namespace finverse::cfd::io
