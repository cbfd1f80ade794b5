// Tolerance files: defaults, glob patterns (first match wins), ignore lists, bad input.
#include <gtest/gtest.h>

#include "core/array_compare.hpp"
#include "core/error.hpp"
#include "core/tolerances.hpp"
#include "test_util.hpp"

using namespace finverse;

TEST(Tolerances, PatternsAndDefaults) {
  test::ScratchDir dir;
  std::ofstream(dir / "t.json") << R"({"default": {"atol": 1e-12, "rtol": 1e-9},
    "datasets": {"/points": {"atol": 1e-6}, "/coefficients/*": {"rtol": 1e-3}}, "ignore": ["/quality/*"]})";
  const auto t = Tolerances::load(dir / "t.json");
  EXPECT_EQ(t.for_object("/points").atol, 1e-6);
  EXPECT_EQ(t.for_object("/points").rtol, 1e-9);  // inherits the default's rtol
  EXPECT_EQ(t.for_object("/coefficients/thrust").rtol, 1e-3);
  EXPECT_EQ(t.for_object("/time").atol, 1e-12);
  EXPECT_TRUE(t.ignored("/quality/valid"));
  EXPECT_FALSE(t.ignored("/points"));
}

TEST(Tolerances, BadFilesNameTheFile) {
  test::ScratchDir dir;
  std::ofstream(dir / "bad.json") << R"({"default": {"atoll": 1}})";
  std::ofstream(dir / "neg.json") << R"({"default": {"atol": -1}})";
  std::ofstream(dir / "junk.json") << "{";
  for (const auto* n : {"bad.json", "neg.json", "junk.json", "missing.json"}) {
    try {
      Tolerances::load(dir / n);
      FAIL() << n;
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find(n), std::string::npos) << e.what();
    }
  }
}

TEST(ArrayCompare, StatisticsAndNaN) {
  NdArray<double> a({2, 3}, {1, 2, 3, 4, 5, std::nan("")});
  auto b = a;
  EXPECT_EQ(compare_values("x", a, b, {}).status, "equal");  // NaN in both is equal
  b(1, 1) = 5.001;
  auto c = compare_values("x", a, b, {0, 1e-3});
  EXPECT_TRUE(c.ok);
  EXPECT_EQ(c.status, "within");
  c = compare_values("x", a, b, {0, 1e-5});
  EXPECT_FALSE(c.ok);
  EXPECT_EQ(c.where, "[1,1]");
  EXPECT_NEAR(c.max_abs, 1e-3, 1e-12);
  EXPECT_NEAR(c.max_rel, 2e-4, 1e-12);
  b(1, 2) = 6;
  c = compare_values("x", a, b, {1, 1});
  EXPECT_FALSE(c.ok);
  EXPECT_EQ(c.status, "NaN");
  EXPECT_EQ(compare_values("x", a, NdArray<double>({6}, 0.0), {}).status, "SHAPE");
}
