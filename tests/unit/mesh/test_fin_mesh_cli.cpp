// fin-mesh end to end on bad input: a template without rays and a self-intersecting planform end
// with exit code 2 and one line naming the file and the cause, leaving no mesh.h5 behind.
#include <gtest/gtest.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>

#include "mesh/fin_template.hpp"
#include "../scratch_dir.hpp"

using namespace finverse::mesh;
namespace test = finverse::test;
namespace fs = std::filesystem;

namespace {

struct Result {
  int code;
  std::string err;
};

Result run(const std::string& args) {
  const std::string cmd = std::string(FIN_MESH_EXE) + " " + args + " --log-level error 2>&1";
  FILE* p = popen(cmd.c_str(), "r");
  std::string out;
  std::array<char, 512> buf{};
  while (fgets(buf.data(), buf.size(), p)) out += buf.data();
  const int status = pclose(p);
  return {WEXITSTATUS(status), out};
}

}  // namespace

TEST(FinMeshCli, TemplateWithoutRays) {
  const test::ScratchDir scratch;
  const fs::path& d = scratch.path();
  auto j = to_json(make_caudal_fin({}));
  j["rays"] = nlohmann::json::array();
  std::ofstream(d / "fin.json") << j.dump();
  const auto r = run("--template " + (d / "fin.json").string() + " --mesh " + (d / "mesh.h5").string());
  EXPECT_EQ(r.code, 2) << r.err;
  EXPECT_NE(r.err.find("fin.json: has 0 rays"), std::string::npos) << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  EXPECT_FALSE(fs::exists(d / "mesh.h5"));
}

TEST(FinMeshCli, SelfIntersectingPlanform) {
  const test::ScratchDir scratch;
  const fs::path& d = scratch.path();
  auto t = make_caudal_fin({});
  std::swap(t.rays[3].points.back(), t.rays[15].points.back());
  std::ofstream(d / "fin.json") << to_json(t).dump();
  const auto r = run("--template " + (d / "fin.json").string() + " --mesh " + (d / "mesh.h5").string());
  EXPECT_EQ(r.code, 2) << r.err;
  EXPECT_NE(r.err.find("self-intersects"), std::string::npos) << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  EXPECT_FALSE(fs::exists(d / "mesh.h5"));
}

TEST(FinMeshCli, WritesValidMeshFiles) {
  const test::ScratchDir scratch;
  const fs::path& d = scratch.path();
  const auto r = run("--mesh " + (d / "mesh.h5").string() + " --vtu " + (d / "mesh.vtu").string());
  EXPECT_EQ(r.code, 0) << r.err;
  EXPECT_TRUE(fs::exists(d / "mesh.h5"));
  EXPECT_TRUE(fs::exists(d / "mesh.vtu"));
  EXPECT_TRUE(fs::exists(d / "mesh_ibm.pvd"));
}
