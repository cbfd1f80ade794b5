// The 3-D flow + shell coupled step H(x); see surface_flow_structure_step.hpp.
#include "fsi/surface_flow_structure_step.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "cfd/forces/nodal_loads.hpp"
#include "core/error.hpp"
#include "fsi/interface_transfer.hpp"

namespace finverse::fsi {

namespace {

std::vector<cfd::Vec3> columns(const Eigen::Matrix3Xd& m) {
  std::vector<cfd::Vec3> v(static_cast<std::size_t>(m.cols()));
  for (Eigen::Index k = 0; k < m.cols(); ++k) v[static_cast<std::size_t>(k)] = {m(0, k), m(1, k), m(2, k)};
  return v;
}

}  // namespace

double SurfaceLoadTransfer::mismatch(double length) const {
  const double scale = std::max(flow_force.norm(), 1e-300);
  return std::max((node_force - flow_force).norm() / scale, (node_moment - flow_moment).norm() / (scale * length));
}

SurfaceLoadTransfer transfer_surface_loads(const cfd::ThinBody& body, const cfd::SurfaceForces& forces,
                                           const Eigen::Matrix3Xd& nodes, const Eigen::Vector3d& centre) {
  if (nodes.cols() != body.node_count)
    throw Error("fsi: " + std::to_string(nodes.cols()) + " mid-surface positions for a thin body around " +
                std::to_string(body.node_count) + " nodes");
  SurfaceLoadTransfer t;
  const std::vector<cfd::Vec3> f = cfd::nodal_forces(body, forces);
  t.loads.resize(3, body.node_count);
  for (int k = 0; k < body.node_count; ++k) {
    const auto& fk = f[static_cast<std::size_t>(k)];
    t.loads.col(k) = Eigen::Vector3d(fk[0], fk[1], fk[2]);
    t.node_force += t.loads.col(k);
    t.node_moment += (nodes.col(k) - centre).cross(t.loads.col(k));
  }
  // The flow side: each triangle's force at the mean of its vertices' mid-surface nodes.
  for (std::size_t q = 0; q < body.triangles.size(); ++q) {
    Eigen::Vector3d p = Eigen::Vector3d::Zero();
    for (int k = 0; k < 3; ++k)
      p += nodes.col(body.source_node[static_cast<std::size_t>(body.triangles[q][static_cast<std::size_t>(k)])]) / 3.0;
    const Eigen::Vector3d F(forces.pressure[q][0] + forces.viscous[q][0], forces.pressure[q][1] + forces.viscous[q][1],
                            forces.pressure[q][2] + forces.viscous[q][2]);
    t.flow_force += F;
    t.flow_moment += (p - centre).cross(F);
  }
  return t;
}

SurfaceLoadTransfer transfer_sheet_loads(const cfd::FlowSolver& flow, double rho, const Eigen::Matrix3Xd& nodes,
                                         const Eigen::Vector3d& centre) {
  const cfd::SheetMarkers* m = flow.sheet();
  if (!m) throw Error("fsi: the flow has no sheet");
  if (static_cast<std::size_t>(nodes.cols()) != m->topology().nodes)
    throw Error("fsi: " + std::to_string(nodes.cols()) + " mid-surface positions for a sheet of " +
                std::to_string(m->topology().nodes) + " nodes");
  const cfd::SheetLoads L = flow.sheet_loads(rho);
  SurfaceLoadTransfer t;
  t.loads.resize(3, nodes.cols());
  for (Eigen::Index k = 0; k < nodes.cols(); ++k) {
    const auto& fk = L.nodal[static_cast<std::size_t>(k)];
    t.loads.col(k) = Eigen::Vector3d(fk[0], fk[1], fk[2]);
    t.node_force += t.loads.col(k);
    t.node_moment += (nodes.col(k) - centre).cross(t.loads.col(k));
  }
  const std::vector<cfd::Vec3> X = m->positions_at_markers(columns(nodes));
  for (std::size_t q = 0; q < X.size(); ++q) {
    const Eigen::Vector3d F(L.marker[q][0], L.marker[q][1], L.marker[q][2]);
    t.flow_force += F;
    t.flow_moment += (Eigen::Vector3d(X[q][0], X[q][1], X[q][2]) - centre).cross(F);
  }
  return t;
}

SurfaceFlowStructureStep::SurfaceFlowStructureStep(cfd::FlowSolver& flow, fem::CoupledStructure& structure,
                                                   const cfd::ThinBody& body, std::vector<std::array<int, 3>> mid,
                                                   Eigen::Matrix3Xd wet_reference, double rho, double dt,
                                                   Eigen::Vector3d moment_centre, double length)
    : flow_(flow), structure_(structure), body_(body), mid_(std::move(mid)), reference_(std::move(wet_reference)),
      rho_(rho), dt_(dt), length_(length), centre_(moment_centre) {
  const auto n = static_cast<Eigen::Index>(body.node_count);
  if (static_cast<Eigen::Index>(structure.wet_nodes().size()) != n || structure.dim() != 3 || reference_.cols() != n)
    throw Error("fsi: the structure's wet nodes (" + std::to_string(structure.wet_nodes().size()) + ", dim " +
                std::to_string(structure.dim()) + ") and the reference (" + std::to_string(reference_.cols()) +
                " nodes) do not match the thin body around " + std::to_string(n) + " nodes (dim 3)");
  if (!(dt > 0) || !(length > 0)) throw Error("fsi: the coupling time step and the length scale must be > 0");
  velocity_start_ = Eigen::Matrix3Xd::Zero(3, n);
  loads_ = Eigen::Matrix3Xd::Zero(3, n);
}

void SurfaceFlowStructureStep::immerse(const Eigen::Matrix3Xd& x0,
                                       const std::optional<cfd::SheetForcingOptions>& sheet) {
  const Eigen::Matrix3Xd zero = Eigen::Matrix3Xd::Zero(3, x0.cols());
  if (sheet)
    flow_.immerse_sheet(cfd::SheetTopology{3, static_cast<std::size_t>(body_.node_count), mid_}, columns(x0), *sheet);
  else
    flow_.immerse_deforming(body_state(x0, zero, zero));
}

void SurfaceFlowStructureStep::place(const Eigen::Matrix3Xd& x, const Eigen::Matrix3Xd& v, const Eigen::Matrix3Xd& a) {
  if (flow_.sheet())
    flow_.set_sheet_state(cfd::SheetState{columns(x), columns(v)});
  else
    flow_.set_body_state(body_state(x, v, a));
}

SurfaceLoadTransfer SurfaceFlowStructureStep::transfer(const Eigen::Matrix3Xd& x) const {
  return flow_.sheet() ? transfer_sheet_loads(flow_, rho_, x, centre_)
                       : transfer_surface_loads(body_, flow_.surface_forces(rho_), x, centre_);
}

InterfaceLayout SurfaceFlowStructureStep::layout() const {
  const Eigen::Index n = 3 * body_.node_count;
  return {n, n};
}

cfd::SurfaceState SurfaceFlowStructureStep::body_state(const Eigen::Matrix3Xd& x, const Eigen::Matrix3Xd& v,
                                                       const Eigen::Matrix3Xd& a) const {
  return cfd::place_thin_body(body_, columns(x), columns(v), columns(a), mid_);
}

void SurfaceFlowStructureStep::begin_step(const StepInfo& info) {
  info_ = info;
  if (std::abs(info.dt - dt_) > 1e-12 * dt_ || std::abs(flow_.next_dt() - dt_) > 1e-12 * dt_)
    throw Error("fsi: step " + std::to_string(info.step) + " asks for dt = " + std::to_string(info.dt) +
                " but flow and structure run at " + std::to_string(dt_));
  step_mismatch_ = 0;
}

std::string SurfaceFlowStructureStep::where() const {
  return "fsi: step " + std::to_string(info_.step) + " (t = " + std::to_string(info_.time + info_.dt) + ")";
}

void SurfaceFlowStructureStep::save() {
  saved_flow_ = flow_.state();
  structure_.save();
}

void SurfaceFlowStructureStep::restore() {
  flow_.restore(saved_flow_);
  structure_.restore();
}

Eigen::VectorXd SurfaceFlowStructureStep::evaluate(const Eigen::VectorXd& x) {
  const Eigen::Index n = body_.node_count;
  const Eigen::Map<const Eigen::Matrix3Xd> X(x.data(), 3, n), V(x.data() + 3 * n, 3, n);
  const Eigen::Matrix3Xd position = reference_ + X;
  const Eigen::Matrix3Xd acceleration = (V - velocity_start_) / dt_;
  double t_new = 0;
  try {
    place(position, V, acceleration);
    t_new = flow_.step().time;
  } catch (const std::exception& e) {
    throw Error(where() + ": flow: " + e.what());
  }
  const SurfaceLoadTransfer tr = transfer(position);
  loads_ = tr.loads;
  step_mismatch_ = std::max(step_mismatch_, tr.mismatch(length_));

  const Eigen::VectorXd load = Eigen::Map<const Eigen::VectorXd>(loads_.data(), 3 * n);
  fem::CoupledStepReport report;
  try {
    report = structure_.advance(t_new, load);
  } catch (const std::exception& e) {
    throw Error(where() + ": structure: " + e.what());
  }
  Eigen::VectorXd out(6 * n);
  const Eigen::VectorXd xs = structure_.wet_positions(), vs = structure_.wet_velocities();
  out.head(3 * n) = xs - Eigen::Map<const Eigen::VectorXd>(reference_.data(), 3 * n);
  out.tail(3 * n) = vs;

  current_.step = info_.step;
  current_.time = t_new;
  current_.force = tr.flow_force;
  current_.moment = tr.flow_moment;
  current_.power = interface_power(loads_, Eigen::Map<const Eigen::Matrix3Xd>(vs.data(), 3, n));
  current_.interface_work = report.interface_work;
  return out;
}

void SurfaceFlowStructureStep::accept(const Eigen::VectorXd& x_in, const Eigen::VectorXd&) {
  const Eigen::Index n = body_.node_count;
  structure_.accept();
  velocity_start_ = Eigen::Map<const Eigen::Matrix3Xd>(x_in.data() + 3 * n, 3, n);
  current_.transfer_mismatch = step_mismatch_;
  records_.push_back(current_);
}

void SurfaceFlowStructureStep::resume(const Eigen::VectorXd& x_in) {
  const Eigen::Index n = body_.node_count;
  velocity_start_ = Eigen::Map<const Eigen::Matrix3Xd>(x_in.data() + 3 * n, 3, n);
}

}  // namespace finverse::fsi
