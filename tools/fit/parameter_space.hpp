// The unknowns of an inverse fit and the scaled variables the optimisers search (DESIGN.md
// section 5.4): moduli as z = log10(E) inside bounds spanning decades, the Poisson ratio as
// z = nu. Every optimiser, the polish and the uncertainty work in z; files and messages report
// physical values.
//
// Specification file (fin-fit --parameters spec.json):
//   {"parameters": [
//      {"name": "E_membrane", "lower": 1e5, "upper": 1e8, "scale": "log10", "unit": "Pa"},
//      {"name": "nu", "lower": 0.15, "upper": 0.49, "scale": "linear"}]}
// "truth" (optional, per parameter) is carried to the outputs for validation cases only.
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <nlohmann/json.hpp>

namespace finverse::fit {

enum class Scale { log10, linear };
const char* to_string(Scale scale);
Scale parse_scale(const std::string& name, const std::string& source);  // "log10" | "linear"

struct Parameter {
  std::string name;
  std::string unit;  // "Pa", "1", ...
  double lower = 0, upper = 0;  // physical bounds
  Scale scale = Scale::log10;
  std::optional<double> truth;  // validation cases only
};

class ParameterSpace {
 public:
  ParameterSpace() = default;
  // Throws InvalidInput naming `source` and the parameter for non-finite, inverted or zero-width
  // bounds, a log10 bound <= 0, an empty or repeated name, a truth outside the bounds.
  explicit ParameterSpace(std::vector<Parameter> parameters, const std::string& source = "parameters");

  int size() const { return static_cast<int>(parameters_.size()); }
  const Parameter& operator[](int i) const { return parameters_.at(i); }
  const std::vector<Parameter>& parameters() const { return parameters_; }
  int index(const std::string& name) const;  // -1 when absent
  std::vector<std::string> names() const;

  double to_scaled(int i, double physical) const;
  double to_physical(int i, double scaled) const;
  Eigen::VectorXd to_scaled(const Eigen::VectorXd& physical) const;
  Eigen::VectorXd to_physical(const Eigen::VectorXd& scaled) const;
  Eigen::VectorXd scaled_lower() const;
  Eigen::VectorXd scaled_upper() const;
  // Truth values in physical units; empty unless every parameter has one.
  Eigen::VectorXd truth() const;

 private:
  std::vector<Parameter> parameters_;
};

// Throws InvalidInput naming `source` and the key.
ParameterSpace parse_parameter_space(const nlohmann::json& j, const std::string& source);
ParameterSpace read_parameter_space(const std::filesystem::path& path);

}  // namespace finverse::fit
