// Stages that disagree (issue 33 "Bad input", core/stage_identity.hpp): a product records the
// content identity of its inputs, and check_made_from refuses, in one line naming both files and
// what differs, a mesh from another template, loads from another motion and materials for another
// mesh; the same numbers rewritten (other attributes) and a file derived from the recorded input
// are accepted.
#include <gtest/gtest.h>

#include "core/error.hpp"
#include "core/hdf5_file.hpp"
#include "core/provenance.hpp"
#include "core/stage_identity.hpp"
#include "test_util.hpp"

using namespace finverse;
using test::ScratchDir;

namespace {

// A stand-in stage file: schema, `points` [n,3] scaled by `scale`, and the given inputs hashed.
std::filesystem::path stage_file(const std::filesystem::path& p, const std::string& schema, std::size_t n, double scale,
                                 std::vector<std::filesystem::path> inputs = {}, const std::string& tool = "test") {
  auto f = h5::File::create(p);
  NdArray<double> pts({n, 3});
  for (std::size_t i = 0; i < pts.size(); ++i) pts.data[i] = scale * double(i);
  f.write("points", pts);
  write_provenance(f, schema, 1, Provenance{tool, nlohmann::json::object(), std::move(inputs)});
  f.commit();
  return p;
}

std::string message_of(const std::filesystem::path& product, const std::filesystem::path& input) {
  try {
    check_made_from(product, input);
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

}  // namespace

TEST(StageIdentity, AMotionOnAnotherTemplatesMeshIsRefusedNamingBothFiles) {
  ScratchDir dir;
  const auto mesh = stage_file(dir / "mesh.h5", "finverse/mesh", 10, 1.0);
  const auto motion = stage_file(dir / "motion.h5", "finverse/motion", 10, 2.0, {mesh});
  EXPECT_EQ(message_of(motion, mesh), "");
  const auto other = stage_file(dir / "other_mesh.h5", "finverse/mesh", 12, 1.0);
  const auto msg = message_of(motion, other);
  EXPECT_NE(msg.find(motion.string()), std::string::npos) << msg;
  EXPECT_NE(msg.find(other.string()), std::string::npos) << msg;
  EXPECT_NE(msg.find("points [10,3] there, points [12,3] here"), std::string::npos) << msg;
}

TEST(StageIdentity, LoadsFromAnotherMotionAndMaterialsForAnotherMeshAreRefused) {
  ScratchDir dir;
  const auto mesh = stage_file(dir / "mesh.h5", "finverse/mesh", 10, 1.0);
  const auto motion = stage_file(dir / "motion.h5", "finverse/motion", 10, 2.0, {mesh});
  const auto loads = stage_file(dir / "loads.h5", "finverse/loads", 10, 3.0, {mesh, motion});
  const auto materials = stage_file(dir / "materials.h5", "finverse/materials", 1, 1.0, {mesh, motion, loads});
  for (const auto& [p, i] : {std::pair{loads, mesh}, {loads, motion}, {materials, mesh}, {materials, loads}})
    EXPECT_EQ(message_of(p, i), "") << p << " " << i;
  // Same shapes, other values: a motion of another run.
  const auto motion2 = stage_file(dir / "motion2.h5", "finverse/motion", 10, 2.5, {mesh});
  EXPECT_NE(message_of(loads, motion2).find("same shapes (points [10,3]), other values"), std::string::npos);
  const auto mesh2 = stage_file(dir / "mesh2.h5", "finverse/mesh", 11, 1.0);
  EXPECT_NE(message_of(materials, mesh2).find("was made from another finverse/mesh"), std::string::npos);
}

TEST(StageIdentity, RewrittenNumbersAndDerivedFilesAreTheSameLineage) {
  ScratchDir dir;
  const auto mesh = stage_file(dir / "mesh.h5", "finverse/mesh", 10, 1.0);
  const auto motion = stage_file(dir / "motion.h5", "finverse/motion", 10, 2.0, {mesh});
  const auto loads = stage_file(dir / "loads.h5", "finverse/loads", 10, 3.0, {mesh, motion});
  // Another producer string (a rebuilt tool), the same datasets: the same identity.
  const auto again = stage_file(dir / "motion_again.h5", "finverse/motion", 10, 2.0, {mesh}, "rebuilt");
  EXPECT_EQ(message_of(loads, again), "");
  // A twin's motion computed from the case's motion records it: accepted with the case's loads.
  const auto twin = stage_file(dir / "twin_motion.h5", "finverse/motion", 10, 7.0, {mesh, loads, motion});
  EXPECT_EQ(message_of(loads, twin), "");
  // A product that records no input of that schema is not checked.
  const auto bare = stage_file(dir / "bare.h5", "finverse/loads", 10, 3.0);
  EXPECT_EQ(message_of(bare, motion), "");
}
