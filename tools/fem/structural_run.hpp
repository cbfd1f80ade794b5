// Runs one analysis of a model over a sequence of output times (the file-driven mode of fin-fem;
// no file I/O here). The model carries everything time dependent: tabulated loads
// (load_history.hpp), prescribed root motion (root_motion.hpp), gravity and the material field
// (stiffness_field.hpp). Every analysis starts from the unloaded reference configuration at
// start_time (< the first output time; the loads and root motion ramp up from rest before
// their first sample, load_history.hpp):
//   static        equilibrium at every output time, each solve continued from the previous one
//                 (ramp_steps equal steps from start_time to the first time, then one step per
//                 interval, cut automatically where Newton fails);
//   quasi_static  equilibrium at the first time as above, then the paper's eq. (2) increment
//                 from each output time to the next (quasi_static_increment.hpp);
//   dynamic       generalized-alpha from rest at start_time with substeps equal steps per output
//                 interval (output times must then be equally spaced, and the ramp a whole number
//                 of steps: start_time is moved back to the nearest one).
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "fem/generalized_alpha.hpp"
#include "fem/model.hpp"
#include "fem/static_solver.hpp"

namespace finverse::fem {

enum class Analysis { static_equilibrium, quasi_static, dynamic };
Analysis parse_analysis(const std::string& name);  // "static" | "quasi_static" | "dynamic"
const char* to_string(Analysis analysis);

struct RunOptions {
  Analysis analysis = Analysis::quasi_static;
  double start_time = 0;  // the reference configuration's time, < the first output time
  int ramp_steps = 10;    // static/quasi_static: load steps from start_time to the first time
  int substeps = 4;       // dynamic: time steps per output interval
  StaticOptions static_options;    // .steps is ignored (see above)
  DynamicOptions dynamic_options;  // .time_step is ignored (set from substeps)
};

struct RunFrame {
  double time = 0;
  NodalState state;
  Eigen::VectorXd velocity;  // full length; dynamic only (empty otherwise)
  int iterations = 0;        // Newton iterations spent since the previous frame
};

// on_frame(k, frame) after each output frame k = 0..n-1 (progress reporting). Throws
// InvalidInput (bad times/options), SingularMatrix, NotConverged.
std::vector<RunFrame> run_structural_analysis(const Model& model, const RunOptions& options,
                                              const std::vector<double>& output_times,
                                              const std::function<void(int, const RunFrame&)>& on_frame = {});

}  // namespace finverse::fem
