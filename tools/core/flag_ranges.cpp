// The numeric flags' ranges (see flag_ranges.hpp).
#include "core/flag_ranges.hpp"

#include <cmath>
#include <cstdlib>
#include <map>

namespace finverse::cli {

namespace {

enum class Rule { positive, non_negative, at_least_one, whole_non_negative, fraction };

// By long name. A "0: default" meaning keeps a flag at >= 0; counts whose 0 would divide or
// allocate nothing are >= 1. Fractions lie in [0, 1].
const std::map<std::string, Rule>& table() {
  static const std::map<std::string, Rule> t = {
      // counts and sizes of grids, images and meshes
      {"rays", Rule::at_least_one},
      {"ray-points", Rule::at_least_one},
      {"segments", Rule::at_least_one},
      {"width", Rule::at_least_one},
      {"height", Rule::at_least_one},
      {"supersample", Rule::at_least_one},
      {"blur-samples", Rule::at_least_one},
      {"nx", Rule::at_least_one},
      {"ny", Rule::at_least_one},
      {"nz", Rule::at_least_one},
      {"elements", Rule::at_least_one},
      {"n-meridian", Rule::at_least_one},
      {"n-circumference", Rule::at_least_one},
      {"frames", Rule::at_least_one},
      {"noise-seeds", Rule::at_least_one},
      {"runs", Rule::at_least_one},
      {"poses", Rule::at_least_one},
      {"min-views", Rule::at_least_one},
      {"substeps", Rule::at_least_one},
      {"frames-per-period", Rule::at_least_one},
      {"steps-per-period", Rule::at_least_one},
      {"instant-count", Rule::at_least_one},
      {"circle-vertices", Rule::at_least_one},
      {"along", Rule::at_least_one},
      {"across", Rule::at_least_one},
      {"stations", Rule::at_least_one},
      // counts where 0 means "the default" or "none"
      {"population", Rule::whole_non_negative},
      {"generations", Rule::whole_non_negative},
      {"polish-evaluations", Rule::whole_non_negative},
      {"lm-evaluations", Rule::whole_non_negative},
      {"max-iterations", Rule::whole_non_negative},
      {"iterations", Rule::whole_non_negative},
      {"first-iterations", Rule::whole_non_negative},
      {"max-effects", Rule::whole_non_negative},
      {"max-rejections", Rule::whole_non_negative},
      {"checkpoint-every", Rule::whole_non_negative},
      {"snapshot-every", Rule::whole_non_negative},
      {"paraview-every", Rule::whole_non_negative},
      {"output-every", Rule::whole_non_negative},
      {"every", Rule::whole_non_negative},
      {"harmonics", Rule::whole_non_negative},
      {"modes", Rule::whole_non_negative},
      {"debris", Rule::whole_non_negative},
      {"surface-subdivisions", Rule::whole_non_negative},
      {"contour-stride", Rule::whole_non_negative},
      {"motion-harmonics", Rule::whole_non_negative},
      {"threads", Rule::whole_non_negative},
      {"structure-max-iterations", Rule::whole_non_negative},
      {"divergence-iterations", Rule::whole_non_negative},
      {"load-steps", Rule::whole_non_negative},
      {"ramp-steps", Rule::whole_non_negative},
      {"compared-frames", Rule::whole_non_negative},
      // physical scales that must be positive
      {"chord", Rule::positive},
      {"height-over-chord", Rule::positive},
      {"max-edge", Rule::positive},
      {"viscosity", Rule::positive},
      {"fps", Rule::positive},
      {"cfl", Rule::positive},
      {"cfl-limit", Rule::positive},
      {"membrane-thickness", Rule::positive},
      {"edge-ray-thickness", Rule::positive},
      {"center-ray-thickness", Rule::positive},
      {"ray-width-ratio", Rule::positive},
      {"tip-thickness-ratio", Rule::positive},
      {"stretch-ratio", Rule::positive},
      {"wall-stretch-ratio", Rule::positive},
      {"youngs-modulus", Rule::positive},
      {"mass-ratio", Rule::positive},
      {"mm-per-px", Rule::positive},
      {"square-mm", Rule::positive},
      {"scale-mm", Rule::positive},
      {"time-step", Rule::positive},
      // physical scales and tolerances where 0 is allowed (a default, or nothing)
      {"periods", Rule::non_negative},
      {"t-end", Rule::non_negative},
      {"reynolds", Rule::non_negative},
      {"re", Rule::non_negative},
      {"cells-per-chord", Rule::non_negative},
      {"cells-per-diameter", Rule::non_negative},
      {"core-cells-per-diameter", Rule::non_negative},
      {"tolerance", Rule::non_negative},
      {"absolute-tolerance", Rule::non_negative},
      {"structure-tolerance", Rule::non_negative},
      {"step-tolerance", Rule::non_negative},
      {"stop-tolerance", Rule::non_negative},
      {"poisson-rtol", Rule::non_negative},
      {"rtol", Rule::non_negative},
      {"atol", Rule::non_negative},
      {"ramp", Rule::non_negative},
      {"ramp-time", Rule::non_negative},
      {"ramp-periods", Rule::non_negative},
      {"stream-ramp-periods", Rule::non_negative},
      {"dt", Rule::non_negative},
      {"period", Rule::non_negative},
      {"frequency", Rule::non_negative},
      {"speed", Rule::non_negative},
      {"rho", Rule::non_negative},
      {"density", Rule::non_negative},
      {"load-density", Rule::non_negative},
      {"noise-sigma", Rule::non_negative},
      {"noise-floor", Rule::non_negative},
      {"exposure", Rule::non_negative},
      {"output-periods", Rule::non_negative},
      {"output-interval", Rule::non_negative},
      {"start-periods", Rule::non_negative},
      {"min-angle", Rule::non_negative},
      {"ibm-thickness", Rule::non_negative},
      {"thickness", Rule::non_negative},
      {"root-band", Rule::non_negative},
      {"marker-spacing", Rule::non_negative},
      {"max-source-distance", Rule::non_negative},
      {"max-fsi-distance", Rule::non_negative},
      {"rayleigh-mass", Rule::non_negative},
      {"rayleigh-stiffness", Rule::non_negative},
      {"relative-step", Rule::non_negative},
      {"temporal-sigma", Rule::non_negative},
      {"neighbour-sigma", Rule::non_negative},
      {"out-of-plane-sigma", Rule::non_negative},
      {"span-curvature-sigma", Rule::non_negative},
      {"keypoint-sigma-3d", Rule::non_negative},
      {"coverage-weight", Rule::non_negative},
      {"coverage-chamfer-weight", Rule::non_negative},
      {"coverage-band", Rule::non_negative},
      {"ray-weight", Rule::non_negative},
      {"keypoint-weight", Rule::non_negative},
      {"max-root-drift", Rule::non_negative},
      {"max-area-ratio", Rule::non_negative},
      {"max-reprojection-px", Rule::non_negative},
      {"outline-tolerance-px", Rule::non_negative},
      {"perturb-calibration-px", Rule::non_negative},
      {"debris-radius", Rule::non_negative},
      {"gain", Rule::non_negative},
      {"field-chords", Rule::non_negative},
      {"body-length", Rule::non_negative},
      {"body-depth", Rule::non_negative},
      {"body-width", Rule::non_negative},
      {"pectoral-length", Rule::non_negative},
      {"pectoral-frequency", Rule::non_negative},
      {"excursion-over-chord", Rule::non_negative},
      {"heave-over-chord", Rule::non_negative},
      {"strouhal", Rule::non_negative},
      {"drag-coefficient", Rule::non_negative},
      {"added-mass-coefficient", Rule::non_negative},
      {"spectral-radius", Rule::non_negative},
      {"rho-inf", Rule::non_negative},
      {"wake", Rule::non_negative},
      {"upstream", Rule::non_negative},
      {"downstream", Rule::non_negative},
      {"outlet-length", Rule::non_negative},
      {"channel-length", Rule::non_negative},
      {"core-margin", Rule::non_negative},
      // fractions
      {"min-iou", Rule::fraction},
      {"target-noise", Rule::fraction},
      {"marker-fraction", Rule::fraction},
      {"board-fraction", Rule::fraction},
      {"keypoint-min-score", Rule::fraction},
      {"vignetting", Rule::fraction},
      {"alpha", Rule::fraction},
      {"pectoral-station", Rule::fraction},
      {"pectoral-level", Rule::fraction},
  };
  return t;
}

const char* words(Rule r) {
  switch (r) {
    case Rule::positive: return "a number > 0";
    case Rule::non_negative: return "a number >= 0";
    case Rule::at_least_one: return "a whole number >= 1";
    case Rule::whole_non_negative: return "a whole number >= 0";
    case Rule::fraction: return "a number from 0 to 1";
  }
  return "";
}

bool holds(Rule r, double x) {
  switch (r) {
    case Rule::positive: return x > 0;
    case Rule::non_negative: return x >= 0;
    case Rule::at_least_one: return x >= 1;
    case Rule::whole_non_negative: return x >= 0;
    case Rule::fraction: return x >= 0 && x <= 1;
  }
  return true;
}

// The value as a number, when the whole string is one (nullopt for words, paths and lists).
std::optional<double> as_number(const std::string& s) {
  if (s.empty()) return std::nullopt;
  char* end = nullptr;
  const double x = std::strtod(s.c_str(), &end);
  if (end == s.c_str() || *end != '\0') return std::nullopt;
  return x;
}

bool is_numeric(const CLI::Option& o) {
  const std::string t = o.get_type_name();
  return t.rfind("FLOAT", 0) == 0 || t.rfind("INT", 0) == 0 || t.rfind("UINT", 0) == 0;
}

void check_app(const CLI::App& app) {
  for (const CLI::Option* o : app.get_options()) {
    if (o->count() == 0 || o->get_lnames().empty()) continue;
    const std::string& name = o->get_lnames().front();
    const auto it = table().find(name);
    for (const std::string& v : o->results()) {
      const auto x = as_number(v);
      if (!x) continue;
      if (!std::isfinite(*x) && (is_numeric(*o) || it != table().end()))
        throw CLI::ValidationError("--" + name, "expected a finite number, got " + v);
      if (it != table().end() && !holds(it->second, *x))
        throw CLI::ValidationError("--" + name, std::string("expected ") + words(it->second) + ", got " + v);
    }
  }
  for (const CLI::App* sub : app.get_subcommands()) check_app(*sub);
}

}  // namespace

std::optional<std::string> flag_range(const std::string& long_name) {
  const auto it = table().find(long_name);
  if (it == table().end()) return std::nullopt;
  return words(it->second);
}

void check_flag_ranges(const CLI::App& app) { check_app(app); }

}  // namespace finverse::cli
