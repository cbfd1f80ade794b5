// The command-line flags that define the fin template, shared by fin-synth and fin-mesh so both
// build the same fin from the same configuration (seed paper section 4.1; defaults from
// config/config.yaml `fin`): either the parametric trout caudal fin or a JSON template file.
#pragma once

#include <filesystem>
#include <string>

#include <CLI/CLI.hpp>

#include "mesh/fin_template.hpp"

namespace finverse::mesh {

struct TemplateOptions {
  CaudalFinParams params;
  std::filesystem::path file;  // when set, the template is read from this JSON file instead
};

void add_template_options(CLI::App& app, TemplateOptions& o);
FinTemplate make_template(const TemplateOptions& o);

}  // namespace finverse::mesh
