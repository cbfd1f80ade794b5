// The silicone flap of Hessenthaler et al. (2017, Int. J. Numer. Meth. Biomed. Eng. 33:e2848, the
// no-flow experiment) as a structural model: an 11 x 2 x 65 mm strip clamped at one end, lying
// across gravity (its thickness along g), loaded only by its net buoyancy (rho_f - rho_s) g per
// unit volume, a dead load that keeps its direction. The flap is lighter than the glycerol, so it
// bends up by ~45 % of its length: geometrically nonlinear, solved with the corotational beam
// (default) or the corotational shell strip under load-controlled Newton.
// Beam or shell: a strip bent to radius R lies between the beam value E b h^3 / 12 and the plate
// value E b h^3 / 12 (1 - nu^2) according to Searle's parameter b^2 / (R h) (small: free
// anticlastic curvature, the beam); here b^2 / (R h) ~ 0.5, and the shell with nu = 0.45 says how
// far from the beam value the strip actually is.
#pragma once

#include <array>
#include <filesystem>
#include <string>
#include <vector>

#include "fem/model.hpp"
#include "fem/sparse_solver.hpp"
#include "fem/validation/shell_meshes.hpp"

namespace finverse::fem::validation {

struct HessenthalerFlap {
  double length = 0.065, width = 0.011, thickness = 0.002;  // [m]
  double fluid_density = 1163.3, solid_density = 1058.3;    // [kg/m^3]
  double gravity = 9.81;                                    // [m/s^2]
  double poisson_ratio = 0.45;
  double tip_deflection_no_flow = 0.02950;                  // measured [m]
  double tip_deflection_phase_I = 0.01641;                  // measured [m]
  double voxel = 0.977e-3;                                  // MRI voxel of the flap images [m]
  double others_shear_modulus = 61000;                      // neo-Hookean calibration [Pa]
  double uniaxial_shear_modulus = 96900;                    // tensile test [Pa]
  double uniaxial_tip_deflection = 0.0217;                  // what 96.9 kPa gives [m]
  // Net upward load per unit length [N/m].
  double buoyancy_per_length() const {
    return (fluid_density - solid_density) * gravity * width * thickness;
  }
};

// Reads hessenthaler2017.json (data/reference). Throws InvalidInput naming the file and the key.
HessenthalerFlap read_hessenthaler_flap(const std::filesystem::path& reference);

// The MRI centreline file (phaseI_centreline.csv): rows x_mm, y_mm, z_mm after '#' comments and a
// header; returns (z, y) in metres. Throws InvalidInput naming the file and line.
std::vector<std::array<double, 2>> read_mri_centreline(const std::filesystem::path& path);

// The published zero-flow centreline fit (hessenthaler2017.json: zero_flow_centreline_fit),
// y = scale sum_i p_i (z / length)^(i + 1), sampled at `points` z evenly from `z_first` to its
// length: (z, y) [m]. Throws InvalidInput naming the file and key.
std::vector<std::array<double, 2>> zero_flow_centreline(const std::filesystem::path& reference, int points,
                                                        double z_first);

enum class FlapModel { beam, shell };
FlapModel parse_flap_model(const std::string& name);  // "beam" | "shell"; InvalidInput otherwise
const char* to_string(FlapModel model);

struct FlapMesh {
  FlapModel model = FlapModel::beam;
  int along = 32;   // elements (beam) or cells (shell) along the flap
  int across = 4;   // shell cells across the width (2 triangles each)
};

struct FlapDeflection {
  double tip = 0;        // tip centre's displacement along the buoyancy [m]
  double tip_axial = 0;  // its displacement along the flap's axis (shortening < 0) [m]
  // Deformed centreline from the clamp to the tip, (x, z) per station along the flap [m] (shell:
  // the width's mean at each row of nodes).
  std::vector<std::array<double, 2>> centreline;
  int newton_iterations = 0;
};

// A flap that differs from the straight, flat, uniform strip: the candidate effects of fin-loop
// flap. Rest curvature: the clamp-to-tip line an arc bent towards +z (the buoyancy); cupping: a
// shallow arc across the width (shell only); distal softening a: E (1 - a) beyond half the length.
struct FlapShape {
  double rest_curvature = 0;    // [1/m]
  double rest_cupping = 0;      // [1/m]
  double distal_softening = 0;  // [-], below 1
};

// Dead loads per unit length [N/m]: `uniform` along +z, plus profiles piecewise constant on equal
// stations from the clamp to the tip, along +z (transverse) and along +x (the clamp's axis);
// nodal: the shell's nodes' dead loads [N], 3 per node in the flap's frame (e.g. a 3-D flow's time
// mean on the same strip; empty: none).
struct FlapLoad {
  double uniform = 0;
  std::vector<double> transverse, along;
  std::vector<double> nodal;
};

// The shell strip without loads, in the flap's frame (along +x from the clamp, width along y,
// thickness and buoyancy along +z): model node n is grid node n (grid.node(i, j), i along, j
// across), the clamp row i = 0 fixed; grid.triangles are the mid-surface's; rows[i] the nodes of
// row i with the weights of the width's mean (the centreline station at i L / along).
struct FlapShellModel {
  Model model;
  TriangleMesh grid;
  std::vector<std::vector<std::pair<int, double>>> rows;
};
// Throws InvalidInput for a mesh without cells or a shape the shell cannot carry.
FlapShellModel flap_shell_model(const HessenthalerFlap& flap, double youngs_modulus, const FlapMesh& mesh,
                                const FlapShape& shape = {});

// Static deflection under `load` of the flap `shape` (tip: the tip row's mean z minus the clamp
// row's, so a curved rest shape's offset counts; tip_axial: tip x minus the length). Throws
// NotConverged when Newton fails, InvalidInput for a shape the model cannot carry.
FlapDeflection flap_deflection(const HessenthalerFlap& flap, double youngs_modulus, const FlapMesh& mesh,
                               const FlapLoad& load, const FlapShape& shape, int load_steps = 8,
                               SolverBackend backend = SolverBackend::cholmod);

// Static deflection under a uniform dead load of `load_per_length` [N/m] along +z (the buoyancy's
// direction) for Young's modulus E [Pa] (Poisson ratio flap.poisson_ratio), ramped in load_steps
// Newton steps. Throws NotConverged when Newton fails.
FlapDeflection flap_deflection(const HessenthalerFlap& flap, double youngs_modulus, const FlapMesh& mesh,
                               double load_per_length, int load_steps = 8,
                               SolverBackend backend = SolverBackend::cholmod);
// The same under the flap's net buoyancy alone.
FlapDeflection flap_buoyancy_deflection(const HessenthalerFlap& flap, double youngs_modulus,
                                        const FlapMesh& mesh, int load_steps = 8,
                                        SolverBackend backend = SolverBackend::cholmod);

}  // namespace finverse::fem::validation
