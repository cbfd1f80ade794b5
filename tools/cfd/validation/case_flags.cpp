// Case options as CLI11 flags of a subcommand; see cases.hpp (add_case_flags).
#include <type_traits>

#include "cfd/validation/cases.hpp"
#include "core/cli.hpp"

namespace finverse::cfd::validation {

namespace {

// One case option as a CLI11 flag with its check.
void add_case_flag(CLI::App* sc, const CaseOption& o) {
  CLI::Option* opt = std::visit(
      [&](auto* p) -> CLI::Option* {
        if constexpr (std::is_same_v<decltype(p), bool*>)
          return sc->add_flag(o.flag, *p, o.help);
        else
          return sc->add_option(o.flag, *p, o.help);
      },
      o.target);
  if (o.lo < o.hi) opt->check(CLI::Range(o.lo, o.hi));
  if (o.positive) opt->check(finverse::cli::positive());
  if (!o.choices.empty()) opt->check(CLI::IsMember(o.choices));
  if (o.existing_file) opt->check(CLI::ExistingFile);
  if (o.show_default) opt->capture_default_str();
}

}  // namespace

void add_case_flags(CLI::App* subcommand, const std::vector<CaseOption>& options) {
  for (const CaseOption& o : options) add_case_flag(subcommand, o);
}

}  // namespace finverse::cfd::validation
