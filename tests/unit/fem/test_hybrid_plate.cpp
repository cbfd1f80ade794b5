// Hybrid plate model (tools/fem/validation/hybrid_plate_model.hpp): beams on the plate's own
// nodes, the leading-edge heave moves the whole plate rigidly, and under an end load shared in
// proportion to the chordwise bending stiffness every chordwise line bends alike, so the plate
// and its three beams act as one cantilever of the summed stiffness: w = P L^3 / (3 sum EI).
#include <algorithm>
#include <filesystem>
#include <fstream>
#include <set>
#include <string>

#include <gtest/gtest.h>

#include "fem/corotational_beam.hpp"
#include "fem/errors.hpp"
#include "fem/static_solver.hpp"
#include "fem/validation/hybrid_plate.hpp"
#include "fem/validation/hybrid_plate_model.hpp"

using namespace finverse::fem;
using namespace finverse::fem::validation;

namespace {

// Dimensions of data/cases/hybrid_plate.json, nu = 0 so that cylindrical bending has no
// anticlastic coupling and the plate strip is exactly a beam of width `span`.
HybridPlateCase test_case() {
  HybridPlateCase c;
  c.chord = 1.0, c.span = 1.0, c.thickness = 0.01;
  c.plate = {"plate", 1e5, 0.0, 10.0};
  const double E[3] = {1e8, 1e7, 5e7}, z[3] = {-0.5, 0.0, 0.5};
  for (int b = 0; b < 3; ++b)
    c.beams.push_back({"b" + std::to_string(b + 1), z[b], {"b", E[b], 0.0, 10.0}, 0.04, 0.02});
  c.pressure = 1.5;
  c.heave_amplitude = 0.1, c.frequency = 0.5, c.periods = 2, c.time_step = 0.005;
  return c;
}

}  // namespace

TEST(HybridPlate, BeamsLieOnTheShellNodes) {
  const HybridPlateCase c = test_case();
  const HybridPlateModel hp = build_hybrid_plate(c, 4, 4, HybridPlateLoad::pressure);
  EXPECT_EQ(hp.model.node_count(), 5 * 5);  // no node of its own for any beam
  std::set<int> shell_nodes, beam_nodes;
  for (const auto& e : hp.model.elements()) {
    auto& target = e->type() == "corotational_beam" ? beam_nodes : shell_nodes;
    for (int n : e->nodes()) target.insert(n);
  }
  EXPECT_EQ(hp.beam_elements, 12);
  EXPECT_EQ(hp.shell_elements, 32);
  for (int n : beam_nodes) EXPECT_TRUE(shell_nodes.count(n)) << "beam node " << n;
  for (size_t b = 0; b < c.beams.size(); ++b) {
    const Vec3& X = hp.model.reference_positions()[hp.tips[b]];
    EXPECT_NEAR(X.x(), c.chord, 1e-14);
    EXPECT_NEAR(X.z(), c.beams[b].z, 1e-14);
    EXPECT_NEAR(X.y(), 0.0, 1e-14);  // no eccentricity
  }
  // Total load = pressure x area, along -y.
  EXPECT_NEAR(hp.model.reference_load().sum(), -c.pressure * c.chord * c.span, 1e-12);
}

TEST(HybridPlate, BeamOffTheGridIsRejected) {
  EXPECT_THROW(build_hybrid_plate(test_case(), 4, 3, HybridPlateLoad::pressure), InvalidInput);
}

TEST(HybridPlate, LeadingEdgeHeaveMovesThePlateRigidly) {
  const HybridPlateCase c = test_case();
  HybridPlateModel hp = build_hybrid_plate(c, 4, 4, HybridPlateLoad::heave);
  NodalState s = hp.model.reference_state();
  StaticSolver solver(hp.model);
  // An eighth of a period (heave 0.29 A): in load steps of a tenth of that the first Newton
  // iterations of each step stay in the positive-definite range.
  const double t = 0.125 / c.frequency;
  solver.solve(s, 0.0, t);
  for (int n = 0; n < hp.model.node_count(); ++n) {
    const Vec3 u = s.position[n] - hp.model.reference_positions()[n];
    EXPECT_NEAR(u.y(), c.heave(t), 1e-9) << "node " << n;
    EXPECT_NEAR(u.x(), 0.0, 1e-9);
    EXPECT_NEAR(u.z(), 0.0, 1e-9);
  }
}

TEST(HybridPlate, StiffnessProportionalEndLoadBendsLikeOneCantilever) {
  const HybridPlateCase c = test_case();
  const int nx = 8, nz = 8;
  HybridPlateModel hp = build_hybrid_plate(c, nx, nz, HybridPlateLoad::none);
  Model& m = hp.model;
  const double d_plate = c.plate.youngs_modulus * c.thickness * c.thickness * c.thickness / 12.0;
  double ei_total = d_plate * c.span;
  const double load_per_width = -1e-5;  // linear range: w ~ 1e-4 of the chord
  // Plate trailing-edge nodes: trapezoidal shares of the line load carried by the plate strip.
  for (int j = 0; j <= nz; ++j) {
    const int n = (nx + 1) * j + nx;  // rectangle_mesh numbering, node(i = nx, j)
    const double share = (j == 0 || j == nz ? 0.5 : 1.0) * c.span / nz;
    m.add_nodal_load(n, 1, load_per_width * share);
  }
  for (size_t b = 0; b < c.beams.size(); ++b) {
    const auto& beam = c.beams[b];
    const double ei = beam.material.youngs_modulus * beam.width * beam.thickness *
                      beam.thickness * beam.thickness / 12.0;
    ei_total += ei;
    m.add_nodal_load(hp.tips[b], 1, load_per_width * ei / d_plate);
  }
  const double total = load_per_width * ei_total / d_plate;
  const double w_expected = total * c.chord * c.chord * c.chord / (3.0 * ei_total);

  NodalState s = m.reference_state();
  StaticSolver solver(m);
  solver.solve(s, 0.0, 1.0);
  for (size_t b = 0; b < c.beams.size(); ++b) {
    const double w = s.position[hp.tips[b]].y();
    EXPECT_NEAR(w / w_expected, 1.0, 0.01) << c.beams[b].name;
  }
}

// The dynamic comparison reads a stored CalculiX history computed for one heave; a case with
// another amplitude must be refused before anything is compared.
TEST(HybridPlate, DynamicReferenceOfAnotherHeaveIsRejected) {
  namespace fs = std::filesystem;
  const fs::path dir = fs::temp_directory_path() / "finverse_test_hybrid_plate_reference";
  fs::create_directories(dir);
  {
    std::ofstream c(dir / "case.json");
    c << R"({"plate": {"chord": 1, "span": 1, "thickness": 0.01, "E": 1e5, "nu": 0.3, "density": 10},
             "beams": [{"name": "b1", "z": 0.0, "E": 1e7, "nu": 0.3, "density": 10,
                        "width": 0.04, "thickness": 0.02}],
             "static": {"pressure": 1.5, "load_steps": 10},
             "dynamic": {"heave_amplitude": 0.001, "frequency": 0.5, "periods": 2, "time_step": 0.005}})";
    std::ofstream r(dir / "reference.json");
    r << R"({"dynamic": {"heave_amplitude": 0.1, "frequency": 0.5, "time": [0.005, 0.01],
                         "tips_y": {"b1": [0.0, 0.0]}}})";
  }
  HybridPlateOptions o;
  o.case_file = dir / "case.json";
  o.reference = dir / "reference.json";
  o.nx = 2, o.nz = 2;
  try {
    run_hybrid_plate_dynamic(o);
    ADD_FAILURE() << "no error for a reference of another heave amplitude";
  } catch (const InvalidInput& e) {
    EXPECT_NE(std::string(e.what()).find("heave_amplitude"), std::string::npos) << e.what();
  }
  fs::remove_all(dir);
}
