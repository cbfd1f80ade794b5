// Case files (fin-cfd run CASE.yaml; tools/cfd/cases): a validation case's file becomes its flags,
// a user's flow file becomes the same set-up as the C++ one, surface files become closed outward
// bodies, and bad files are one-line errors naming the file and the key.
#include <gtest/gtest.h>

#include <fstream>
#include <string>
#include <vector>

#include "../scratch_dir.hpp"
#include "cfd/cases/case_file.hpp"
#include "cfd/cases/flow_case.hpp"
#include "cfd/cases/run_case_file.hpp"
#include "cfd/cases/surface_file.hpp"
#include "cfd/validation/sphere_flow.hpp"
#include "core/error.hpp"

namespace finverse::cfd::cases {
namespace {

void write(const std::filesystem::path& p, const std::string& text) { std::ofstream(p) << text; }

std::string error_of(const std::filesystem::path& p) {
  try {
    read_case_file(p, false);
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

TEST(CaseFile, ValidationCaseKeysBecomeItsFlagsAndCoarseOverridesThem) {
  finverse::test::ScratchDir dir;
  write(dir / "c.yaml",
        "case: dfg_2d2\nreference: ../ref.json\ngrid:\n  cells_per_diameter: 24\n  wall_stretch_ratio: 0.97\n"
        "time: {t_end: 10}\nsolver: {staircase_balance: true, zero_wall_pressure_gradient: false}\n"
        "coarse:\n  grid: {cells_per_diameter: 12, wall_stretch_ratio: null}\n");
  const CaseFile full = read_case_file(dir / "c.yaml", false);
  EXPECT_EQ(full.kind, "dfg_2d2");
  const std::vector<std::string> expect_full = {"--cells-per-diameter",
                                                "24",
                                                "--reference",
                                                (dir.path().parent_path() / "ref.json").string(),
                                                "--staircase-balance",
                                                "--t-end",
                                                "10",
                                                "--wall-stretch-ratio",
                                                "0.97"};
  EXPECT_EQ(full.arguments, expect_full);
  const CaseFile coarse = read_case_file(dir / "c.yaml", true);
  const std::vector<std::string> expect_coarse = {
      "--cells-per-diameter", "12",      "--reference", (dir.path().parent_path() / "ref.json").string(),
      "--staircase-balance",  "--t-end", "10"};
  EXPECT_EQ(coarse.arguments, expect_coarse);
}

TEST(CaseFile, RunOfAValidationCaseBecomesItsSubcommandAndCommandLineFlagsComeLast) {
  finverse::test::ScratchDir dir;
  write(dir / "c.yaml",
        "case: sphere_re100\ngrid: {cells_per_diameter: 20}\ncoarse: {grid: {cells_per_diameter: 6}}\n");
  const auto flags_of = [](const std::string& name) -> std::optional<std::vector<std::string>> {
    if (name != "sphere_re100") return std::nullopt;
    return std::vector<std::string>{"--cells-per-diameter", "--t-end"};
  };
  const std::string file = (dir / "c.yaml").string();
  const auto args = expand_case_file({"fin-cfd", "--coarse", "run", file, "--t-end", "1"}, flags_of);
  EXPECT_EQ(args, (std::vector<std::string>{"fin-cfd", "--coarse", "sphere_re100", "--cells-per-diameter", "6",
                                            "--t-end", "1"}));
  EXPECT_EQ(expand_case_file({"fin-cfd", "sphere_re100"}, flags_of),
            (std::vector<std::string>{"fin-cfd", "sphere_re100"}));
  write(dir / "bad.yaml", "case: sphere_re100\ngrid: {cells_per_diameterr: 20}\n");
  try {
    expand_case_file({"fin-cfd", "run", (dir / "bad.yaml").string()}, flags_of);
    FAIL() << "a misspelt key was accepted";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("cells_per_diameterr: not an option of case sphere_re100"), std::string::npos)
        << e.what();
  }
  write(dir / "other.yaml", "case: no_such_case\n");
  EXPECT_THROW(expand_case_file({"fin-cfd", "run", (dir / "other.yaml").string()}, flags_of), Error);
}

// The sphere validation's own set-up and the same flow written as a case file run the same
// numbers: the file format loses nothing of the set-up.
TEST(CaseFile, FlowCaseFileRunsTheSphereValidationBitForBit) {
  finverse::test::ScratchDir dir;
  write(dir / "s.yaml", R"(case: flow
name: s
domain: {x: [-2, 4], y: [-2, 2], z: [-2, 2]}
grid: {h: 0.25, core: {x: [-0.75, 1.75], y: [-0.75, 0.75], z: [-0.75, 0.75]}, stretch_ratio: 1.12}
fluid: {nu: 0.01, rho: 1}
boundaries:
  x_lo: {type: inlet, velocity: [1, 0, 0]}
  x_hi: {type: convective_outlet}
  y_lo: {type: slip}
  y_hi: {type: slip}
  z_lo: {type: slip}
  z_hi: {type: slip}
initial: {velocity: [1, 0, 0]}
bodies: [{name: sphere, shape: sphere, radius: 0.5, subdivisions: 2}]
time: {t_end: 0.6, cfl: 0.8}
solver: {helmholtz_rtol: 1.0e-8, poisson_rtol: 1.0e-7}
outputs: {force_every: 2, reference_speed: 1, reference_area: 0.7853981633974483,
          control_volume: {x: [-1, 2], y: [-1, 1], z: [-1, 1]}}
)");
  SphereFlowSetup ss;
  ss.cells_per_diameter = 4;
  ss.t_end = 0.6;
  ss.box_x = {-2, 4};
  ss.box_half_width = 2;
  ss.subdivisions = 2;
  ss.force_every = 2;
  const SphereFlowResult reference = run_sphere_flow(ss);
  const FlowCaseResult r = run_flow_case(read_case_file(dir / "s.yaml", false).flow);
  ASSERT_EQ(r.time.size(), reference.time.size());
  const double scale = 2 / (3.141592653589793 / 4);
  for (std::size_t k = 0; k < r.time.size(); ++k) {
    EXPECT_EQ(r.time[k], reference.time[k]);
    EXPECT_EQ(scale * r.force[k][0][0], reference.cd_history[k]) << k;
  }
  EXPECT_GT(reference.cd, 0.5);
}

TEST(CaseFile, MisspeltOrMissingKeysNameTheFileTheKeyAndTheLine) {
  finverse::test::ScratchDir dir;
  const auto p = dir / "f.yaml";
  write(p, "case: flow\ndomain: {x: [0, 1], y: [0, 1], z: [0, 1]}\ngridd: {h: 0.1}\n");
  EXPECT_EQ(error_of(p), p.string() + ":3: gridd: unknown key");
  write(p, "grid: 1\n");
  EXPECT_EQ(error_of(p), p.string() + ": case: missing (a validation case's name, or flow)");
  write(p,
        "case: flow\ndomain: {x: [0, 1], y: [0, 1], z: [0]}\ngrid: {h: 0.1, core: {x: [0.2, 0.8], y: [0.2, 0.8], "
        "z: [0.2, 0.8]}}\n");
  EXPECT_EQ(error_of(p), p.string() + ":2: domain.z: expected a list of 2 numbers");
  write(p, "case: [flow\n");
  EXPECT_NE(error_of(p).find(p.string() + ":"), std::string::npos);
  EXPECT_NE(error_of(p).find("not valid YAML"), std::string::npos);
}

TEST(CaseFile, PlaneFlowTakesAnOutlineFileAndHasNoZSides) {
  finverse::test::ScratchDir dir;
  write(dir / "flap.txt", "# x y\n0 0\n0.1 0\n0.1 0.02\n\n0 0.02\n");
  const std::string head =
      "case: flow\ndomain: {x: [-1, 2], y: [-1, 1]}\ngrid: {h: 0.05, core: {x: [-0.2, 0.4], y: [-0.2, 0.2]}}\n"
      "fluid: {nu: 0.01}\nboundaries:\n  x_lo: {type: inlet, profile: parabolic, velocity: [1, 0, 0], "
      "ramp_time: 0.5}\n  x_hi: {type: convective_outlet}\n  y_lo: {type: no_slip}\n  y_hi: {type: no_slip}\n";
  write(dir / "p.yaml", head + "bodies: [{name: flap, outline_file: flap.txt, scale: 2}]\ntime: {t_end: 1}\n");
  const FlowCaseSpec s = read_case_file(dir / "p.yaml", false).flow;
  EXPECT_EQ(s.dim, 2);
  ASSERT_EQ(s.bodies.size(), 1u);
  EXPECT_EQ(s.bodies[0].outline, (std::vector<std::array<double, 2>>{{0, 0}, {0.2, 0}, {0.2, 0.04}, {0, 0.04}}));
  EXPECT_TRUE(s.sides[0].parabolic);
  EXPECT_EQ(s.sides[0].ramp_time, 0.5);
  EXPECT_EQ(flow_case_grid(s).dim(), 2);
  write(dir / "z.yaml", head + "  z_lo: {type: slip}\nbodies: [{outline_file: flap.txt}]\ntime: {t_end: 1}\n");
  EXPECT_EQ(error_of(dir / "z.yaml"), (dir / "z.yaml").string() +
                                          ":10: boundaries.z_lo: a plane flow (no domain.z) "
                                          "has no z sides");
  write(dir / "flap.txt", "0 0\n0.1 zero\n");
  EXPECT_EQ(error_of(dir / "p.yaml"), (dir / "flap.txt").string() + ":2: expected two numbers, x y");
}

// A closed box as 12 triangles with every corner repeated per triangle, as STL stores it.
std::string box_stl(bool inside_out) {
  const double c[8][3] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}};
  const int f[12][3] = {{0, 2, 1}, {0, 3, 2}, {4, 5, 6}, {4, 6, 7}, {0, 1, 5}, {0, 5, 4},
                        {1, 2, 6}, {1, 6, 5}, {2, 3, 7}, {2, 7, 6}, {3, 0, 4}, {3, 4, 7}};
  std::string s = "solid box\n";
  for (const auto& t : f) {
    s += " facet normal 0 0 0\n  outer loop\n";
    const int order[3] = {t[0], inside_out ? t[2] : t[1], inside_out ? t[1] : t[2]};
    for (int v : order)
      s +=
          "   vertex " + std::to_string(c[v][0]) + " " + std::to_string(c[v][1]) + " " + std::to_string(c[v][2]) + "\n";
    s += "  endloop\n endfacet\n";
  }
  return s + "endsolid box\n";
}

TEST(SurfaceFile, StlCornersAreMergedAndTheSurfaceTurnedOutward) {
  finverse::test::ScratchDir dir;
  for (bool inside_out : {false, true}) {
    write(dir / "box.stl", box_stl(inside_out));
    const TriangulatedSurface s = read_surface_file(dir / "box.stl");
    EXPECT_EQ(s.points.size(), 8u);
    EXPECT_EQ(s.triangles.size(), 12u);
    EXPECT_NEAR(signed_volume(s), 1.0, 1e-12) << "inside out: " << inside_out;
  }
  write(dir / "box.obj",
        "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 1\nv 1 0 1\nv 1 1 1\nv 0 1 1\n"
        "f 1 4 3 2\nf 5 6 7 8\nf 1 2 6 5\nf 2 3 7 6\nf 3 4 8 7\nf 4 1 5 8\n");
  TriangulatedSurface obj = read_surface_file(dir / "box.obj");
  EXPECT_EQ(obj.triangles.size(), 12u);  // quads split in two
  transform(obj, 2.0, {1, 0, 0});
  EXPECT_NEAR(signed_volume(obj), 8.0, 1e-12);
  EXPECT_THROW(read_surface_file(dir / "box.ply"), Error);
  EXPECT_THROW(read_surface_file(dir / "missing.stl"), Error);
}

}  // namespace
}  // namespace finverse::cfd::cases
