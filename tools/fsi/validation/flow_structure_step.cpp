// The flow + flag coupled step H(x); see flow_structure_step.hpp.
#include "fsi/validation/flow_structure_step.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "core/error.hpp"

namespace finverse::fsi::validation {

namespace {

std::vector<std::array<int, 2>> chain(int n) {
  std::vector<std::array<int, 2>> s;
  for (int k = 0; k + 1 < n; ++k) s.push_back({k, k + 1});
  return s;
}

double cross(const Eigen::Vector2d& a, const Eigen::Vector2d& b) { return a.x() * b.y() - a.y() * b.x(); }

}  // namespace

FlowStructureStep::FlowStructureStep(cfd::FlowSolver& flow, fem::CoupledStructure& structure, const FlagFlowBody& body,
                                     double rho, double dt)
    : flow_(flow),
      structure_(structure),
      body_(body),
      surface_(body.wet_nodes(), chain(body.wet_nodes())),
      rho_(rho),
      dt_(dt) {
  if (static_cast<int>(structure.wet_nodes().size()) != body.wet_nodes() || structure.dim() != 2)
    throw Error("fsi: the structure's wet nodes (" + std::to_string(structure.wet_nodes().size()) + ", dim " +
                std::to_string(structure.dim()) + ") do not match the flow body's " + std::to_string(body.wet_nodes()) +
                " (dim 2)");
  if (!(dt > 0)) throw Error("fsi: the coupling time step must be > 0");
  velocity_start_ = Eigen::Matrix2Xd::Zero(2, body.wet_nodes());
  loads_ = Eigen::Matrix2Xd::Zero(2, body.wet_nodes());
}

InterfaceLayout FlowStructureStep::layout() const { return wet_layout(body_.wet_nodes()); }

void FlowStructureStep::begin_step(const StepInfo& info) {
  start_step(info, flow_.next_dt(), dt_);
  step_mismatch_ = 0;
  kinds_.reset();
}

void FlowStructureStep::save() {
  saved_flow_ = flow_.state();
  structure_.save();
}

void FlowStructureStep::restore() {
  flow_.restore(saved_flow_);
  structure_.restore();
}

Eigen::VectorXd FlowStructureStep::evaluate(const Eigen::VectorXd& x) {
  const Eigen::Index n = body_.wet_nodes();
  const Eigen::Map<const Eigen::Matrix2Xd> X(x.data(), 2, n), V(x.data() + 2 * n, 2, n);
  const Eigen::Matrix2Xd position = body_.wet_reference() + X;
  const Eigen::Matrix2Xd acceleration = (V - velocity_start_) / dt_;
  double t_new = 0;
  try {
    const cfd::PolygonState state = body_.state(position, V, acceleration);
    if (frozen_kinds_ && !kinds_) kinds_ = state;
    flow_.set_body_state(state, frozen_kinds_ ? &*kinds_ : nullptr);
    t_new = flow_.step().time;
  } catch (const std::exception& e) {
    throw Error(where() + ": flow: " + e.what());
  }

  // Flow -> structure: the flag's samples to the wet nodes (conservative, linear on each segment).
  const cfd::EdgeTraction traction = flow_.edge_traction(rho_);
  std::vector<WetSurface2D::Sample> samples;
  Eigen::Vector2d flag_force = Eigen::Vector2d::Zero();
  double flag_moment = 0;
  const Eigen::Vector2d centre = body_.cylinder_centre();
  for (const cfd::EdgeTractionSample& s : traction.samples) {
    const auto segment = body_.flag_segment(s.edge);
    if (!segment) continue;
    const Eigen::Vector2d f(s.force[0], s.force[1]), p(s.point[0], s.point[1]);
    samples.push_back({*segment, s.xi, f});
    flag_force += f;
    flag_moment += cross(p - centre, f);
  }
  loads_ = surface_.nodal_loads(samples);
  const Eigen::Vector2d node_force = loads_.rowwise().sum();
  double node_moment = 0;
  for (Eigen::Index k = 0; k < n; ++k) node_moment += cross(position.col(k) - centre, loads_.col(k));
  const double scale = std::max(flag_force.norm(), 1e-300);
  step_mismatch_ = std::max({step_mismatch_, (node_force - flag_force).norm() / scale,
                             std::abs(node_moment - flag_moment) / (scale * body_.diameter())});

  fem::CoupledStepReport report;
  const Eigen::VectorXd out = advance_structure(structure_, t_new, loads_, body_.wet_reference(), report);
  const Eigen::VectorXd vs = out.tail(2 * n);

  current_.step = info_.step;
  current_.time = t_new;
  current_.force = {traction.force[0], traction.force[1]};
  current_.flag_force = {flag_force.x(), flag_force.y()};
  current_.power = interface_power(loads_, Eigen::Map<const Eigen::Matrix2Xd>(vs.data(), 2, n));
  current_.interface_work = report.interface_work;
  return out;
}

void FlowStructureStep::accept(const Eigen::VectorXd& x_in, const Eigen::VectorXd&) {
  const Eigen::Index n = body_.wet_nodes();
  structure_.accept();
  velocity_start_ = Eigen::Map<const Eigen::Matrix2Xd>(x_in.data() + 2 * n, 2, n);
  current_.transfer_mismatch = step_mismatch_;
  records_.push_back(current_);
}

void FlowStructureStep::resume(const Eigen::VectorXd& x_in) {
  const Eigen::Index n = body_.wet_nodes();
  velocity_start_ = Eigen::Map<const Eigen::Matrix2Xd>(x_in.data() + 2 * n, 2, n);
}

}  // namespace finverse::fsi::validation
