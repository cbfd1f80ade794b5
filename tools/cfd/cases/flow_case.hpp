// A user's own flow, described by data instead of C++ (`fin-cfd run CASE.yaml` with `case: flow`;
// case_file.hpp reads the file): a box domain (a rectangle in 2-D) on a stretched grid around a
// uniform core, the fluid, a boundary condition per side, fixed closed bodies (3-D: a built-in
// sphere or box, or the user's own surface file: STL, OBJ, VTK .vtp, or a mesh.h5's closed thin
// body, surface_file.hpp; 2-D: one polygon, given by its vertices, a two-column file or as a
// circle), the time span, and what to record: the force on each body and its
// coefficients C = F / (1/2 rho U^2 A) from the surface traction (DESIGN.md 5.1), and optionally
// the independent control-volume force. 3-D bodies may instead be zero-thickness sheets (a
// built-in flat plate), forced with regularized kernels. The sphere at Re 100 of the validation set is such a case
// (data/cases/cfd/sphere_re100_stl.yaml gives it as an STL file).
#pragma once

#include <array>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "cfd/flow/flow_solver.hpp"
#include "cfd/flow/velocity_boundary.hpp"
#include "cfd/immersed/prescribed_rigid_motion.hpp"
#include "cfd/immersed/triangulated_surface.hpp"

namespace finverse::cfd::cases {

// A pipe's inflow: the parabola u = speed (1 - r^2 / radius^2) on the disc where a pipe whose fluid
// is inside (CaseBody::encloses_fluid) crosses an inlet side (enclosed_fluid.hpp).
struct PipeInlet {
  std::array<double, 3> centre{};  // on the side's plane [m]
  double radius = 0;               // [m]
  double speed = 0;                // centreline speed into the domain [m/s]
};

struct SideCondition {
  FlowBcType type = FlowBcType::Slip;
  std::array<double, 3> velocity{};  // inlet: the inflow velocity [m/s] (parabolic: at the centre)
  bool parabolic = false;            // inlet: a parabola across the side instead of a uniform stream
  double ramp_time = 0;              // inlet: (1 - cos(pi t / ramp)) / 2 for t < ramp [s]
  std::vector<PipeInlet> pipes;      // inlet: parabolas on pipes' cross-sections (zero elsewhere)
  bool local_convection = false;     // convective outlet: each face's own speed (convection: local)
};

struct CaseBody {
  std::string name;
  // 3-D: closed, oriented towards the fluid (outward, or inward for encloses_fluid), in the
  // domain's coordinates [m]; a sheet: open, any orientation.
  TriangulatedSurface surface;
  // The fluid is inside this closed surface (a pipe, a junction; `fluid: inside`): the solid is
  // everything outside it, and the surface may cross the domain's sides (docs/studies/pipe_flow.md).
  bool encloses_fluid = false;
  // A zero-thickness surface (FlowSolver::immerse_sheet; docs/studies/thin_surface.md) instead of a
  // closed body: every body of a case is a sheet or none is.
  bool sheet = false;
  // 2-D sheets: the mid-line's nodes (z = 0) and segments {a, b, -1}, in `surface`.
  std::vector<std::array<double, 2>> outline;  // 2-D closed body: its outline, a simple polygon [m]
  std::string source;                          // where it came from (file name or built-in shape), for the record
  // A prescribed rigid motion from the placement above (at t = 0 when the motion is zero there);
  // none: fixed.
  std::optional<PrescribedRigidMotion> motion;
};

struct FlowCaseSpec {
  std::string name = "flow";  // results go to <out_dir>/<name>/
  std::string description;
  int dim = 3;                           // 2: a plane flow (no z); forces per unit depth [N/m]
  std::array<double, 6> domain{};        // x0, x1, y0, y1, z0, z1 [m]
  std::array<double, 6> core{};          // the uniform core of cell width h, inside the domain
  double h = 0;                          // core cell width [m]
  double stretch_ratio = 1.1;            // largest neighbouring cell-width ratio outside the core
  double nu = 1e-6, rho = 1000;          // kinematic viscosity [m^2/s], density [kg/m^3]
  std::array<SideCondition, 6> sides{};  // XLo, XHi, YLo, YHi, ZLo, ZHi
  std::array<double, 3> initial_velocity{};
  VelocityFunction initial_field;  // C++ callers: the initial velocity as a field (else initial_velocity)
  std::vector<CaseBody> bodies;
  double t_end = 0;   // simulated time [s]
  double cfl = 0.5;   // target convective CFL number
  double dt_max = 0;  // [s]; 0: cfl h / reference_speed
  double helmholtz_rtol = 1e-8, poisson_rtol = 1e-7;
  bool wall_momentum_balance = false;  // dp/dn from the wall's momentum balance instead of 0
  bool near_wall_closed_faces = false; // FlowOptions::near_wall_closed_faces
  bool cut_cells = true;               // 2-D: the cut-cell mass balance of the fixed body (else staircase)
  int force_every = 10;                // steps between force evaluations (and the last step)
  double reference_speed = 1;          // U of the coefficients [m/s]
  double reference_area = 1;           // A of the coefficients [m^2]; 2-D: a length [m]
  bool control_volume = false;         // also the control-volume force (all bodies together)
  // Moving bodies: the time-mean and amplitude ((max - min) / 2) of every coefficient over the
  // force evaluations at t >= mean_from (a whole number of periods; < 0: not reported).
  double mean_from = -1;
  SheetForcingOptions sheet;           // the sheet bodies' kernel and markers
  // Coefficients graded against a reference (outputs.grade): the summary's metric name (e.g.
  // plate_Cx), the reference value, the relative tolerance and where the value comes from.
  struct Grade {
    std::string metric;
    double reference = 0, tolerance = 0;
    std::string source;
  };
  std::vector<Grade> grades;
  std::array<double, 6> control_volume_box{};
};

struct FlowCaseResult {
  std::vector<double> time;                                  // force evaluations [s]
  std::vector<std::vector<std::array<double, 3>>> force;     // [evaluation][body] traction force [N]
  std::vector<std::vector<std::array<double, 3>>> pressure;  // its pressure part [N]
  std::vector<std::vector<std::array<double, 3>>> viscous;   // its viscous part [N]
  std::vector<std::array<double, 3>> control_volume_force;   // [evaluation] (when asked) [N]
  std::array<int, 3> cells{};
  long steps = 0, ghost_cells = 0, triangles = 0, surface_samples = 0;
  double mean_poisson_iterations = 0, mean_momentum_iterations = 0, max_divergence = 0, cpu_seconds = 0;
};

// The stretched grid of the case: per axis a uniform core of width h, geometric growth outside,
// cell counts rounded to multiples of 8 (three multigrid halvings).
StretchedGrid flow_case_grid(const FlowCaseSpec& spec);

// Every closed body as one surface (disjoint components; the solver immerses one), flagged
// encloses_fluid when one of them does, and the first triangle of each body (and its end).
TriangulatedSurface merged_bodies(const std::vector<CaseBody>& bodies, std::vector<std::size_t>& first_triangle,
                                  std::vector<std::size_t>* first_node = nullptr);

// Runs the case; `progress` is called after every step with the first body's drag coefficient at
// the latest force evaluation; `finished` (3-D closed bodies) with the solver at t_end, to sample
// its fields.
// The case's side conditions (inlets with their profiles and ramps, pipes) and solver options
// (nu, CFL, dt_max, tolerances), as run_flow_case sets up its solver; for runs that drive a
// FlowSolver themselves (fin-fsi flap).
FlowBoundary flow_case_boundary(const FlowCaseSpec& spec);
FlowOptions flow_case_options(const FlowCaseSpec& spec);

FlowCaseResult run_flow_case(const FlowCaseSpec& spec,
                             const std::function<void(const StepStats&, double cx)>& progress = {},
                             const std::function<void(const FlowSolver&)>& finished = {});

}  // namespace finverse::cfd::cases
