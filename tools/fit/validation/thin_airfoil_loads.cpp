// Thin-airfoil plate loads for the fit twins (see thin_airfoil_loads.hpp).
#include "fit/validation/thin_airfoil_loads.hpp"

#include <cmath>
#include <numbers>

#include <Eigen/Geometry>

#include "fit/errors.hpp"

namespace finverse::fit::validation {

namespace {
double eval(const std::function<double(double)>& f, double t) { return f ? f(t) : 0.0; }
}  // namespace

double thin_airfoil_pressure(const ThinAirfoilFlow& flow, const RigidPlateMotion& m, double x, double t) {
  const double c = flow.chord, U = flow.speed, rho = flow.rho, b = 0.5 * c;
  // v(x) = v_a + v_b x; centred: v0 = v_a + v_b c/2, v1 = v_b (and their time derivatives).
  const double va = eval(m.hdot, t) - U * eval(m.theta, t), vb = -eval(m.thetadot, t);
  const double dva = eval(m.hddot, t) - U * eval(m.thetadot, t), dvb = -eval(m.thetaddot, t);
  const double v0 = va + vb * b, v1 = vb, dv0 = dva + dvb * b, dv1 = dvb;
  const double A0 = -v0 / U, A1 = -v1 * c / (2 * U);
  const double cot_half = std::sqrt((c - x) / x), sin_phi = 2 * std::sqrt(x * (c - x)) / c;
  const double xi = x - b;
  const double circulatory = 2 * rho * U * U * (A0 * cot_half + A1 * sin_phi);
  const double added_mass = rho * (2 * dv0 * std::sqrt(x * (c - x)) + dv1 * xi * std::sqrt(b * b - xi * xi));
  return circulatory - added_mass;
}

fem::LoadHistory thin_airfoil_loads(const fem::Model& model, const ThinAirfoilFlow& flow,
                                    const RigidPlateMotion& motion, const std::vector<double>& times,
                                    double ramp) {
  if (!(flow.rho > 0) || !(flow.speed > 0) || !(flow.chord > 0))
    throw InvalidInput("thin-airfoil loads: rho, speed and chord must be > 0");
  // Interior 3-point rule (barycentric 2/3, 1/6, 1/6), weight 1/3 each.
  const double q[3][3] = {{2.0 / 3, 1.0 / 6, 1.0 / 6}, {1.0 / 6, 2.0 / 3, 1.0 / 6}, {1.0 / 6, 1.0 / 6, 2.0 / 3}};
  struct Point { int node[3]; double N[3]; double x, area_weight; };
  std::vector<Point> points;
  const auto& X = model.reference_positions();
  for (const auto& e : model.elements()) {
    const auto nodes = e->nodes();
    if (nodes.size() != 3) continue;
    const fem::Vec3 a = X[nodes[0]], b = X[nodes[1]], c = X[nodes[2]];
    const double area = 0.5 * (b - a).cross(c - a).norm();
    for (const auto& l : q) {
      Point p{};
      for (int k = 0; k < 3; ++k) {
        p.node[k] = nodes[k];
        p.N[k] = l[k];
      }
      p.x = l[0] * a.x() + l[1] * b.x() + l[2] * c.x() - flow.leading_edge_x;
      p.area_weight = area / 3;
      if (!(p.x > 0 && p.x < flow.chord))
        throw InvalidInput("thin-airfoil loads: a shell triangle lies outside the chord (0, " +
                           std::to_string(flow.chord) + ") from the leading edge");
      points.push_back(p);
    }
  }
  if (points.empty()) throw InvalidInput("thin-airfoil loads: the model has no shell triangles");
  std::vector<Eigen::VectorXd> values;
  values.reserve(times.size());
  for (double t : times) {
    Eigen::VectorXd f = Eigen::VectorXd::Zero(6 * model.node_count());
    for (const auto& p : points) {
      const double F = thin_airfoil_pressure(flow, motion, p.x, t) * p.area_weight;
      for (int k = 0; k < 3; ++k) f(6 * p.node[k] + 1) += p.N[k] * F;
    }
    values.push_back(std::move(f));
  }
  return fem::LoadHistory(times, std::move(values), ramp);
}

}  // namespace finverse::fit::validation
