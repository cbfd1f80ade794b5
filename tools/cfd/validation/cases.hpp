// The flow solver's validation cases (DESIGN.md section 6), run by `fin-cfd <case>` or from a case
// file (`fin-cfd run data/cases/cfd/<case>.yaml`, case_file.hpp): each runs its set-up, writes
// <out_dir>/<case>/summary.json (and its force history), and grades the result against the
// literature (data/reference/*.json). The set-ups themselves are in the files beside this one.
#pragma once

#include <CLI/CLI.hpp>
#include <filesystem>
#include <string>
#include <utility>
#include <variant>
#include <vector>

namespace finverse::cfd::validation {

// Every option of every case; 0 or empty means "the case's default".
struct CaseOptions {
  bool coarse = false;  // the CI variant (coarser grid, shorter run, grades reported only)
  std::filesystem::path out_dir = "results/validation";
  // Immersed-body benchmarks (DFG, Turek-Hron, sphere, DFG 3D-1Z).
  int cells_per_diameter = 0;                 // h = D / N in the box around the body
  double t_end = 0;                           // simulated time
  std::string reference;                      // the case's data/reference/*.json (empty: the case's own)
  double wake_box = 0;                        // DFG, Turek-Hron: the uniform box's downstream end
  double stretch_ratio = 0;                   // DFG, Turek-Hron: stretching ratio outside the box
  int core_cells_per_diameter = 0;            // DFG, Turek-Hron: a finer core around the body
  double core_wake = 0;                       // DFG, Turek-Hron: the core's length behind the body [D]
  double cfl = 0;                             // DFG, Turek-Hron: target convective CFL number
  double wall_stretch_ratio = 0;              // DFG, Turek-Hron: ratio between the box and the walls
  bool staircase_balance = false;             // the staircase mass balance instead of the cut-cell one
  bool zero_wall_pressure_gradient = false;   // DFG, Turek-Hron: dp/dn = 0 on the body
  bool wall_momentum_balance = false;         // sphere, DFG 3D-1Z: the wall's momentum balance for dp/dn
  std::string wall_extrapolation = "linear";  // DFG 2-D: the surface traction's extrapolation to the wall
  double kick_velocity = -1;                  // Turek-Hron CFD3: the start-up push (< 0: the default)
  int span_cells = 0;                         // DFG 3D-1Z, spanwise_plate_2d3d: cells along z
  // Heaving plate against Garrick's theory (heaving_plate_garrick.hpp; also cfl above).
  double reynolds = 0;                        // U c / nu (pipe_poiseuille: rho U D / mu)
  double reduced_frequency = 0;               // k = pi f c / U
  std::string amplitudes;                     // h0/c, comma-separated
  double thickness = 0;                       // t/c
  int cells_per_chord = 0;
  int periods = 0, periods_averaged = 0;
  bool at_rest = false;                       // spanwise_plate_2d3d: the plate held still (drag alone)
  // The zero-thickness sheet (sheet_forcing.hpp): kernel name (empty: the default), marker spacing
  // [cells] and projection passes (0: the defaults).
  std::string kernel;
  double marker_spacing = 0;
  int projections = 0;
  bool raw_sheet_force = false;  // the markers' impulses as the load, without the band correction
  // Channel: checkpoint and restart, ParaView output.
  int checkpoint_every = 0;
  std::string restart;
  bool vtk = false;
};

// One command-line flag / case-file key of a case, bound to its CaseOptions field.
struct CaseOption {
  using Target = std::variant<int*, double*, bool*, std::string*>;
  CaseOption(std::string flag_, Target target_, std::string help_, double lo_ = 0, double hi_ = 0,
             bool positive_ = false)
      : flag(std::move(flag_)), target(target_), help(std::move(help_)), lo(lo_), hi(hi_), positive(positive_) {}
  std::string flag;  // "--cells-per-diameter"; the case-file key is the same without the dashes
  Target target;
  std::string help;
  double lo = 0, hi = 0;             // accepted range when lo < hi
  bool positive = false;             // accepted: > 0
  std::vector<std::string> choices;  // accepted values of a string option
  bool existing_file = false;
  bool show_default = false;
};

struct ValidationCase {
  std::string name;  // subcommand and results/validation/<name>
  std::string description;
  int (*run)(const CaseOptions&);  // exit code: 0 every graded metric passes, 1 one misses
  std::string reference = "";      // the default --reference file (data/reference/*.json), if any
};

const std::vector<ValidationCase>& validation_cases();
const ValidationCase* find_case(const std::string& name);
// The options `c` takes, bound to `o`.
std::vector<CaseOption> case_options(const ValidationCase& c, CaseOptions& o);
// The options as flags of `subcommand`, with their checks (ranges, choices, existing files).
void add_case_flags(CLI::App* subcommand, const std::vector<CaseOption>& options);
// Runs case `name` with `o` (an empty o.reference: the case's own file).
int run_case(const ValidationCase& c, CaseOptions o);

int run_taylor_green(const CaseOptions& o);
int run_channel(const CaseOptions& o);
int run_dfg_2d1(const CaseOptions& o);
int run_dfg_2d2(const CaseOptions& o);
int run_dfg_2d3(const CaseOptions& o);
int run_turek_hron_cfd2(const CaseOptions& o);
int run_turek_hron_cfd3(const CaseOptions& o);
int run_ib_couette(const CaseOptions& o);
int run_sheet_towed_plate(const CaseOptions& o);
int run_cylinder_towed(const CaseOptions& o);
int run_cylinder_oscillating(const CaseOptions& o);
int run_sphere_re100(const CaseOptions& o);
int run_dfg_3d1z(const CaseOptions& o);
int run_heaving_plate_garrick(const CaseOptions& o);
int run_spanwise_plate_2d3d(const CaseOptions& o);
int run_pipe_poiseuille(const CaseOptions& o);

}  // namespace finverse::cfd::validation
