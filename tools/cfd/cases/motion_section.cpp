// Reading a body's motion: section; see motion_section.hpp.
#include "cfd/cases/motion_section.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <map>
#include <numbers>
#include <sstream>

namespace finverse::cfd::cases {

namespace {

constexpr double kDegree = std::numbers::pi / 180;

// Fields of a line split at commas, tabs and spaces.
std::vector<std::string> fields(const std::string& line) {
  std::string s = line;
  std::replace(s.begin(), s.end(), ',', ' ');
  std::replace(s.begin(), s.end(), '\t', ' ');
  std::istringstream in(s);
  std::vector<std::string> out;
  for (std::string f; in >> f;) out.push_back(f);
  return out;
}

struct PoseTable {
  std::vector<std::string> names;  // value columns (after t)
  std::vector<double> time, values;
};

// A pose table: '#' comments, a header line (t, then column names), rows of numbers.
PoseTable read_table(const std::filesystem::path& p) {
  std::ifstream in(p);
  if (!in) throw Error(p.string() + ": cannot read the pose table");
  PoseTable t;
  std::string line;
  bool header = false;
  for (int number = 1; std::getline(in, line); ++number) {
    const auto f = fields(line);
    if (f.empty() || f[0][0] == '#') continue;
    const std::string where = p.string() + ":" + std::to_string(number) + ": ";
    if (!header) {
      if (f[0] != "t" || f.size() < 2) throw Error(where + "expected a header: t, then the column names (x y z angle1 ...)");
      t.names.assign(f.begin() + 1, f.end());
      header = true;
      continue;
    }
    if (f.size() != t.names.size() + 1)
      throw Error(where + "expected " + std::to_string(t.names.size() + 1) + " numbers, as the header names");
    for (std::size_t c = 0; c < f.size(); ++c) {
      std::size_t used = 0;
      double v = 0;
      try {
        v = std::stod(f[c], &used);
      } catch (const std::exception&) {
        used = 0;
      }
      if (used != f[c].size() || !std::isfinite(v)) throw Error(where + "'" + f[c] + "' is not a finite number");
      if (c == 0) {
        if (!t.time.empty() && !(v > t.time.back())) throw Error(where + "the times must increase");
        t.time.push_back(v);
      } else {
        t.values.push_back(v);
      }
    }
  }
  if (t.time.size() < 2) throw Error(p.string() + ": a pose table needs at least two rows");
  return t;
}

MotionChannel channel(const Reader& r, const YAML::Node& n, const std::string& at, double unit) {
  r.only(n, at, {"offset", "rate", "harmonics"});
  MotionChannel c;
  if (n["offset"]) c.offset = unit * r.number(n["offset"], at + ".offset");
  if (n["rate"]) c.rate = unit * r.number(n["rate"], at + ".rate");
  if (const YAML::Node h = n["harmonics"]) {
    if (!h.IsSequence()) r.fail(h, at + ".harmonics", "expected a list of {amplitude, frequency, phase}");
    for (std::size_t k = 0; k < h.size(); ++k) {
      const std::string hk = at + ".harmonics[" + std::to_string(k) + "]";
      r.only(h[k], hk, {"amplitude", "frequency", "phase"});
      if (!h[k]["amplitude"] || !h[k]["frequency"]) r.fail(h[k], hk, "expected amplitude: and frequency:");
      Harmonic m;
      m.amplitude = unit * r.number(h[k]["amplitude"], hk + ".amplitude");
      m.frequency = r.number(h[k]["frequency"], hk + ".frequency");
      if (h[k]["phase"]) m.phase = kDegree * r.number(h[k]["phase"], hk + ".phase");
      if (!(m.frequency >= 0) || !std::isfinite(m.frequency))
        r.fail(h[k]["frequency"], hk + ".frequency", "expected a finite frequency >= 0 [Hz]");
      c.harmonics.push_back(m);
    }
  }
  return c;
}

}  // namespace

PrescribedRigidMotion motion_section(const Reader& r, const YAML::Node& n, const std::string& at, int dim) {
  r.only(n, at, {"pivot", "translation", "rotation", "table", "period"});
  Vec3 pivot{0, 0, 0};
  if (n["pivot"]) {
    if (dim == 2) {
      const auto p = r.numbers<2>(n["pivot"], at + ".pivot");
      pivot = {p[0], p[1], 0};
    } else {
      pivot = r.numbers<3>(n["pivot"], at + ".pivot");
    }
  }
  std::array<MotionChannel, 3> translation{};
  std::vector<PrescribedRigidMotion::Rotation> rotations;
  const char* names[] = {"x", "y", "z"};
  const bool table = static_cast<bool>(n["table"]);
  if (const YAML::Node t = n["translation"]) {
    if (table) r.fail(t, at + ".translation", "give the translation by the table's columns or here, not both");
    r.only(t, at + ".translation", dim == 2 ? std::initializer_list<const char*>{"x", "y"}
                                             : std::initializer_list<const char*>{"x", "y", "z"});
    for (int d = 0; d < dim; ++d)
      if (t[names[d]]) translation[static_cast<std::size_t>(d)] = channel(r, t[names[d]], at + ".translation." + names[d], 1.0);
  }
  if (const YAML::Node rot = n["rotation"]) {
    if (!rot.IsSequence()) r.fail(rot, at + ".rotation", "expected a list of {axis, offset, rate, harmonics}");
    for (std::size_t k = 0; k < rot.size(); ++k) {
      const std::string rk = at + ".rotation[" + std::to_string(k) + "]";
      r.only(rot[k], rk, {"axis", "offset", "rate", "harmonics"});
      PrescribedRigidMotion::Rotation q;
      if (rot[k]["axis"]) {
        q.axis = r.numbers<3>(rot[k]["axis"], rk + ".axis");
        if (dim == 2 && (q.axis[0] != 0 || q.axis[1] != 0)) r.fail(rot[k]["axis"], rk + ".axis", "a plane body rotates about z: [0, 0, 1]");
        if (!(norm(q.axis) > 0)) r.fail(rot[k]["axis"], rk + ".axis", "expected a non-zero vector");
      } else if (dim == 3) {
        r.fail(rot[k], rk, "axis: missing (a 3-D rotation needs its axis)");
      }
      if (table && (rot[k]["offset"] || rot[k]["rate"] || rot[k]["harmonics"]))
        r.fail(rot[k], rk, "with a table, a rotation gives only its axis (the angle is the table's column)");
      YAML::Node angle = YAML::Clone(rot[k]);
      angle.remove("axis");
      q.angle = channel(r, angle, rk, kDegree);
      rotations.push_back(q);
    }
  }
  std::optional<TimeSpline> spline;
  if (table) {
    const auto path = r.path(n["table"], at + ".table");
    PoseTable t = read_table(path);
    std::map<std::string, int> column;
    for (std::size_t c = 0; c < t.names.size(); ++c) column[t.names[c]] = static_cast<int>(c);
    std::vector<bool> used(t.names.size(), false);
    for (int d = 0; d < dim; ++d)
      if (column.count(names[d])) {
        translation[static_cast<std::size_t>(d)].column = column[names[d]];
        used[static_cast<std::size_t>(column[names[d]])] = true;
      }
    for (std::size_t k = 0; k < rotations.size(); ++k) {
      std::string name = "angle" + std::to_string(k + 1);
      if (!column.count(name) && rotations.size() == 1) name = "angle";
      if (!column.count(name))
        throw Error(path.string() + ": no column " + name + " for " + at + ".rotation[" + std::to_string(k) + "]");
      rotations[k].angle.column = column[name];
      used[static_cast<std::size_t>(column[name])] = true;
    }
    for (std::size_t c = 0; c < used.size(); ++c)
      if (!used[c])
        throw Error(path.string() + ": column '" + t.names[c] + "' is not a motion of " + at +
                    " (expected x, y" + (dim == 3 ? ", z" : "") + " or angle1 .. angle" +
                    std::to_string(rotations.size()) + " for the rotations listed)");
    for (std::size_t c = 0; c < t.names.size(); ++c)
      if (t.names[c].rfind("angle", 0) == 0)
        for (std::size_t row = 0; row < t.time.size(); ++row) t.values[row * t.names.size() + c] *= kDegree;
    std::optional<double> period;
    if (n["period"]) {
      period = r.number(n["period"], at + ".period");
      if (!(*period > 0)) r.fail(n["period"], at + ".period", "expected a period > 0 [s]");
    }
    const PeriodicLayout layout = periodic_layout(t.time, period);
    if (period && !layout.wrap) r.fail(n["period"], at + ".period", "the table does not span whole periods: " + layout.note);
    t.time.resize(layout.frames);
    t.values.resize(layout.frames * t.names.size());
    spline.emplace(t.time, t.values, t.names.size(), layout.wrap, path.string());
  } else if (n["period"]) {
    r.fail(n["period"], at + ".period", "a period belongs to a table:");
  }
  return PrescribedRigidMotion(pivot, translation, rotations, std::move(spline), r.file.string() + ": " + at + ".motion");
}

}  // namespace finverse::cfd::cases
