// Reading case files; see case_file.hpp for the format.
#include "cfd/cases/case_file.hpp"

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <iomanip>
#include <map>
#include <numbers>
#include <sstream>

#include "cfd/cases/case_reader.hpp"
#include "cfd/cases/enclosed_fluid.hpp"
#include "cfd/cases/motion_section.hpp"
#include "cfd/cases/surface_file.hpp"
#include "cfd/immersed/immersed_polygon.hpp"
#include "cfd/immersed/surface_geometry.hpp"
#include "cfd/immersed/surface_shapes.hpp"
#include "core/error.hpp"
#include "core/machine_memory.hpp"

namespace finverse::cfd::cases {

namespace {

namespace fs = std::filesystem;

// A validation case's options: every scalar leaf as a flag, coarse: applied on request.
void collect_flags(const Reader& r, const YAML::Node& map, const std::string& where,
                   std::map<std::string, std::string>& flags) {
  for (const auto& kv : map) {
    const std::string key = kv.first.as<std::string>();
    const std::string at = where.empty() ? key : where + "." + key;
    if (where.empty() && (key == "case" || key == "description" || key == "coarse")) continue;
    if (kv.second.IsMap()) {
      collect_flags(r, kv.second, at, flags);
      continue;
    }
    std::string flag = "--" + key;
    for (char& c : flag)
      if (c == '_') c = '-';
    // null (in coarse:): back to the case's own default.
    if (kv.second.IsNull()) {
      flags.erase(flag);
      continue;
    }
    if (!kv.second.IsScalar()) r.fail(kv.second, at, "expected a value or a section");
    std::string value = kv.second.Scalar();
    // Input files are found beside the case file; outputs (out, summary, checkpoint) where fin-cfd runs.
    if (key == "reference" || key == "restart" || key == "mesh" || key == "motion")
      value = r.path(kv.second, at).string();
    flags[flag] = value;
  }
}

FlowBcType side_type(const Reader& r, const YAML::Node& n, const std::string& key) {
  static const std::map<std::string, FlowBcType> types = {{"inlet", FlowBcType::Inlet},
                                                          {"convective_outlet", FlowBcType::ConvectiveOutlet},
                                                          {"zero_gradient_outlet", FlowBcType::ZeroGradientOutlet},
                                                          {"slip", FlowBcType::Slip},
                                                          {"no_slip", FlowBcType::NoSlip},
                                                          {"periodic", FlowBcType::Periodic}};
  const std::string t = r.scalar<std::string>(n, key, "a boundary type");
  const auto it = types.find(t);
  if (it == types.end())
    r.fail(n, key, "'" + t + "', expected inlet, convective_outlet, zero_gradient_outlet, slip, no_slip or periodic");
  return it->second;
}

// A flat plate's triangles (the flow case's `shape: plate`): `cells` elements along the chord and
// as many along the span as keep them about square, each split in two.
TriangulatedSurface flat_plate(std::array<double, 3> le, double chord, double span, double incidence_deg, int cells) {
  if (!(chord > 0 && span > 0 && std::isfinite(incidence_deg)))
    throw Error("plate: chord and span must be > 0, incidence finite");
  const double a = incidence_deg * std::numbers::pi / 180;
  const int nz = std::max(1, static_cast<int>(std::lround(cells * span / chord)));
  TriangulatedSurface s;
  for (int k = 0; k <= nz; ++k)
    for (int i = 0; i <= cells; ++i) {
      const double x = chord * i / cells, z = span * (static_cast<double>(k) / nz - 0.5);
      s.points.push_back({le[0] + x * std::cos(a), le[1] - x * std::sin(a), le[2] + z});
    }
  const auto node = [&](int i, int k) { return k * (cells + 1) + i; };
  for (int k = 0; k < nz; ++k)
    for (int i = 0; i < cells; ++i) {
      s.triangles.push_back({node(i, k), node(i + 1, k), node(i + 1, k + 1)});
      s.triangles.push_back({node(i, k), node(i + 1, k + 1), node(i, k + 1)});
    }
  return s;
}

CaseBody body(const Reader& r, const YAML::Node& n, const std::string& at) {
  r.only(n, at,
         {"name", "surface", "shape", "centre", "radius", "subdivisions", "lo", "hi", "scale", "translate",
          "leading_edge", "chord", "span", "incidence", "cells", "motion", "fluid", "from", "to", "segments"});
  CaseBody b;
  b.name = n["name"] ? r.scalar<std::string>(n["name"], at + ".name", "a name") : "body";
  if (n["surface"] && n["shape"]) r.fail(n, at, "give either surface: (a file) or shape:, not both");
  if (n["surface"]) {
    const fs::path p = r.path(n["surface"], at + ".surface");
    b.surface = read_surface_file(p);
    b.source = p.filename().string();
    try {  // closed, consistently oriented: named here rather than when the solver immerses it
      SurfaceGeometry(b.surface, b.source);
    } catch (const Error& e) {
      r.fail(n["surface"], at + ".surface", e.what());
    }
  } else if (n["shape"]) {
    const std::string shape = r.scalar<std::string>(n["shape"], at + ".shape", "sphere, box, cylinder or plate");
    if (shape == "sphere") {
      if (!n["radius"]) r.fail(n, at, "a sphere needs radius:");
      const auto c = n["centre"] ? r.numbers<3>(n["centre"], at + ".centre") : std::array<double, 3>{0, 0, 0};
      const int level = n["subdivisions"] ? r.scalar<int>(n["subdivisions"], at + ".subdivisions", "an integer") : 4;
      b.surface = icosphere(c, r.positive(n["radius"], at + ".radius"), level, true);
      b.source = "icosphere, " + std::to_string(level) + " subdivisions";
    } else if (shape == "cylinder") {
      if (!n["from"] || !n["to"] || !n["radius"]) r.fail(n, at, "a cylinder needs from:, to: and radius:");
      const int segments = n["segments"] ? r.scalar<int>(n["segments"], at + ".segments", "an integer") : 128;
      if (segments < 8 || segments > 4096) r.fail(n["segments"], at + ".segments", "expected 8..4096");
      const auto a = r.numbers<3>(n["from"], at + ".from"), c = r.numbers<3>(n["to"], at + ".to");
      if (a == c) r.fail(n["to"], at + ".to", "the axis has zero length (to: equals from:)");
      b.surface = cylinder_between(a, c, r.positive(n["radius"], at + ".radius"), segments);
      b.source = "cylinder, " + std::to_string(segments) + " segments";
    } else if (shape == "box") {
      if (!n["lo"] || !n["hi"]) r.fail(n, at, "a box needs lo: and hi:");
      b.surface = box_surface(r.numbers<3>(n["lo"], at + ".lo"), r.numbers<3>(n["hi"], at + ".hi"));
      b.source = "box";
    } else if (shape == "plate") {
      // A flat plate as a zero-thickness sheet: chord along x turned nose-up by `incidence`
      // [degrees] about z through the leading edge's midpoint, span along z.
      for (const char* k : {"leading_edge", "chord", "span", "incidence"})
        if (!n[k])
          r.fail(n, at, std::string("a plate needs leading_edge:, chord:, span:, incidence: (missing ") + k + ")");
      const int cells = n["cells"] ? r.scalar<int>(n["cells"], at + ".cells", "an integer") : 16;
      if (cells < 1 || cells > 4096) r.fail(n["cells"], at + ".cells", "expected 1..4096 elements along the chord");
      b.surface =
          flat_plate(r.numbers<3>(n["leading_edge"], at + ".leading_edge"), r.positive(n["chord"], at + ".chord"),
                     r.positive(n["span"], at + ".span"), r.number(n["incidence"], at + ".incidence"), cells);
      b.sheet = true;
      b.source = "flat plate (sheet)";
    } else {
      r.fail(n["shape"], at + ".shape", "'" + shape + "', expected sphere, box, cylinder or plate");
    }
  } else {
    r.fail(n, at, "expected surface: (a .stl, .obj, .vtp or mesh .h5 file) or shape:");
  }
  if (n["scale"] || n["translate"])
    transform(b.surface, n["scale"] ? r.positive(n["scale"], at + ".scale") : 1.0,
              n["translate"] ? r.numbers<3>(n["translate"], at + ".translate") : std::array<double, 3>{0, 0, 0});
  if (n["motion"]) b.motion = motion_section(r, n["motion"], at + ".motion", 3);
  if (n["fluid"]) {
    const std::string f = r.scalar<std::string>(n["fluid"], at + ".fluid", "inside or outside");
    if (f != "inside" && f != "outside") r.fail(n["fluid"], at + ".fluid", "'" + f + "', expected inside or outside");
    b.encloses_fluid = f == "inside";
    if (b.encloses_fluid && b.sheet) r.fail(n["fluid"], at + ".fluid", "a sheet encloses nothing; give a closed surface");
    if (b.encloses_fluid && b.motion)
      r.fail(n["fluid"], at + ".fluid", "a body that encloses the fluid is fixed (leave out motion:)");
    // Outward as read; the walls of the fluid face inwards (triangulated_surface.hpp).
    if (b.encloses_fluid) enclose_fluid(b.surface);
  }
  return b;
}

// `over` merged into a copy of `base`: maps key by key, anything else replaced.
YAML::Node merged(const YAML::Node& base, const YAML::Node& over) {
  if (!base.IsMap() || !over.IsMap()) return YAML::Clone(over);
  YAML::Node out = YAML::Clone(base);
  for (const auto& kv : over) {
    const std::string k = kv.first.as<std::string>();
    out[k] = out[k] ? merged(out[k], kv.second) : YAML::Clone(kv.second);
  }
  return out;
}

// A plane flow's flat plate as a zero-thickness sheet: the mid-line from the leading edge, turned
// nose-up by `incidence` [degrees], in `cells` segments.
void plane_plate(const Reader& r, const YAML::Node& n, const std::string& at, CaseBody& b) {
  for (const char* k : {"leading_edge", "chord", "incidence"})
    if (!n[k]) r.fail(n, at, std::string("a plate needs leading_edge:, chord:, incidence: (missing ") + k + ")");
  const auto le = r.numbers<2>(n["leading_edge"], at + ".leading_edge");
  const double chord = r.positive(n["chord"], at + ".chord");
  const double a = r.number(n["incidence"], at + ".incidence") * std::numbers::pi / 180;
  const int cells = n["cells"] ? r.scalar<int>(n["cells"], at + ".cells", "an integer") : 16;
  if (cells < 1 || cells > 4096) r.fail(n["cells"], at + ".cells", "expected 1..4096 elements along the chord");
  if (!(chord > 0) || !std::isfinite(a)) r.fail(n, at, "a plate needs chord > 0 and a finite incidence");
  for (int k = 0; k <= cells; ++k) {
    const double x = chord * k / cells;
    b.surface.points.push_back({le[0] + x * std::cos(a), le[1] - x * std::sin(a), 0});
    if (k < cells) b.surface.triangles.push_back({k, k + 1, -1});
  }
  b.sheet = true;
  b.source = "flat plate (sheet)";
}

// A plane flow's body: its outline as vertices, a two-column file (x y per line, # comments), or
// a circle (a regular polygon with its vertices on the circle).
CaseBody plane_body(const Reader& r, const YAML::Node& n, const std::string& at) {
  r.only(n, at,
         {"name", "outline", "outline_file", "shape", "centre", "radius", "semi_axes", "angle", "vertices", "scale",
          "translate", "leading_edge", "chord", "incidence", "cells", "motion"});
  CaseBody b;
  b.name = n["name"] ? r.scalar<std::string>(n["name"], at + ".name", "a name") : "body";
  if (n["outline"]) {
    const YAML::Node o = n["outline"];
    if (!o.IsSequence() || o.size() < 3) r.fail(o, at + ".outline", "expected a list of at least 3 [x, y] vertices");
    for (std::size_t i = 0; i < o.size(); ++i) b.outline.push_back(r.numbers<2>(o[i], at + ".outline"));
    b.source = "outline";
  } else if (n["outline_file"]) {
    const fs::path p = r.path(n["outline_file"], at + ".outline_file");
    std::ifstream in(p);
    if (!in) r.fail(n["outline_file"], at + ".outline_file", "cannot read " + p.string());
    std::string line;
    for (int number = 1; std::getline(in, line); ++number) {
      if (line.find_first_not_of(" \t\r") == std::string::npos || line[line.find_first_not_of(" \t")] == '#') continue;
      std::istringstream row(line);
      double x = 0, y = 0;
      if (!(row >> x >> y)) throw Error(p.string() + ":" + std::to_string(number) + ": expected two numbers, x y");
      b.outline.push_back({x, y});
    }
    if (b.outline.size() < 3) throw Error(p.string() + ": an outline needs at least 3 vertices");
    b.source = p.filename().string();
  } else if (n["shape"]) {
    const std::string shape = r.scalar<std::string>(n["shape"], at + ".shape", "circle, ellipse or plate");
    if (shape == "plate") {
      plane_plate(r, n, at, b);
    } else if (shape == "circle" || shape == "ellipse") {
      const bool circle = shape == "circle";
      if (!n["centre"] || !n[circle ? "radius" : "semi_axes"])
        r.fail(n, at, circle ? "a circle needs centre: and radius:" : "an ellipse needs centre: and semi_axes:");
      const auto c = r.numbers<2>(n["centre"], at + ".centre");
      const auto ab = circle ? std::array<double, 2>{r.number(n["radius"], at + ".radius"), 0.0}
                             : r.numbers<2>(n["semi_axes"], at + ".semi_axes");
      const int vertices = n["vertices"] ? r.scalar<int>(n["vertices"], at + ".vertices", "an integer") : 256;
      if (vertices < 8 || vertices > 100000) r.fail(n["vertices"], at + ".vertices", "expected 8..100000 vertices");
      if (!(ab[0] > 0) || !(circle || ab[1] > 0)) r.fail(n, at, "expected a radius or semi-axes > 0");
      const double a = ab[0], e = circle ? ab[0] : ab[1];
      const double tilt = n["angle"] ? r.number(n["angle"], at + ".angle") * std::numbers::pi / 180 : 0.0;
      for (int k = 0; k < vertices; ++k) {
        const double s = 2 * std::numbers::pi * k / vertices, x = a * std::cos(s), y = e * std::sin(s);
        b.outline.push_back(
            {c[0] + x * std::cos(tilt) - y * std::sin(tilt), c[1] + x * std::sin(tilt) + y * std::cos(tilt)});
      }
      b.source = shape + ", " + std::to_string(vertices) + " vertices";
    } else {
      r.fail(n["shape"], at + ".shape", "'" + shape + "', expected circle, ellipse or plate (a plane flow)");
    }
  } else {
    r.fail(n, at, "a plane flow's body needs outline:, outline_file: or shape: circle, ellipse or plate");
  }
  const double scale = n["scale"] ? r.positive(n["scale"], at + ".scale") : 1.0;
  const auto shift = n["translate"] ? r.numbers<2>(n["translate"], at + ".translate") : std::array<double, 2>{0, 0};
  for (auto& v : b.outline) v = {scale * v[0] + shift[0], scale * v[1] + shift[1]};
  for (auto& v : b.surface.points) v = {scale * v[0] + shift[0], scale * v[1] + shift[1], 0};
  if (n["motion"]) b.motion = motion_section(r, n["motion"], at + ".motion", 2);
  return b;
}

// The domain box, the uniform core and its cell width h, checked against the machine's memory
// before any grid is built.
void domain_and_grid(const Reader& r, const YAML::Node& d, const YAML::Node& g, FlowCaseSpec& s) {
  r.only(d, "domain", {"x", "y", "z"});
  r.only(g, "grid", {"h", "core", "stretch_ratio"});
  if (!g["core"]) r.fail(g, "grid.core", "missing");
  r.only(g["core"], "grid.core", {"x", "y", "z"});
  const char* axes[] = {"x", "y", "z"};
  // No z in the domain: a plane flow.
  s.dim = d["z"] ? 3 : 2;
  for (int a = 0; a < s.dim; ++a) {
    if (!d[axes[a]]) r.fail(d, std::string("domain.") + axes[a], "missing");
    if (!g["core"][axes[a]]) r.fail(g["core"], std::string("grid.core.") + axes[a], "missing");
    const auto dx = r.numbers<2>(d[axes[a]], std::string("domain.") + axes[a]);
    if (!(dx[0] < dx[1])) r.fail(d[axes[a]], std::string("domain.") + axes[a], "expected [low, high] with low < high");
    const auto cx = r.numbers<2>(g["core"][axes[a]], std::string("grid.core.") + axes[a]);
    if (!(dx[0] <= cx[0] && cx[0] < cx[1] && cx[1] <= dx[1]))
      r.fail(g["core"][axes[a]], std::string("grid.core.") + axes[a], "expected a core inside the domain");
    s.domain[2 * a] = dx[0];
    s.domain[2 * a + 1] = dx[1];
    s.core[2 * a] = cx[0];
    s.core[2 * a + 1] = cx[1];
  }
  if (!g["h"]) r.fail(g, "grid.h", "missing");
  s.h = r.positive(g["h"], "grid.h");
  if (g["stretch_ratio"]) {
    s.stretch_ratio = r.number(g["stretch_ratio"], "grid.stretch_ratio");
    if (!(s.stretch_ratio >= 1)) r.fail(g["stretch_ratio"], "grid.stretch_ratio", "expected a ratio >= 1");
  }
  {
    // The uniform core's cells at h, before any grid is built: about 400 bytes a cell in 3-D
    // (velocity, history, pressure, multigrid), half that in a plane.
    double cells = 1;
    for (int a = 0; a < s.dim; ++a) cells *= (s.core[2 * a + 1] - s.core[2 * a]) / s.h;
    std::ostringstream what;
    what << r.file.string() << ": grid.h " << s.h << ": at least " << std::setprecision(3) << cells << " cells";
    require_memory((s.dim == 3 ? 400.0 : 200.0) * cells, what.str());
  }
}

FlowCaseSpec flow_case(const Reader& r, YAML::Node root, bool coarse) {
  // The coarse (CI) variant: its coarse: section is merged over the file.
  if (root["coarse"]) {
    if (!root["coarse"].IsMap()) r.fail(root["coarse"], "coarse", "expected a section of keys");
    if (coarse) {
      const YAML::Node c = root["coarse"];
      root = merged(root, c);
    }
  }
  r.only(root, "",
         {"case", "name", "description", "domain", "grid", "fluid", "boundaries", "initial", "bodies", "time", "solver",
          "outputs", "coarse"});
  FlowCaseSpec s;
  const auto need = [&](const char* key) -> YAML::Node {
    if (!root[key]) r.fail(root, key, "missing");
    return root[key];
  };
  s.name = root["name"] ? r.scalar<std::string>(root["name"], "name", "a name") : r.file.stem().string();
  if (root["description"]) s.description = r.scalar<std::string>(root["description"], "description", "text");
  domain_and_grid(r, need("domain"), need("grid"), s);
  const YAML::Node f = need("fluid");
  r.only(f, "fluid", {"nu", "rho"});
  if (!f["nu"]) r.fail(f, "fluid.nu", "missing");
  s.nu = r.positive(f["nu"], "fluid.nu");
  if (f["rho"]) s.rho = r.positive(f["rho"], "fluid.rho");
  const YAML::Node b = need("boundaries");
  r.only(b, "boundaries", {"x_lo", "x_hi", "y_lo", "y_hi", "z_lo", "z_hi"});
  const char* sides[] = {"x_lo", "x_hi", "y_lo", "y_hi", "z_lo", "z_hi"};
  for (int k = 0; k < 6; ++k) {
    const std::string at = std::string("boundaries.") + sides[k];
    if (k >= 2 * s.dim) {
      if (b[sides[k]]) r.fail(b[sides[k]], at, "a plane flow (no domain.z) has no z sides");
      continue;
    }
    if (!b[sides[k]]) r.fail(b, at, "missing");
    const YAML::Node side = b[sides[k]];
    r.only(side, at, {"type", "velocity", "profile", "ramp_time", "pipes", "convection"});
    if (!side["type"]) r.fail(side, at + ".type", "missing");
    s.sides[k].type = side_type(r, side["type"], at + ".type");
    if (side["pipes"]) {
      if (s.sides[k].type != FlowBcType::Inlet) r.fail(side["pipes"], at + ".pipes", "only an inlet side has pipes");
      if (side["velocity"] || side["profile"])
        r.fail(side["pipes"], at + ".pipes", "give either velocity: (and profile:) or pipes:, not both");
      if (s.dim != 3) r.fail(side["pipes"], at + ".pipes", "pipes need a 3-D flow");
      s.sides[k].pipes = read_pipe_inlets(r, side["pipes"], at + ".pipes", s, k);
    }
    if (side["velocity"]) s.sides[k].velocity = r.numbers<3>(side["velocity"], at + ".velocity");
    if (side["profile"]) {
      const std::string p = r.scalar<std::string>(side["profile"], at + ".profile", "uniform or parabolic");
      if (p != "uniform" && p != "parabolic")
        r.fail(side["profile"], at + ".profile", "'" + p + "', expected uniform or parabolic");
      s.sides[k].parabolic = p == "parabolic";
    }
    if (side["ramp_time"]) s.sides[k].ramp_time = r.non_negative(side["ramp_time"], at + ".ramp_time");
    if (side["convection"]) {
      const std::string c = r.scalar<std::string>(side["convection"], at + ".convection", "mean or local");
      if (c != "mean" && c != "local") r.fail(side["convection"], at + ".convection", "'" + c + "', expected mean or local");
      if (s.sides[k].type != FlowBcType::ConvectiveOutlet)
        r.fail(side["convection"], at + ".convection", "only a convective_outlet side has a convection speed");
      s.sides[k].local_convection = c == "local";
    }
  }
  if (root["initial"]) {
    r.only(root["initial"], "initial", {"velocity"});
    s.initial_velocity = r.numbers<3>(root["initial"]["velocity"], "initial.velocity");
  }
  const YAML::Node bodies = need("bodies");
  if (!bodies.IsSequence() || bodies.size() == 0) r.fail(bodies, "bodies", "expected a list of bodies");
  for (std::size_t i = 0; i < bodies.size(); ++i)
    s.bodies.push_back(s.dim == 3 ? body(r, bodies[i], "bodies[" + std::to_string(i) + "]")
                                  : plane_body(r, bodies[i], "bodies[" + std::to_string(i) + "]"));
  check_enclosed_fluid(r, root, s);
  const YAML::Node t = need("time");
  r.only(t, "time", {"t_end", "cfl", "dt_max"});
  if (!t["t_end"]) r.fail(t, "time.t_end", "missing");
  s.t_end = r.positive(t["t_end"], "time.t_end");
  if (t["cfl"]) s.cfl = r.positive(t["cfl"], "time.cfl");
  if (t["dt_max"]) s.dt_max = r.non_negative(t["dt_max"], "time.dt_max");
  if (const YAML::Node sv = root["solver"]) {
    r.only(sv, "solver",
           {"helmholtz_rtol", "poisson_rtol", "wall_momentum_balance", "cut_cells", "kernel", "marker_spacing",
            "band_correction", "near_wall_closed_faces"});
    if (sv["kernel"]) {
      const std::string k = r.scalar<std::string>(sv["kernel"], "solver.kernel", "roma3, peskin4, smooth3 or smooth4");
      try {
        s.sheet.kernel = delta_kernel_from_name(k);
      } catch (const Error&) {
        r.fail(sv["kernel"], "solver.kernel", "'" + k + "', expected roma3, peskin4, smooth3 or smooth4");
      }
    }
    if (sv["marker_spacing"]) s.sheet.spacing = r.positive(sv["marker_spacing"], "solver.marker_spacing");
    if (sv["band_correction"])
      s.sheet.band_correction = r.scalar<bool>(sv["band_correction"], "solver.band_correction", "true or false");
    if (sv["cut_cells"]) s.cut_cells = r.scalar<bool>(sv["cut_cells"], "solver.cut_cells", "true or false");
    if (sv["helmholtz_rtol"]) s.helmholtz_rtol = r.positive(sv["helmholtz_rtol"], "solver.helmholtz_rtol");
    if (sv["poisson_rtol"]) s.poisson_rtol = r.positive(sv["poisson_rtol"], "solver.poisson_rtol");
    if (sv["near_wall_closed_faces"])
      s.near_wall_closed_faces =
          r.scalar<bool>(sv["near_wall_closed_faces"], "solver.near_wall_closed_faces", "true or false");
    if (sv["wall_momentum_balance"])
      s.wall_momentum_balance =
          r.scalar<bool>(sv["wall_momentum_balance"], "solver.wall_momentum_balance", "true or false");
  }
  if (const YAML::Node o = root["outputs"]) {
    r.only(o, "outputs", {"force_every", "reference_speed", "reference_area", "control_volume", "grade", "mean_from"});
    if (o["mean_from"]) {
      s.mean_from = r.number(o["mean_from"], "outputs.mean_from");
      if (!(s.mean_from >= 0)) r.fail(o["mean_from"], "outputs.mean_from", "expected a time >= 0 [s]");
    }
    if (const YAML::Node g = o["grade"]) {
      if (!g.IsSequence()) r.fail(g, "outputs.grade", "expected a list of {metric, reference, tolerance, source}");
      for (std::size_t i = 0; i < g.size(); ++i) {
        const std::string at = "outputs.grade[" + std::to_string(i) + "]";
        r.only(g[i], at, {"metric", "reference", "tolerance", "source"});
        for (const char* k : {"metric", "reference", "tolerance"})
          if (!g[i][k]) r.fail(g[i], at, std::string("missing ") + k);
        FlowCaseSpec::Grade gr;
        gr.metric = r.scalar<std::string>(g[i]["metric"], at + ".metric", "a metric name, e.g. plate_Cx");
        gr.reference = r.number(g[i]["reference"], at + ".reference");
        gr.tolerance = r.number(g[i]["tolerance"], at + ".tolerance");
        if (!(gr.tolerance > 0)) r.fail(g[i]["tolerance"], at + ".tolerance", "expected a relative tolerance > 0");
        if (g[i]["source"]) gr.source = r.scalar<std::string>(g[i]["source"], at + ".source", "text");
        s.grades.push_back(gr);
      }
    }
    if (o["force_every"]) {
      s.force_every = r.scalar<int>(o["force_every"], "outputs.force_every", "an integer");
      if (s.force_every < 1)
        r.fail(o["force_every"], "outputs.force_every", std::to_string(s.force_every) + ", expected >= 1");
    }
    if (o["reference_speed"]) s.reference_speed = r.number(o["reference_speed"], "outputs.reference_speed");
    if (o["reference_area"]) s.reference_area = r.number(o["reference_area"], "outputs.reference_area");
    if (const YAML::Node cv = o["control_volume"]) {
      r.only(cv, "outputs.control_volume", {"x", "y", "z"});
      const char* axes[] = {"x", "y", "z"};
      for (int a = 0; a < s.dim; ++a) {
        const auto box = r.numbers<2>(cv[axes[a]], std::string("outputs.control_volume.") + axes[a]);
        s.control_volume_box[2 * a] = box[0];
        s.control_volume_box[2 * a + 1] = box[1];
      }
      s.control_volume = true;
    }
  }
  if (s.mean_from >= s.t_end)
    r.fail(root["outputs"]["mean_from"], "outputs.mean_from", "expected a time before time.t_end");
  return s;
}

}  // namespace

CaseFile read_case_file(const std::filesystem::path& file, bool coarse) {
  const Reader r{file};
  YAML::Node root;
  try {
    root = YAML::LoadFile(file.string());
  } catch (const YAML::BadFile&) {
    throw Error(file.string() + ": cannot read the case file");
  } catch (const YAML::Exception& e) {
    throw Error(file.string() + ":" + std::to_string(e.mark.line + 1) + ": not valid YAML: " + e.msg);
  }
  if (!root.IsMap()) throw Error(file.string() + ": expected a YAML map with a 'case' key");
  if (!root["case"]) throw Error(file.string() + ": case: missing (a validation case's name, or flow)");
  CaseFile c;
  c.kind = r.scalar<std::string>(root["case"], "case", "a case name");
  if (c.kind == "flow") {
    c.flow = flow_case(r, root, coarse);
    return c;
  }
  std::map<std::string, std::string> flags;
  collect_flags(r, root, "", flags);
  if (coarse && root["coarse"]) {
    if (!root["coarse"].IsMap()) r.fail(root["coarse"], "coarse", "expected a section of keys");
    collect_flags(r, root["coarse"], "coarse", flags);
  }
  for (const auto& [flag, value] : flags) {
    if (value == "false") continue;
    c.arguments.push_back(flag);
    if (value != "true") c.arguments.push_back(value);
  }
  return c;
}

}  // namespace finverse::cfd::cases
