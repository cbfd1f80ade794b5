// summary.json: grading of each metric kind, JSON round trip, atomic write.
#include <gtest/gtest.h>

#include <cmath>

#include "core/summary.hpp"
#include "test_util.hpp"

using finverse::Summary;

TEST(Summary, GradesEachKind) {
  Summary s("validation", "elastica_beam", "test");
  EXPECT_TRUE(*s.relative("w", 0.3020, 0.30172, 0.005, "ref").pass());
  EXPECT_FALSE(*s.relative("w2", 0.31, 0.30172, 0.005, "ref").pass());
  EXPECT_TRUE(*s.absolute("a", 1e-4, 0.0, 1e-3, "ref").pass());
  EXPECT_TRUE(*s.at_most("ratio", 0.4, 0.5, "goal").pass());
  EXPECT_FALSE(*s.at_most("ratio2", 0.6, 0.5, "goal").pass());
  EXPECT_TRUE(*s.at_least("p", 0.2, 0.01, "floor").pass());
  EXPECT_FALSE(*s.at_least("p2", 0.001, 0.01, "floor").pass());
  EXPECT_FALSE(s.info("n", 12).pass().has_value());
  EXPECT_FALSE(*s.relative("nan", std::nan(""), 1.0, 0.1, "ref").pass());
  EXPECT_FALSE(s.pass());
  EXPECT_NEAR(s.metrics()[0].error(), std::abs(0.3020 - 0.30172) / 0.30172, 1e-15);
}

TEST(Summary, RoundTripsThroughJson) {
  finverse::test::ScratchDir dir;
  Summary s("bench", "fem", "test");
  s.relative("w", 0.3020, 0.30172, 0.005, "Mattiasson 1981");
  s.info("time", 1.5, "s");
  s.parameters()["elements"] = 32;
  s.set_timing(2.5, 2);
  s.write(dir / "bench/fem.json");
  const auto back = Summary::read(dir / "bench/fem.json");
  EXPECT_EQ(back.to_json()["metrics"], s.to_json()["metrics"]);
  EXPECT_EQ(back.to_json()["parameters"]["elements"], 32);
  EXPECT_TRUE(back.pass());
  const auto j = nlohmann::json::parse(finverse::test::slurp(dir / "bench/fem.json"));
  EXPECT_EQ(j["schema"], "finverse/summary");
  EXPECT_EQ(j["metrics"][1]["reference"], nullptr);
}

TEST(Summary, RejectsUnknownKind) { EXPECT_THROW(Summary("other", "x", ""), finverse::Error); }
