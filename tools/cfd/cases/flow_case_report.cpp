// Force history and summary of a flow case; see flow_case_report.hpp.
#include "cfd/cases/flow_case_report.hpp"

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
                      {"reference_speed", s.reference_speed},
                      {"reference_area", s.reference_area}};
  return sum;
}

}  // namespace finverse::cfd::cases
