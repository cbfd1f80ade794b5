// Flows inside walls (issue 49; cases/enclosed_fluid.hpp): a surface that encloses the fluid
// classifies every cell outside it as solid, also beyond its bounding box; a case file's pipe,
// inlet discs and floating bodies are read and checked, each bad geometry a one-line error naming
// the file and the key; a short pipe run keeps the parabola and conserves mass; and a zero-thickness
// sheet held in the pipe takes the drag that the pressure drop says.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <numbers>
#include <regex>
#include <string>

#include "../scratch_dir.hpp"
#include "cfd/cases/case_file.hpp"
#include "cfd/cases/flow_case.hpp"
#include "cfd/flow/flow_solver.hpp"
#include "cfd/immersed/ghost_cells.hpp"
#include "cfd/immersed/surface_geometry.hpp"
#include "cfd/immersed/surface_shapes.hpp"
#include "cfd/validation/pipe_poiseuille.hpp"
#include "core/error.hpp"

namespace finverse::cfd {
namespace {

TriangulatedSurface pipe_wall(double radius, double z0, double z1) {
  TriangulatedSurface s = cylinder_between({0, 0, z0}, {0, 0, z1}, radius, 64);
  enclose_fluid(s);
  return s;
}

TEST(EnclosedFluid, TheWallMustFaceTheFluidInside) {
  TriangulatedSurface outward = cylinder_between({0, 0, 0}, {0, 0, 1}, 0.2, 32);
  outward.encloses_fluid = true;
  EXPECT_THROW(SurfaceGeometry(outward, "pipe"), Error);
  TriangulatedSurface inward = pipe_wall(0.2, 0, 1);
  inward.encloses_fluid = false;
  EXPECT_THROW(SurfaceGeometry(inward, "pipe"), Error);
  const SurfaceGeometry wall(pipe_wall(0.2, 0, 1), "pipe");
  EXPECT_TRUE(wall.encloses_fluid());
  EXPECT_LT(wall.volume(), 0);
  EXPECT_FALSE(wall.inside({0, 0, 0.5}));  // "inside" is the solid: the axis is fluid
  EXPECT_TRUE(wall.inside({0.3, 0, 0.5}));
  EXPECT_TRUE(wall.inside({50, -40, 30}));  // far away: solid
}

TEST(EnclosedFluid, EveryCellOutsideThePipeIsSolidAlsoBeyondItsBoundingBox) {
  const double h = 0.1, R = 0.5;
  const StretchedGrid grid(Axis::uniform(-0.8, 0.8, 16), Axis::uniform(-0.8, 0.8, 16), Axis::uniform(0, 1.6, 16));
  const SurfaceGeometry wall(pipe_wall(R, -0.3, 1.9), "pipe");
  const GhostCellSet cells(grid, wall);
  for (int k = 0; k < 16; ++k)
    for (int j = 0; j < 16; ++j)
      for (int i = 0; i < 16; ++i) {
        const double r = std::hypot(grid.xc(i), grid.yc(j));
        const CellKind kind = cells.kind(i, j, k);
        if (r < R - h) {
          EXPECT_EQ(kind, CellKind::Fluid) << i << " " << j << " " << k;
        } else if (r > R + 2 * h) {
          EXPECT_EQ(kind, CellKind::Solid) << i << " " << j << " " << k;
        } else if (r > R + h) {
          EXPECT_NE(kind, CellKind::Fluid) << i << " " << j << " " << k;
        }
      }
  ASSERT_FALSE(cells.ghosts().empty());
  for (const GhostCell& g : cells.ghosts()) {
    // The image point lies in the fluid, inside the pipe.
    EXPECT_LT(std::hypot(g.image_point[0], g.image_point[1]), R);
    EXPECT_GT(std::hypot(grid.xc(g.i), grid.yc(g.j)), R - 1e-12);
  }
}

// A pipe of the flap's inlet with a ball in it; the tests edit one line each.
const std::string kPipeCase = R"(case: flow
domain: {x: [-0.016, 0.016], y: [-0.016, 0.016], z: [0, 0.032]}
grid: {h: 0.002, core: {x: [-0.016, 0.016], y: [-0.016, 0.016], z: [0, 0.032]}}
fluid: {nu: 1.0745e-5, rho: 1163.3}
boundaries:
  x_lo: {type: no_slip}
  x_hi: {type: no_slip}
  y_lo: {type: no_slip}
  y_hi: {type: no_slip}
  z_lo: {type: inlet, ramp_time: 0.5, pipes: [{centre: [0, 0, 0], radius: 0.01095, velocity: 0.63}]}
  z_hi: {type: convective_outlet}
bodies:
  - {name: pipe, shape: cylinder, from: [0, 0, -0.004], to: [0, 0, 0.036], radius: 0.01095, segments: 64, fluid: inside}
  - {name: ball, shape: sphere, centre: [0, 0, 0.016], radius: 0.004, subdivisions: 2}
time: {t_end: 0.1}
)";

std::string pipe_case_error(const std::string& pattern, const std::string& replacement) {
  const std::string text = std::regex_replace(kPipeCase, std::regex(pattern), replacement,
                                              std::regex_constants::format_first_only);
  EXPECT_NE(text, kPipeCase) << pattern;
  finverse::test::ScratchDir dir;
  std::ofstream(dir / "pipe.yaml") << text;
  try {
    cases::read_case_file(dir / "pipe.yaml", false);
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

TEST(EnclosedFluid, ACaseFileReadsThePipeItsInletDiscAndTheBallInside) {
  finverse::test::ScratchDir dir;
  std::ofstream(dir / "pipe.yaml") << kPipeCase;
  const cases::CaseFile c = cases::read_case_file(dir / "pipe.yaml", false);
  ASSERT_EQ(c.flow.bodies.size(), 2u);
  EXPECT_TRUE(c.flow.bodies[0].encloses_fluid);
  EXPECT_FALSE(c.flow.bodies[1].encloses_fluid);
  EXPECT_LT(SurfaceGeometry(c.flow.bodies[0].surface, "pipe").volume(), 0);
  ASSERT_EQ(c.flow.sides[4].pipes.size(), 1u);
  EXPECT_DOUBLE_EQ(c.flow.sides[4].pipes[0].radius, 0.01095);
  EXPECT_DOUBLE_EQ(c.flow.sides[4].pipes[0].speed, 0.63);
}

TEST(EnclosedFluid, BadGeometryIsAOneLineErrorNamingTheFileAndTheKey) {
  const auto has = [](const std::string& e, std::initializer_list<const char*> parts) {
    EXPECT_NE(e.find("pipe.yaml:"), std::string::npos) << e;
    EXPECT_EQ(e.find('\n'), std::string::npos) << e;
    for (const char* p : parts) EXPECT_NE(e.find(p), std::string::npos) << e << " lacks " << p;
  };
  has(pipe_case_error(R"(centre: \[0, 0, 0\], radius)", "centre: [0.003, 0, 0], radius"),
      {"boundaries.z_lo.pipes[0]", "does not meet a pipe's cross-section"});
  has(pipe_case_error("radius: 0.01095, velocity", "radius: 0.008, velocity"),
      {"boundaries.z_lo.pipes[0]", "does not fill the pipe's cross-section"});
  has(pipe_case_error(R"(centre: \[0, 0, 0\], radius)", "centre: [0, 0, 0.001], radius"),
      {"boundaries.z_lo.pipes[0].centre", "not on the side's plane"});
  has(pipe_case_error("radius: 0.004", "radius: 0.012"), {"bodies[1]", "sticks through a wall"});
  has(pipe_case_error("z_hi: \\{type: convective_outlet\\}", "z_hi: {type: convective_outlet, pipes: []}"),
      {"boundaries.z_hi.pipes", "only an inlet side"});
  has(pipe_case_error(", fluid: inside", ""), {"boundaries.z_lo.pipes", "no body encloses the fluid"});
  has(pipe_case_error("fluid: inside", "fluid: inside, motion: {translation: {x: {rate: 1}}}"),
      {"bodies[0].fluid", "fixed"});
  has(pipe_case_error("fluid: inside", "fluid: indoors"), {"bodies[0].fluid", "expected inside or outside"});
}

TEST(EnclosedFluid, AShortPipeRunKeepsTheParabolaAndConservesMass) {
  validation::PipePoiseuilleSetup p;
  p.cells_per_diameter = 8;
  p.length_diameters = 4;
  p.t_end = 0.04;
  const validation::PipePoiseuilleResult r = validation::run_pipe_poiseuille(p);
  EXPECT_GT(r.steps, 10);
  EXPECT_LT(r.max_divergence, 1e-8);
  EXPECT_NEAR(r.centreline_speed / r.centreline_reference, 1, 0.03);
  EXPECT_NEAR(r.pressure_gradient / r.pressure_gradient_reference, 1, 0.25);
  EXPECT_NEAR(r.wall_shear / r.wall_shear_reference, 1, 0.15);
  EXPECT_LT(std::abs(r.inflow_rate_error), 0.03);
}


// A sheet beside walls that enclose the fluid (the flap in the junction): a plate along the axis
// of a pipe at Re 138 takes the skin friction of the flow round it. In the steady state the flow
// rate is fixed and the profile at the outlet recovered, so the pressure drop between the first
// and the last layer of cells balances the plate's drag and the wall's shear between them (each
// end's half cell of wall carries the undisturbed Poiseuille shear); lateral forces vanish by
// symmetry. The sheet's force (its markers) and the wall's (traction) come from the same run.
struct PipeRun {
  double drag = 0, lateral = 0, wall = 0, pressure_drop = 0;
};
PipeRun run_pipe_with(const std::string& bodies_tail) {
  std::string text = std::regex_replace(kPipeCase, std::regex(R"(  - \{name: ball.*\n)"), bodies_tail);
  text = std::regex_replace(text, std::regex("nu: 1.0745e-5"), "nu: 1.0e-4");
  text = std::regex_replace(text, std::regex("ramp_time: 0.5"), "ramp_time: 0.02");
  text = std::regex_replace(text, std::regex("t_end: 0.1"), "t_end: 0.3");
  finverse::test::ScratchDir dir;
  std::ofstream(dir / "pipe.yaml") << text;
  const cases::CaseFile c = cases::read_case_file(dir / "pipe.yaml", false);
  PipeRun out;
  const cases::FlowCaseResult r = cases::run_flow_case(c.flow, {}, [&](const FlowSolver& f) {
    // The mean pressure over the fluid cells of a layer (kinematic, times rho); the outlet's
    // pressure is not pinned, so the drop from the first layer to the last, times the area.
    const auto layer = [&](int k) {
      double sum = 0;
      int n = 0;
      for (int j = 0; j < f.grid().ny(); ++j)
        for (int i = 0; i < f.grid().nx(); ++i)
          if (f.immersed()->kind(i, j, k) == CellKind::Fluid) sum += f.p()(i, j, k), ++n;
      return c.flow.rho * sum / n;
    };
    out.pressure_drop = (layer(0) - layer(f.grid().nz() - 1)) * std::numbers::pi * 0.01095 * 0.01095;
  });
  const auto& last = r.force.back();
  out.wall = last[0][2];
  if (last.size() == 2) {
    out.drag = last[1][2];
    out.lateral = std::hypot(last[1][0], last[1][1]);
  }
  return out;
}

TEST(EnclosedFluid, ASheetInThePipeTakesTheDragThePressureDropSays) {
  const double h = 0.002, length = 0.032;
  const PipeRun empty = run_pipe_with("");
  const PipeRun plate = run_pipe_with(
      "  - {name: plate, shape: plate, leading_edge: [-0.004, 0, 0.01], chord: 0.008, span: 0.012, incidence: 0, "
      "cells: 4}\n");
  const double end_cells = empty.wall * h / length;
  EXPECT_NEAR(empty.pressure_drop / (empty.wall - end_cells), 1, 0.01);
  EXPECT_GT(plate.drag, 0.3 * plate.pressure_drop);
  EXPECT_LT(plate.lateral, 0.02 * plate.drag);
  EXPECT_NEAR(plate.pressure_drop / (plate.drag + plate.wall - end_cells), 1, 0.04)
      << "drop " << plate.pressure_drop << " N, plate " << plate.drag << " N, wall " << plate.wall << " N";
}

TEST(EnclosedFluid, AClosedBodyBesideASheetMustBeFixed) {
  std::string text = std::regex_replace(
      kPipeCase, std::regex(R"(  - \{name: ball.*\n)"),
      "  - {name: plate, shape: plate, leading_edge: [-0.004, 0, 0.01], chord: 0.008, span: 0.012, incidence: 0}\n"
      "  - {name: ball, shape: sphere, centre: [0, 0.006, 0.024], radius: 0.002, subdivisions: 2, "
      "motion: {translation: {z: {rate: 0.01}}}}\n");
  finverse::test::ScratchDir dir;
  std::ofstream(dir / "pipe.yaml") << text;
  const cases::CaseFile c = cases::read_case_file(dir / "pipe.yaml", false);
  try {
    cases::run_flow_case(c.flow);
    ADD_FAILURE() << "a moving closed body beside a sheet was accepted";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("a closed body beside a sheet must be fixed"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace finverse::cfd
