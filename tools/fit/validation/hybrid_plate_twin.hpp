// Twin experiments on the hybrid plate of the seed paper's section 3.4 (data/cases/
// hybrid_plate.json, fem/validation/hybrid_plate_model.hpp): a model factory whose parameters
// are the paper's five unknowns "E_s", "E_b1", "E_b2", "E_b3" (one per beam of the case), "nu"
// (plate and beams), driven by the case's leading-edge heave and a load history the caller
// knows; and the truth target: the dynamic run with the true moduli, positions at every output
// step. A twin fit is then
//     auto twin = std::make_shared<HybridPlateTwin>(c, 8, 8, loads);
//     DynamicObjective f(twin, hybrid_plate_truth(*twin, twin->truth()).window(T, 2 * T));
// The plate's shells are built without a region modulus (build_hybrid_plate), so every
// evaluation builds its model (no in-place route); an 8 x 8 plate builds in well under a
// millisecond.
#pragma once

#include <functional>
#include <vector>

#include <Eigen/Core>

#include "fem/load_history.hpp"
#include "fem/validation/hybrid_plate_model.hpp"
#include "fit/model_factory.hpp"
#include "fit/target_motion.hpp"

namespace finverse::fit::validation {

class HybridPlateTwin : public ModelFactory {
 public:
  // loads: full-length (6 per node of the nx x nz plate) nodal loads, empty: the heave alone.
  // Throws fem::InvalidInput for a grid that misses a beam or loads of the wrong length.
  HybridPlateTwin(fem::validation::HybridPlateCase plate, int nx = 8, int nz = 8, fem::LoadHistory loads = {});

  std::vector<std::string> parameter_names() const override;
  std::unique_ptr<fem::Model> build(const Eigen::VectorXd& physical) const override;
  Eigen::VectorXd default_parameters() const override { return truth(); }
  std::vector<int> prescribed_nodes() const override { return leading_edge_; }

  // The case's moduli and Poisson ratio (the plate's), in parameter order.
  Eigen::VectorXd truth() const;
  const fem::validation::HybridPlateCase& plate_case() const { return case_; }
  int nx() const { return nx_; }
  int nz() const { return nz_; }
  const fem::LoadHistory& loads() const { return loads_; }
  bool has_loads() const { return !loads_.empty(); }

 private:
  fem::validation::HybridPlateCase case_;
  int nx_, nz_;
  fem::LoadHistory loads_;
  std::vector<int> leading_edge_;
};

// Uniform dead pressure p(t) along -y on the plate (consistent nodal forces, a third of each
// triangle's force per vertex, as the case's static load), sampled at `times`.
fem::LoadHistory hybrid_plate_pressure_loads(const fem::validation::HybridPlateCase& plate, int nx, int nz,
                                             const std::function<double(double)>& pressure,
                                             const std::vector<double>& times);

struct TwinTruthOptions {
  double output_interval = 0;  // 0: the case's time step
  int substeps = 1;            // time steps per output interval
  double end_time = 0;         // 0: the case's periods / frequency
  double spectral_radius = 0.8;  // as DynamicObjectiveOptions (dynamic_objective.hpp)
};

// The truth: generalized-alpha from rest at t = 0 (the heave starts from rest there) with the
// given parameters, positions at t_k = k * output_interval, k = 1..end_time / output_interval.
TargetMotion hybrid_plate_truth(const HybridPlateTwin& twin, const Eigen::VectorXd& physical,
                                const TwinTruthOptions& options = {});

}  // namespace finverse::fit::validation
