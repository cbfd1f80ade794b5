// Tests of the root drive file (fem/io/root_drive_file.hpp): defaults are the paper's trout,
// f = St U / (A c) unless frequency_hz overrides it, unknown keys and out-of-range values are
// refused naming the key, and on a two-ray mesh the dorsal ray gets eta = +1.
#include <gtest/gtest.h>

#include "fem/errors.hpp"
#include "fem/io/root_drive_file.hpp"

namespace finverse::fem::io {
namespace {

TEST(RootDriveFile, DefaultsFrequencyAndRefusals) {
  const RootDriveSpec d = parse_root_drive(nlohmann::json::object(), "drive.json");
  EXPECT_EQ(d.heave_over_chord, 0.44);
  EXPECT_EQ(d.pitch.edge_deg, 22);
  EXPECT_NEAR(d.frequency(0.1, 0.01), 0.44 * 0.1 / 0.01, 1e-12);
  const RootDriveSpec f = parse_root_drive({{"frequency_hz", 3.5}, {"pitch_phase_deg", -60}}, "drive.json");
  EXPECT_EQ(f.frequency(0.1, 0.01), 3.5);
  EXPECT_EQ(f.pitch.phase_deg, -60);
  try {
    parse_root_drive({{"heave_over_cord", 0.4}}, "drive.json");
    FAIL() << "unknown key accepted";
  } catch (const InvalidInput& e) {
    EXPECT_NE(std::string(e.what()).find("heave_over_cord"), std::string::npos);
  }
  EXPECT_THROW(parse_root_drive({{"strouhal", -1}}, "drive.json"), InvalidInput);
  EXPECT_THROW(parse_root_drive({{"pitch_edge_deg", "22"}}, "drive.json"), InvalidInput);
}

TEST(RootDriveFile, DorsalRayFirstOnAMesh) {
  // Root nodes 0 (z = +1 mm) and 1 (z = -1 mm), a ray leaving each along x (nodes 2, 3).
  stage::Mesh m;
  m.points = NdArray<double>({4, 3}, {0, 0, 0.001, 0, 0, -0.001, 0.002, 0, 0.001, 0.002, 0, -0.001});
  m.root_nodes = NdArray<std::int32_t>({2}, {1, 0});
  m.beam_elements = NdArray<std::int32_t>({2, 2}, {1, 3, 0, 2});
  m.beam_ray = NdArray<std::int32_t>({2}, {7, 4});
  const RootDrive d = make_root_drive(m, RootDriveSpec{}, 2.0, 0.01, "mesh.h5");
  ASSERT_EQ(d.rays().size(), 2u);
  EXPECT_EQ(d.rays()[0].root_index, 1);  // node 0, z = +1 mm: dorsal
  EXPECT_EQ(d.rays()[0].eta, 1.0);
  EXPECT_EQ(d.rays()[1].eta, -1.0);
  EXPECT_NEAR(d.heave(0.625), 0.0044, 1e-15);  // h0 = 0.44 c at sin = 1, after the 0.5 s ramp
}

}  // namespace
}  // namespace finverse::fem::io
