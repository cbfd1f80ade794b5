// The written contract (tools/core/CONTRACTS.md) is the one rendered from the code; regenerate
// it with `fin-contract --markdown > tools/core/CONTRACTS.md` after changing contract_specs.cpp.
#include <gtest/gtest.h>

#include "core/contract.hpp"
#include "test_util.hpp"

TEST(ContractDoc, MarkdownMatchesCode) {
  EXPECT_EQ(finverse::test::slurp(CONTRACTS_MD), finverse::contract::markdown_all())
      << "CONTRACTS.md is stale: run fin-contract --markdown > tools/core/CONTRACTS.md";
}

TEST(ContractDoc, CheckerExecutableValidatesFiles) {
  finverse::test::ScratchDir dir;
  auto m = finverse::test::sample_mesh();
  finverse::stage::write(dir / "mesh.h5", m, finverse::test::test_provenance());
  const std::string exe = FIN_CONTRACT_EXE;
  EXPECT_EQ(std::system((exe + " check " + (dir / "mesh.h5").string() + " > /dev/null").c_str()), 0);
  std::ofstream(dir / "junk.h5") << "junk";
  EXPECT_NE(std::system((exe + " check " + (dir / "junk.h5").string() + " 2> /dev/null").c_str()), 0);
}
