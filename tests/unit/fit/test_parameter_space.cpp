// Parameter space: validation messages, the JSON specification, the scaled <-> physical maps.
#include <gtest/gtest.h>

#include "fit_test_util.hpp"

#include <cmath>

#include "fit/errors.hpp"
#include "fit/parameter_space.hpp"
#include "fit/residual_function.hpp"

namespace fit = finverse::fit;

namespace {

using fit::test::param;

// The message of the InvalidInput thrown by f, or "" when nothing is thrown.
template <class F>
std::string error_of(F f) {
  try {
    f();
  } catch (const fit::InvalidInput& e) {
    return e.what();
  }
  return "";
}

}  // namespace

TEST(ParameterSpace, ScaledAndPhysicalRoundTrip) {
  fit::ParameterSpace space({param("E", 1e5, 1e8), param("nu", 0.15, 0.49, fit::Scale::linear)});
  EXPECT_EQ(space.size(), 2);
  EXPECT_EQ(space.index("nu"), 1);
  EXPECT_EQ(space.index("G"), -1);
  EXPECT_DOUBLE_EQ(space.scaled_lower()(0), 5);
  EXPECT_DOUBLE_EQ(space.scaled_upper()(0), 8);
  EXPECT_DOUBLE_EQ(space.scaled_lower()(1), 0.15);
  Eigen::VectorXd p(2);
  p << 2.5e6, 0.3;
  const Eigen::VectorXd z = space.to_scaled(p);
  EXPECT_NEAR(z(0), std::log10(2.5e6), 1e-15);
  EXPECT_EQ(z(1), 0.3);
  EXPECT_NEAR(space.to_physical(z)(0), 2.5e6, 1e-6);
  EXPECT_EQ(space.truth().size(), 0);
}

TEST(ParameterSpace, RejectsBadBoundsWithOneLineMessages) {
  auto make = [](std::vector<fit::Parameter> ps) { return [ps] { fit::ParameterSpace s(ps, "spec.json"); }; };
  const std::string inverted = error_of(make({param("E_ray3", 1e8, 1e5)}));
  EXPECT_NE(inverted.find("spec.json"), std::string::npos) << inverted;
  EXPECT_NE(inverted.find("E_ray3"), std::string::npos) << inverted;
  EXPECT_NE(inverted.find("inverted"), std::string::npos) << inverted;
  EXPECT_EQ(inverted.find('\n'), std::string::npos);
  EXPECT_NE(error_of(make({param("E", 1e6, 1e6)})).find("zero-width"), std::string::npos);
  EXPECT_NE(error_of(make({param("E", 0, 1e6)})).find("positive lower"), std::string::npos);
  EXPECT_NE(error_of(make({param("E", -1, 1e6)})).find("positive lower"), std::string::npos);
  EXPECT_NE(error_of(make({param("E", 1, 2), param("E", 3, 4)})).find("repeated"), std::string::npos);
  EXPECT_NE(error_of(make({param("", 1, 2)})).find("empty name"), std::string::npos);
  EXPECT_NE(error_of(make({param("E", 1, NAN)})).find("finite"), std::string::npos);
  EXPECT_NE(error_of(make({})).find("no parameters"), std::string::npos);
  fit::Parameter t = param("E", 1, 2);
  t.truth = 3;
  EXPECT_NE(error_of(make({t})).find("truth"), std::string::npos);
  // Linear parameters may have a non-positive lower bound.
  EXPECT_EQ(error_of(make({param("x", -1, 1, fit::Scale::linear)})), "");
}

TEST(ParameterSpace, ParsesJson) {
  const auto j = nlohmann::json::parse(R"({"parameters": [
      {"name": "E_membrane", "lower": 1e5, "upper": 1e8, "scale": "log10", "unit": "Pa", "truth": 1.2e7},
      {"name": "nu", "lower": 0.15, "upper": 0.49, "scale": "linear", "truth": 0.4}]})");
  const fit::ParameterSpace space = fit::parse_parameter_space(j, "spec.json");
  ASSERT_EQ(space.size(), 2);
  EXPECT_EQ(space[0].unit, "Pa");
  EXPECT_EQ(space[1].scale, fit::Scale::linear);
  ASSERT_EQ(space.truth().size(), 2);
  EXPECT_EQ(space.truth()(0), 1.2e7);
}

TEST(ParameterSpace, JsonErrorsNameSourceAndParameter) {
  auto parse = [](const char* text) {
    return [text] { fit::parse_parameter_space(nlohmann::json::parse(text), "spec.json"); };
  };
  const std::string scale = error_of(parse(R"({"parameters": [{"name": "E", "lower": 1, "upper": 2, "scale": "log"}]})"));
  EXPECT_NE(scale.find("spec.json"), std::string::npos) << scale;
  EXPECT_NE(scale.find("'E'"), std::string::npos) << scale;
  EXPECT_NE(scale.find("unknown scale 'log'"), std::string::npos) << scale;
  EXPECT_NE(error_of(parse(R"({"parameters": [{"name": "E", "upper": 2}]})")).find("missing key 'lower'"),
            std::string::npos);
  EXPECT_NE(error_of(parse(R"({"parameters": [{"name": "E", "lower": 1, "upper": 2, "lowr": 3}]})"))
                .find("unknown key 'lowr'"),
            std::string::npos);
  EXPECT_NE(error_of(parse(R"({"params": []})")).find("'parameters'"), std::string::npos);
  EXPECT_NE(error_of(parse(R"({"parameters": [{"name": "E", "lower": "1", "upper": 2}]})")).find("number"),
            std::string::npos);
  EXPECT_NE(error_of(parse(R"({"parameters": [{"name": "E", "lower": 5, "upper": 2}]})")).find("inverted"),
            std::string::npos);
  EXPECT_NE(error_of([] { fit::parse_scale("cubic", "flag --scale"); }).find("flag --scale"), std::string::npos);
  EXPECT_NE(error_of([] { fit::read_parameter_space("/nonexistent/spec.json"); }).find("/nonexistent/spec.json"),
            std::string::npos);
}

TEST(ResidualFunction, MeanDistanceIsTheWeightedMeanPointDistance) {
  // Two node-samples, distances 3 and 1 (vectors (0,3,0) and (1,0,0)), weights 1 and 3:
  // residuals carry sqrt(w): r = (0, 3, 0, sqrt(3), 0, 0); J = (1*3 + 3*1) / 4 = 1.5.
  Eigen::VectorXd r(6), sw(2);
  r << 0, 3, 0, std::sqrt(3.0), 0, 0;
  sw << 1, std::sqrt(3.0);
  EXPECT_NEAR(fit::mean_distance(r, sw), 1.5, 1e-15);
  EXPECT_THROW(fit::mean_distance(Eigen::VectorXd::Zero(5), sw), fit::InvalidInput);
}
