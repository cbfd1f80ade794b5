// Quasi-steady strip-theory loads under the analytic root drive (quasi_steady_loads.hpp).
#include "fem/io/quasi_steady_loads.hpp"

#include <cmath>
#include <sstream>

#include <Eigen/Geometry>

#include "core/log.hpp"
#include "core/provenance.hpp"
#include "fem/errors.hpp"
#include "fem/io/root_drive_file.hpp"

namespace finverse::fem::io {

stage::Loads quasi_steady_loads(const stage::Mesh& mesh, const RootDrive& drive, const std::vector<double>& times,
                                const QuasiSteadyLoadOptions& o) {
  const std::size_t nv = mesh.points.shape.empty() ? 0 : mesh.points.dim(0);
  const std::size_t ntri = mesh.triangles.shape.empty() ? 0 : mesh.triangles.dim(0);
  if (ntri == 0) throw InvalidInput("quasi-steady loads: the mesh has no shell triangles to load");
  if (times.empty()) throw InvalidInput("quasi-steady loads: no output times");
  for (double v : {o.density, o.chord, o.scale})
    if (!(std::isfinite(v) && v > 0)) throw InvalidInput("quasi-steady loads: density, chord and scale must be > 0");
  for (double v : {o.speed, o.drag_coefficient, o.added_mass_coefficient})
    if (!(std::isfinite(v) && v >= 0)) throw InvalidInput("quasi-steady loads: speed and coefficients must be >= 0");
  auto X = [&](std::size_t i) { return Vec3(mesh.points(i, 0), mesh.points(i, 1), mesh.points(i, 2)); };
  // Central differences of the rigid motion over a thousandth of a period.
  const double h = 1e-3 / drive.frequency();
  const std::size_t nt = times.size();
  stage::Loads L;
  L.time = NdArray<double>({nt});
  L.nodal_force = NdArray<double>({nt, nv, 3}, 0.0);
  L.pressure_jump = NdArray<double>({nt, ntri}, 0.0);
  L.force_total = NdArray<double>({nt, 3}, 0.0);
  L.thrust = L.lateral = L.vertical = NdArray<double>({nt}, 0.0);
  double area = 0;
  for (std::size_t e = 0; e < ntri; ++e) {
    const Vec3 a = X(static_cast<std::size_t>(mesh.triangles(e, 0))), b = X(static_cast<std::size_t>(mesh.triangles(e, 1))),
               c = X(static_cast<std::size_t>(mesh.triangles(e, 2)));
    area += 0.5 * (b - a).cross(c - a).norm();
  }
  const Vec3 stream(o.speed, 0, 0);
  for (std::size_t k = 0; k < nt; ++k) {
    const double t = times[k];
    L.time(k) = t;
    Vec3 total = Vec3::Zero();
    for (std::size_t e = 0; e < ntri; ++e) {
      std::size_t n[3];
      for (int j = 0; j < 3; ++j) {
        const auto v = mesh.triangles(e, static_cast<std::size_t>(j));
        if (v < 0 || static_cast<std::size_t>(v) >= nv) throw InvalidInput("quasi-steady loads: /triangles names a node outside the mesh");
        n[j] = static_cast<std::size_t>(v);
      }
      Vec3 x[3][3];  // [time -h, 0, +h][corner]
      for (int s = 0; s < 3; ++s)
        for (int j = 0; j < 3; ++j) x[s][j] = drive.rigid_position(X(n[j]), t + (s - 1) * h);
      const Vec3 cross = (x[1][1] - x[1][0]).cross(x[1][2] - x[1][0]);
      const double A = 0.5 * cross.norm();
      if (!(A > 0)) continue;
      const Vec3 normal = cross.normalized();
      const Vec3 centroid_m = (x[0][0] + x[0][1] + x[0][2]) / 3, centroid = (x[1][0] + x[1][1] + x[1][2]) / 3,
                 centroid_p = (x[2][0] + x[2][1] + x[2][2]) / 3;
      const Vec3 v = (centroid_p - centroid_m) / (2 * h), acc = (centroid_p - 2 * centroid + centroid_m) / (h * h);
      const double wn = (v - stream).dot(normal), an = acc.dot(normal);
      const double p = -o.scale * (0.5 * o.density * o.drag_coefficient * std::abs(wn) * wn +
                                   o.added_mass_coefficient * o.density * o.chord * an);
      L.pressure_jump(k, e) = p;
      const Vec3 f = p * A * normal;
      total += f;
      for (int j = 0; j < 3; ++j)
        for (int d = 0; d < 3; ++d) L.nodal_force(k, n[j], static_cast<std::size_t>(d)) += f(d) / 3;
    }
    const double q = 0.5 * o.density * o.speed * o.speed * area;
    for (int d = 0; d < 3; ++d) L.force_total(k, static_cast<std::size_t>(d)) = total(d);
    L.thrust(k) = q > 0 ? -total.x() / q : 0.0;
    L.lateral(k) = q > 0 ? total.y() / q : 0.0;
    L.vertical(k) = q > 0 ? total.z() / q : 0.0;
  }
  L.rho = o.density;
  L.U = o.speed;
  L.reference_area = area;
  L.period = 1 / drive.frequency();
  return L;
}

double write_quasi_steady_loads(const FileLoadsOptions& o, const nlohmann::json& config) {
  const auto mesh = stage::read<stage::Mesh>(o.mesh);
  auto spec = read_root_drive(o.root_drive);
  const double c = mesh.chord.value_or(0.0);
  if (!(c > 0)) throw InvalidInput(o.mesh.string() + ": attribute chord: expected > 0");
  if (!(o.periods > 0) || o.frames_per_period < 2 || !(o.start_periods >= 0))
    throw InvalidInput("fin-fem loads: --periods > 0, --start-periods >= 0 and --frames-per-period >= 2 expected");
  if (!(o.reynolds > 0 && o.viscosity > 0)) throw InvalidInput("fin-fem loads: --reynolds and --viscosity must be > 0");
  QuasiSteadyLoadOptions lo = o.load;
  lo.chord = c;
  lo.speed = o.reynolds * o.viscosity / c;
  const double f = spec.frequency(lo.speed, c), T = 1 / f;
  spec.ramp_periods = 0;  // the steady periodic load; a run ramps it in from rest itself
  const RootDrive drive = make_root_drive(mesh, spec, f, c, o.mesh.string());
  std::vector<double> times;
  const int n = static_cast<int>(std::lround(o.periods * o.frames_per_period));
  for (int k = 0; k <= n; ++k) times.push_back(o.start_periods * T + T * k / o.frames_per_period);
  auto loads = quasi_steady_loads(mesh, drive, times, lo);
  double largest = 0;
  for (std::size_t i = 0; i + 2 < loads.nodal_force.data.size(); i += 3)
    largest = std::max(largest, std::hypot(loads.nodal_force.data[i], loads.nodal_force.data[i + 1],
                                           loads.nodal_force.data[i + 2]));
  double peak_lateral = 0;
  for (std::size_t k = 0; k < times.size(); ++k) peak_lateral = std::max(peak_lateral, std::abs(loads.force_total(k, 1)));
  std::ostringstream m;
  m << "quasi-steady loads: f = " << f << " Hz, U = " << lo.speed << " m/s, " << times.size() << " times from "
    << times.front() << " s; peak lateral force " << peak_lateral << " N, largest nodal force " << largest << " N";
  log::info(m.str());
  stage::write(o.out, loads, Provenance{"fin-fem", config, {o.mesh, o.root_drive}});
  return largest;
}

}  // namespace finverse::fem::io
