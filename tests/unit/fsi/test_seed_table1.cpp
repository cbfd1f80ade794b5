// The seed's Table 1 printed beside our Turek-Hron run (tools/fsi/validation/seed_table1.hpp).
#include <gtest/gtest.h>

#include <fstream>

#include "fsi/validation/seed_table1.hpp"

namespace fv = finverse::fsi::validation;

namespace {

nlohmann::json reference() {
  std::ifstream in(FINVERSE_TUREK_HRON_REFERENCE);
  return nlohmann::json::parse(in);
}

}  // namespace

TEST(SeedTable1, EveryColumnOfTheCaseAndOurRowFromTheSummary) {
  finverse::Summary s("validation", "fsi_turek_hron", "");
  s.info("Am_over_D_peak", 0.301);
  s.info("St", 0.277);
  s.info("CD_mean", 2.26);
  const auto lines = fv::seed_table1_lines(reference(), "FSI3", s);
  ASSERT_EQ(lines.size(), 7u);  // title, header, four sources, ours
  EXPECT_NE(lines[0].find("|mean| + amplitude"), std::string::npos);
  EXPECT_NE(lines.back().find("ours"), std::string::npos);
  EXPECT_NE(lines.back().find("0.30"), std::string::npos);
  EXPECT_NE(lines.back().find("0.277"), std::string::npos);
  bool turek = false;
  for (const auto& l : lines) turek |= l.find("Turek_Hron") != std::string::npos && l.find("0.36") != std::string::npos;
  EXPECT_TRUE(turek);
}

TEST(SeedTable1, NoRowWithoutAPeriodAndNoTableForFsi1) {
  finverse::Summary s("validation", "fsi_turek_hron", "");
  const auto lines = fv::seed_table1_lines(reference(), "FSI2", s);
  ASSERT_FALSE(lines.empty());
  EXPECT_NE(lines.back().find("no full period"), std::string::npos);
  EXPECT_TRUE(fv::seed_table1_lines(reference(), "FSI1", s).empty());
}
