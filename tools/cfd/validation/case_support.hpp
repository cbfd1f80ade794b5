// Pieces every validation case of the flow solver shares (cases.hpp): the reference file, the
// force-history CSV rows, the summary's last step, the log's number format and the grid axes of
// the plate cases.
#pragma once

#include <chrono>
#include <filesystem>
#include <initializer_list>
#include <nlohmann/json.hpp>
#include <string>

#include "cfd/grid/stretched_axis.hpp"
#include "core/summary.hpp"

namespace finverse::cfd::validation {

std::string fmt(const char* format, double value);

// The --reference file of a case (literature numbers, data/reference/*.json); one-line errors.
nlohmann::json read_reference(const std::string& path);

// One CSV row of a force history: the values in %.9g, comma-separated, newline-terminated.
std::string csv_row(std::initializer_list<double> values);

double seconds_since(std::chrono::steady_clock::time_point t0);

// Axis::stretched from lo to hi with the uniform part [ulo, uhi] of width h, its cell count
// rounded up to a multiple of 8 (three multigrid halvings).
Axis multigrid_axis(double lo, double hi, double ulo, double uhi, double h, double ratio);

// The start-up ramp of the plate cases' motion amplitude, r = (1 - cos(pi t / t_ramp)) / 2 up to
// t_ramp and 1 after, with its first two time derivatives: a plate set moving impulsively normal
// to itself has singular edge velocities.
struct Ramp {
  double r = 1, dr = 0, ddr = 0;
};
Ramp cosine_ramp(double t, double t_ramp);

// Writes <dir>/summary.json with the run's timing; 0 when every graded metric passes, else 1.
int finish(Summary& s, const std::filesystem::path& dir, double wall_seconds);

// The run statistics both 3-D body cases (sphere, DFG 3D-1Z) report.
template <class Result>
void solver_statistics_3d(Summary& s, const Result& r) {
  s.info("steps", static_cast<double>(r.steps));
  s.info("cells", static_cast<double>(r.cells[0]) * r.cells[1] * r.cells[2]);
  s.info("ghost_cells", static_cast<double>(r.ghost_cells));
  s.info("surface_samples", static_cast<double>(r.surface_samples));
  s.info("mean_poisson_iterations", r.mean_poisson_iterations);
  s.info("mean_momentum_iterations", r.mean_momentum_iterations);
  s.info("max_divergence_end", r.max_divergence, "1/s");
  s.info("solver_seconds", r.cpu_seconds, "s");
}

}  // namespace finverse::cfd::validation
