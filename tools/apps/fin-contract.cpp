// fin-contract: the stage-file contracts, as documentation or as a checker.
//
//   fin-contract --markdown                 print CONTRACTS.md (the written contract)
//   fin-contract --list                     schema names, versions and conventional file names
//   fin-contract check results/mesh.h5      validate a file against the schema it declares
//
// Exit status: 0 valid, 2 invalid or unreadable (the one-line error names file and dataset).
#include <cstdio>
#include <filesystem>

#include "core/cli.hpp"
#include "core/contract.hpp"
#include "core/error.hpp"
#include "core/hdf5_file.hpp"

int main(int argc, char** argv) {
  using namespace finverse;
  CLI::App app{"fin-contract: print or check the stage-file contracts"};
  cli::Standard standard(app, "fin-contract");
  bool markdown = false, list = false;
  app.add_flag("--markdown", markdown, "print the contracts as Markdown");
  app.add_flag("--list", list, "list the schemas");
  auto* check = app.add_subcommand("check", "validate files against the schema they declare");
  std::vector<std::filesystem::path> files;
  check->add_option("files", files, "HDF5 stage files")->required();
  standard.log_level = "warn";

  return cli::run(app, standard, argc, argv, [&]() -> int {
    if (markdown) std::fputs(contract::markdown_all().c_str(), stdout);
    if (list)
      for (const auto& s : contract::all())
        std::printf("%-22s v%d  %-16s %s\n", s.schema.c_str(), s.version, s.file_name.c_str(), s.writer.c_str());
    for (const auto& f : files) {
      const auto file = h5::File::open_read(f);
      const auto schema = file.attr_string(".", "schema");
      if (!schema) throw Error(f.string() + ": missing root attribute 'schema'");
      const auto dims = contract::check(file, contract::get(*schema));
      std::string d;
      for (const auto& [k, v] : dims) d += " " + k + "=" + std::to_string(v);
      std::printf("%s: valid %s v%d:%s\n", f.c_str(), schema->c_str(), contract::get(*schema).version, d.c_str());
    }
    if (!markdown && !list && files.empty()) std::fputs(app.help().c_str(), stdout);
    return kExitOk;
  });
}
