// A subcommand that runs one validation case and writes its summary (fin-fsi's hessenthaler_plane
// and flap): the case's flags, --out-dir and --name; run() writes <out_dir>/<name>/summary.json
// and lists its metrics. Exit 1 when a graded metric misses (a result, not a failure).
#pragma once

#include <filesystem>
#include <iostream>
#include <string>
#include <utility>

#include <CLI/CLI.hpp>

#include "core/summary.hpp"

template <class Options>
struct SummaryCommand {
  Options o;
  std::string out_dir = "results/validation", name;
  CLI::App* cmd = nullptr;
  finverse::Summary (*run_case)(const Options&) = nullptr;

  void add(CLI::App& app, const std::string& sub, const std::string& help, std::string default_name,
           void (*flags)(CLI::App&, Options&), finverse::Summary (*run)(const Options&)) {
    name = std::move(default_name);
    run_case = run;
    cmd = app.add_subcommand(sub, help);
    flags(*cmd, o);
    cmd->add_option("--out-dir", out_dir, "directory that receives <name>/summary.json")->capture_default_str();
    cmd->add_option("--name", name, "case name")->capture_default_str();
  }
  int run() {
    const std::string sub = cmd->get_name();
    o.progress = [sub](const std::string& line) { std::cerr << "fin-fsi " << sub << ": " << line << "\n"; };
    const finverse::Summary summary = run_case(o);
    const auto path = std::filesystem::path(out_dir) / name / "summary.json";
    std::filesystem::create_directories(path.parent_path());
    summary.write(path);
    for (const auto& m : summary.metrics()) std::cerr << "  " << m.name << " = " << m.value << " " << m.units << "\n";
    std::cerr << "fin-fsi " << sub << ": wrote " << path.string() << "\n";
    return summary.pass() ? 0 : 1;
  }
};

