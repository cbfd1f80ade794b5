// The fin's material parameters (DESIGN.md 5.4) mapped onto fin-fem's fin model
// (fem/io/fin_model.hpp): "E_membrane" (shell region 0), "E_ray<id>" (mesh ray id), "E_rays"
// (every ray; an "E_ray<id>" overrides it), "nu" (one Poisson ratio for all). Parameters not
// listed keep the materials file's values; its distal softening and modulation apply on top.
// The drive is fin-fem run's (loads.h5 forces and motion.h5 root motion, ramping up from rest).
// Default fin space: membrane E [1e5, 1e8] Pa, each ray's E [1e7, 1e10] Pa (log10), nu [0.15, 0.49].
#pragma once

#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "core/stage_files.hpp"
#include "fem/io/material_spec.hpp"
#include "fem/root_motion.hpp"
#include "fit/drive_parameters.hpp"
#include "fit/model_factory.hpp"
#include "fit/parameter_space.hpp"

namespace finverse::fit {

// Ray ids of the mesh (beams/ray), ascending, each once.
std::vector<int> mesh_ray_ids(const stage::Mesh& mesh);

// The default fin parameters (see above), as Parameter structs and as the specification file's
// JSON ({"parameters": [...]}, parameter_space.hpp).
std::vector<Parameter> default_fin_parameters(const stage::Mesh& mesh);
nlohmann::json default_fin_parameter_spec(const stage::Mesh& mesh);

struct FinDrive {
  std::optional<stage::Loads> loads;
  std::string loads_source = "loads.h5";
  std::optional<stage::Motion> root_motion;  // only the root nodes' positions are used
  std::string motion_source = "motion.h5";
  fem::RootRotation root_rotation = fem::RootRotation::fit;
  double ramp = 0;  // s; 0: ten output intervals (as fin-fem run)
  fem::Vec3 gravity = fem::Vec3::Zero();
  double frequency = 0;  // Hz: the beat, for drive_* parameters (drive_parameters.hpp)
};

class FinModelFactory : public ModelFactory {
 public:
  // Throws InvalidInput naming the parameter for an unknown or repeated name (an "E_ray<id>"
  // whose id the mesh lacks included), and fem::InvalidInput naming the file for bad mesh, loads
  // or motion data (the nominal model is built here once to find such problems early).
  FinModelFactory(stage::Mesh mesh, fem::io::MaterialSpec base, std::vector<std::string> parameter_names,
                  FinDrive drive = {}, std::string mesh_source = "mesh.h5");

  std::vector<std::string> parameter_names() const override { return names_; }
  std::unique_ptr<fem::Model> build(const Eigen::VectorXd& physical) const override;
  Eigen::VectorXd default_parameters() const override { return defaults_; }
  std::vector<int> prescribed_nodes() const override { return root_nodes_; }
  RayleighDamping damping() const override { return {base_.rayleigh_mass, base_.rayleigh_stiffness}; }
  Eigen::VectorXd rebuild_key(const Eigen::VectorXd& physical) const override;
  void set_moduli(fem::Model& model, const Eigen::VectorXd& physical) const override;
  bool moduli_and_poisson_only() const override { return drive_slots_.empty(); }
  int poisson_index() const override { return nu_; }
  // The mesh's points moved to `positions` (the root drive and loads unchanged: the root
  // displacements are then measured from these positions and the rotation fitted from them).
  std::shared_ptr<const ModelFactory> rebased(const std::vector<fem::Vec3>& positions) const override;

  double ramp() const { return ramp_; }
  // Start of a run from rest: the first output time minus the ramp (as fin-fem run).
  double start_time() const { return start_time_; }
  const stage::Mesh& mesh() const { return mesh_; }

 private:
  fem::io::MaterialSpec spec_for(const Eigen::VectorXd& physical) const;
  double membrane_modulus(const Eigen::VectorXd& p) const;
  double ray_modulus(int ray, const Eigen::VectorXd& p) const;

  stage::Mesh mesh_;
  fem::io::MaterialSpec base_;
  std::vector<std::string> names_;
  FinDrive drive_;
  std::string mesh_source_;
  int membrane_ = -1, rays_ = -1, nu_ = -1;  // parameter indices (-1: not a parameter)
  std::vector<std::pair<int, int>> ray_;     // (ray id, parameter index) of each "E_ray<id>"
  std::vector<std::pair<DriveSlot, int>> drive_slots_;  // (slot, parameter index) of each "drive_*"
  Eigen::VectorXd defaults_;
  std::vector<int> root_nodes_;
  fem::LoadHistory loads_;  // built once from drive_.loads
  double ramp_ = 0, start_time_ = 0;
  // Per element of the model: which modulus it takes (-2: none, -1: membrane, else a ray id) and
  // its modulus relative to that one (the distal factor).
  std::vector<int> element_slot_;
  std::vector<double> element_ratio_;
};

}  // namespace finverse::fit
