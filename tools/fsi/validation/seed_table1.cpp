// The seed paper's Table 1 beside our Turek-Hron run (see seed_table1.hpp).
#include "fsi/validation/seed_table1.hpp"

#include <cstdio>
#include <optional>

namespace finverse::fsi::validation {
namespace {

std::optional<double> metric(const Summary& s, const std::string& name) {
  for (const auto& m : s.metrics())
    if (m.name == name) return m.value;
  return std::nullopt;
}

std::string row(const std::string& source, double am, double st, double cd) {
  char buf[128];
  std::snprintf(buf, sizeof buf, "  %-18s %6.2f %6.3f %6.2f", source.c_str(), am, st, cd);
  return buf;
}

}  // namespace

std::vector<std::string> seed_table1_lines(const nlohmann::json& reference, const std::string& case_name,
                                           const Summary& summary) {
  const std::string key = case_name + "_like";
  if (!reference.contains("seed_paper_table1") || !reference["seed_paper_table1"].contains(key)) return {};
  std::vector<std::string> lines{"seed paper Table 1, " + case_name +
                                     " (A_m/D = peak |u_y| / D, i.e. |mean| + amplitude, in every column):",
                                 "  source               A_m/D     St    C_D"};
  for (const auto& [source, v] : reference["seed_paper_table1"][key].items())
    lines.push_back(row(source == "present" ? "seed paper" : source, v.at("Am_D").get<double>(),
                        v.at("St").get<double>(), v.at("CD").get<double>()));
  const auto am = metric(summary, "Am_over_D_peak"), st = metric(summary, "St"), cd = metric(summary, "CD_mean");
  if (am && st && cd)
    lines.push_back(row("ours", *am, *st, *cd));
  else
    lines.push_back("  ours                 (no full period of u_y: nothing to put beside them)");
  return lines;
}

}  // namespace finverse::fsi::validation
