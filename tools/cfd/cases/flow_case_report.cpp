// Force history and summary of a flow case; see flow_case_report.hpp.
#include "cfd/cases/flow_case_report.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include "core/atomic_file.hpp"
#include "core/error.hpp"

namespace finverse::cfd::cases {

namespace {
const char* const kAxis[] = {"x", "y", "z"};
double coefficient_scale(const FlowCaseSpec& s) {
  return 2 / (s.rho * s.reference_speed * s.reference_speed * s.reference_area);
}

// Time-mean (trapezoidal in time) and amplitude ((max - min) / 2) of each body's coefficients over
// the force evaluations at t >= mean_from, reported as <body>_C<axis>_mean and _amplitude.
template <class Report>
void window_statistics(const FlowCaseSpec& s, const FlowCaseResult& r, Report&& report) {
  const double scale = coefficient_scale(s);
  std::size_t k0 = 0;
  while (k0 < r.time.size() && r.time[k0] < s.mean_from - 1e-12) ++k0;
  if (r.time.size() < k0 + 2)
    throw Error(s.name +
                ": outputs.mean_from: fewer than two force evaluations after t = " + std::to_string(s.mean_from));
  for (std::size_t b = 0; b < s.bodies.size(); ++b)
    for (int c = 0; c < 3; ++c) {
      double integral = 0, lo = scale * r.force[k0][b][c], hi = lo;
      for (std::size_t k = k0 + 1; k < r.time.size(); ++k) {
        const double a = scale * r.force[k - 1][b][c], v = scale * r.force[k][b][c];
        integral += 0.5 * (a + v) * (r.time[k] - r.time[k - 1]);
        lo = std::min(lo, v);
        hi = std::max(hi, v);
      }
      const std::string name = s.bodies[b].name + "_C" + kAxis[c];
      report(name + "_mean", integral / (r.time.back() - r.time[k0]));
      report(name + "_amplitude", 0.5 * (hi - lo));
    }
}

}  // namespace

void write_force_history(const std::filesystem::path& csv, const FlowCaseSpec& s, const FlowCaseResult& r) {
  std::string text = "t";
  for (const CaseBody& b : s.bodies)
    for (const char* q : {"F", "C"})
      for (const char* a : kAxis) text += std::string(",") + b.name + "_" + q + a;
  text += '\n';
  const double scale = coefficient_scale(s);
  char v[32];
  for (std::size_t k = 0; k < r.time.size(); ++k) {
    std::snprintf(v, sizeof v, "%.9g", r.time[k]);
    text += v;
    for (const auto& f : r.force[k]) {
      for (double c : f) std::snprintf(v, sizeof v, ",%.9g", c), text += v;
      for (double c : f) std::snprintf(v, sizeof v, ",%.9g", scale * c), text += v;
    }
    text += '\n';
  }
  write_text_atomic(csv, text);
}

Summary flow_case_summary(const FlowCaseSpec& s, const FlowCaseResult& r) {
  Summary sum("validation", s.name,
              s.description.empty() ? "fin-cfd run: a flow case from a case file" : s.description);
  const double scale = coefficient_scale(s);
  // A coefficient named in outputs.grade is graded against its reference, the others reported.
  std::size_t graded = 0;
  const auto coefficient = [&](const std::string& name, double value) {
    for (const auto& g : s.grades)
      if (g.metric == name) {
        ++graded;
        return sum.relative(name, value, g.reference, g.tolerance, g.source);
      }
    return sum.info(name, value);
  };
  for (std::size_t b = 0; b < s.bodies.size(); ++b) {
    const auto& f = r.force.back()[b];
    const auto& p = r.pressure.back()[b];
    for (int c = 0; c < 3; ++c) {
      coefficient(s.bodies[b].name + "_C" + kAxis[c], scale * f[c]);
      sum.info(s.bodies[b].name + "_C" + kAxis[c] + "_pressure", scale * p[c]);
      sum.info(s.bodies[b].name + "_F" + kAxis[c], f[c], s.dim == 2 ? "N/m" : "N");
    }
  }
  if (s.mean_from >= 0) window_statistics(s, r, coefficient);
  if (graded != s.grades.size())
    throw Error(s.name + ": outputs.grade names a metric that is not a body's coefficient (<body>_Cx, _Cy, _Cz)");
  if (!r.control_volume_force.empty())
    for (int c = 0; c < 3; ++c)
      sum.info(std::string("C") + kAxis[c] + "_control_volume", scale * r.control_volume_force.back()[c]);
  sum.info("steps", static_cast<double>(r.steps));
  sum.info("cells", static_cast<double>(r.cells[0]) * r.cells[1] * r.cells[2]);
  sum.info("ghost_cells", static_cast<double>(r.ghost_cells));
  sum.info("triangles", static_cast<double>(r.triangles));
  sum.info("mean_poisson_iterations", r.mean_poisson_iterations);
  sum.info("mean_momentum_iterations", r.mean_momentum_iterations);
  sum.info("max_divergence_end", r.max_divergence, "1/s");
  sum.info("solver_seconds", r.cpu_seconds, "s");
  nlohmann::json bodies = nlohmann::json::array();
  for (const CaseBody& b : s.bodies)
    bodies.push_back({{"name", b.name}, {"source", b.source}, {"triangles", b.surface.triangles.size()}});
  sum.parameters() = {{"domain", s.domain},
                      {"core", s.core},
                      {"h", s.h},
                      {"stretch_ratio", s.stretch_ratio},
                      {"grid", r.cells},
                      {"nu", s.nu},
                      {"rho", s.rho},
                      {"t_end", s.t_end},
                      {"cfl", s.cfl},
                      {"dt_max", s.dt_max},
                      {"bodies", bodies},
                      {"wall_momentum_balance", s.wall_momentum_balance},
                      {"near_wall_closed_faces", s.near_wall_closed_faces},
                      {"reference_speed", s.reference_speed},
                      {"reference_area", s.reference_area}};
  return sum;
}

}  // namespace finverse::cfd::cases
