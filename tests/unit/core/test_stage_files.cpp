// Stage files: every contract type round-trips through its typed writer and reader, and every
// kind of contract violation gives a one-line error naming the file and the dataset.
#include <gtest/gtest.h>

#include "core/contract.hpp"
#include "core/error.hpp"
#include "core/stage_files.hpp"
#include "test_util.hpp"

using namespace finverse;
using test::ScratchDir;

namespace {

template <class S>
void expect_round_trip(S original, const std::filesystem::path& path) {
  stage::write(path, original, test::test_provenance());
  S back = stage::read<S>(path);
  // Compare field by field through the same visitor, so a new field cannot be forgotten.
  std::vector<std::string> seen;
  original.fields([&](const char* name, const auto& a) { seen.emplace_back(name); (void)a; });
  std::size_t i = 0;
  auto compare = [&](const char* name, const auto& a) {
    using T = std::decay_t<decltype(a)>;
    bool matched = false;
    back.fields([&](const char* n2, const auto& b) {
      if constexpr (std::is_same_v<T, std::decay_t<decltype(b)>>) {
        if (std::string(name) == n2) {
          matched = true;
          if constexpr (std::is_same_v<T, stage::Strings>) {
            EXPECT_EQ(a, b) << name;
          } else {
            ASSERT_EQ(a.shape, b.shape) << name;
            for (std::size_t k = 0; k < a.size(); ++k) {
              if constexpr (std::is_floating_point_v<typename T::value_type>) {
                if (std::isnan(a.data[k])) {
                  EXPECT_TRUE(std::isnan(b.data[k])) << name << " at " << k;
                  continue;
                }
              }
              ASSERT_EQ(a.data[k], b.data[k]) << name << " at " << k;
            }
          }
        }
      }
    });
    EXPECT_TRUE(matched) << name;
    ++i;
  };
  original.fields(compare);
  EXPECT_EQ(i, seen.size());
  // And the file validates with the stand-alone checker.
  const auto f = h5::File::open_read(path);
  EXPECT_NO_THROW(contract::check(f, contract::get(S::kSchema)));
  EXPECT_EQ(f.attr_string(".", "producer").value().rfind("core_tests finverse", 0), 0u);
  EXPECT_EQ(f.attr_string(".", "config").value(), R"({"case":"unit"})");
}

// Asserts that `fn` throws a single-line finverse::Error that mentions every fragment.
template <class Fn>
void expect_error(Fn fn, const std::vector<std::string>& fragments) {
  try {
    fn();
    FAIL() << "no error thrown";
  } catch (const Error& e) {
    const std::string m = e.what();
    EXPECT_EQ(m.find('\n'), std::string::npos) << m;
    for (const auto& frag : fragments) EXPECT_NE(m.find(frag), std::string::npos) << "'" << frag << "' not in: " << m;
  }
}

}  // namespace

TEST(StageFiles, EveryContractTypeRoundTrips) {
  ScratchDir dir;
  expect_round_trip(test::sample_truth(), dir / "truth.h5");
  expect_round_trip(test::sample_kinematics(), dir / "kinematics.h5");
  expect_round_trip(test::sample_mesh(), dir / "mesh.h5");
  expect_round_trip(test::sample_motion(), dir / "motion.h5");
  expect_round_trip(test::sample_loads(), dir / "loads.h5");
  expect_round_trip(test::sample_materials(), dir / "materials.h5");
  stage::NodalLoads nodal;
  nodal.time = NdArray<double>({2}, {0.0, 0.5});
  nodal.nodal_force = NdArray<double>({2, 3, 3}, 0.25);
  expect_round_trip(nodal, dir / "nodal_loads.h5");
  expect_round_trip(test::sample_fsi(), dir / "fsi.h5");
  EXPECT_EQ(stage::read<stage::Motion>(dir / "motion.h5").period, 0.016);
  EXPECT_EQ(stage::read<stage::Truth>(dir / "truth.h5").effects, R"({"damping": 0.02})");
}

TEST(StageFiles, EveryContractIsCovered) {
  // Each schema in the contract table has a typed struct whose fields are exactly its datasets.
  auto names = [](auto s) {
    std::vector<std::string> n;
    s.fields([&](const char* name, const auto&) { n.emplace_back(name); });
    return n;
  };
  auto spec_names = [](const std::string& schema) {
    std::vector<std::string> n;
    for (const auto& d : contract::get(schema).datasets) n.push_back(d.path);
    return n;
  };
  auto sorted = [](std::vector<std::string> v) { std::sort(v.begin(), v.end()); return v; };
  EXPECT_EQ(sorted(names(stage::Truth{})), sorted(spec_names(stage::Truth::kSchema)));
  EXPECT_EQ(sorted(names(stage::Kinematics{})), sorted(spec_names(stage::Kinematics::kSchema)));
  EXPECT_EQ(sorted(names(stage::Mesh{})), sorted(spec_names(stage::Mesh::kSchema)));
  EXPECT_EQ(sorted(names(stage::Motion{})), sorted(spec_names(stage::Motion::kSchema)));
  EXPECT_EQ(sorted(names(stage::Loads{})), sorted(spec_names(stage::Loads::kSchema)));
  EXPECT_EQ(sorted(names(stage::Materials{})), sorted(spec_names(stage::Materials::kSchema)));
  EXPECT_EQ(sorted(names(stage::NodalLoads{})), sorted(spec_names(stage::NodalLoads::kSchema)));
  EXPECT_EQ(sorted(names(stage::Fsi{})), sorted(spec_names(stage::Fsi::kSchema)));
  // fin-loop's residual.h5 and loop.h5 have their typed structs beside their writer
  // (tools/loop/io/loop_files.cpp), which checks them against these contracts on writing.
  EXPECT_NO_THROW(contract::get("finverse/residual"));
  EXPECT_NO_THROW(contract::get("finverse/loop"));
  EXPECT_EQ(contract::all().size(), 10u);
}

TEST(StageFiles, OptionalDatasetMayBeAbsent) {
  ScratchDir dir;
  auto m = test::sample_motion();
  m.velocity = {};
  m.period.reset();
  stage::write(dir / "motion.h5", m, test::test_provenance());
  const auto back = stage::read<stage::Motion>(dir / "motion.h5");
  EXPECT_TRUE(back.velocity.data.empty());
  EXPECT_FALSE(back.period.has_value());
}

// Files that break the contract in one way each. They are written with the raw wrapper, as a
// foreign or buggy producer would.
class BrokenMotion : public ::testing::Test {
 protected:
  std::filesystem::path write(const std::string& name, const std::function<void(h5::File&)>& body) {
    const auto p = dir / name;
    auto f = h5::File::create(p);
    write_provenance(f, "finverse/motion", 1, test::test_provenance());
    body(f);
    f.commit();
    return p;
  }
  ScratchDir dir;
};

TEST_F(BrokenMotion, MissingDataset) {
  const auto p = write("m.h5", [](h5::File& f) { f.write("time", test::wave({4}), {"s"}); });
  expect_error([&] { stage::read<stage::Motion>(p); }, {p.string(), "/points", "missing dataset"});
}

TEST_F(BrokenMotion, WrongShape) {
  const auto p = write("m.h5", [](h5::File& f) {
    f.write("time", test::wave({4}), {"s"});
    f.write("points", test::wave({5, 30, 3}), {"m"});
  });
  expect_error([&] { stage::read<stage::Motion>(p); }, {p.string(), "/points", "expected shape [nf=4,nv,3]", "[5,30,3]"});
}

TEST_F(BrokenMotion, WrongRank) {
  const auto p = write("m.h5", [](h5::File& f) {
    f.write("time", test::wave({4}), {"s"});
    f.write("points", test::wave({4, 90}), {"m"});
  });
  expect_error([&] { stage::read<stage::Motion>(p); }, {p.string(), "/points", "rank 3"});
}

TEST_F(BrokenMotion, NaN) {
  const auto p = write("m.h5", [](h5::File& f) {
    f.write("time", test::wave({4}), {"s"});
    auto pts = test::wave({4, 30, 3});
    pts(2, 7, 1) = std::nan("");
    f.write("points", pts, {"m"});
  });
  expect_error([&] { stage::read<stage::Motion>(p); }, {p.string(), "/points", "non-finite", "at [2,7,1]"});
}

TEST_F(BrokenMotion, WrongUnits) {
  const auto p = write("m.h5", [](h5::File& f) {
    f.write("time", test::wave({4}), {"ms"});
    f.write("points", test::wave({4, 30, 3}), {"m"});
  });
  expect_error([&] { stage::read<stage::Motion>(p); }, {p.string(), "/time", "units are 'ms', expected 's'"});
}

TEST_F(BrokenMotion, WrongDtype) {
  const auto p = write("m.h5", [](h5::File& f) {
    f.write("time", test::counting({4}, 9), {"s"});
    f.write("points", test::wave({4, 30, 3}), {"m"});
  });
  expect_error([&] { stage::read<stage::Motion>(p); }, {p.string(), "/time", "expected dtype float64, found int32"});
}

TEST_F(BrokenMotion, WrongSchemaVersion) {
  const auto p = write("m.h5", [](h5::File& f) {
    f.set_attr(".", "schema_version", std::int64_t{2});
    f.write("time", test::wave({4}), {"s"});
    f.write("points", test::wave({4, 30, 3}), {"m"});
  });
  expect_error([&] { stage::read<stage::Motion>(p); }, {p.string(), "schema_version 2", "reads version 1"});
}

TEST_F(BrokenMotion, WrongSchema) {
  ScratchDir d2;
  stage::write(d2 / "mesh.h5", *std::make_unique<stage::Mesh>(test::sample_mesh()), test::test_provenance());
  expect_error([&] { stage::read<stage::Motion>(d2 / "mesh.h5"); }, {"mesh.h5", "schema is 'finverse/mesh'", "finverse/motion"});
}

TEST_F(BrokenMotion, TruncatedFile) {
  auto m = test::sample_motion(50, 400);
  stage::write(dir / "full.h5", m, test::test_provenance());
  std::filesystem::copy_file(dir / "full.h5", dir / "cut.h5");
  std::filesystem::resize_file(dir / "cut.h5", std::filesystem::file_size(dir / "full.h5") / 2);
  expect_error([&] { stage::read<stage::Motion>(dir / "cut.h5"); }, {(dir / "cut.h5").string()});
}

TEST(StageFiles, WriterRefusesWhatReadersWouldRejectAndLeavesNoFile) {
  ScratchDir dir;
  auto m = test::sample_motion();
  m.points(1, 2, 0) = std::numeric_limits<double>::infinity();
  expect_error([&] { stage::write(dir / "m.h5", m, test::test_provenance()); }, {"m.h5", "/points", "non-finite"});
  EXPECT_FALSE(std::filesystem::exists(dir / "m.h5"));
  EXPECT_FALSE(std::filesystem::exists(dir / "m.h5.tmp"));

  auto l = test::sample_loads(6, 30, 40);
  l.nodal_force = test::wave({6, 31, 3});  // nv disagrees with nothing yet, but force_total is fine...
  l.pressure_jump = test::wave({7, 40});   // ...and nt disagrees with time
  expect_error([&] { stage::write(dir / "l.h5", l, test::test_provenance()); }, {"l.h5", "/pressure_jump", "[nt=6,ntri]"});
  EXPECT_FALSE(std::filesystem::exists(dir / "l.h5"));

  auto l2 = test::sample_loads();
  l2.rho.reset();
  expect_error([&] { stage::write(dir / "l2.h5", l2, test::test_provenance()); }, {"l2.h5", "rho"});
  EXPECT_FALSE(std::filesystem::exists(dir / "l2.h5"));
}

TEST(StageFiles, InputsAreHashed) {
  ScratchDir dir;
  std::ofstream(dir / "in.txt") << "abc";
  auto m = test::sample_motion();
  stage::write(dir / "m.h5", m, Provenance{"core_tests", {}, {dir / "in.txt"}});
  const auto inputs = nlohmann::json::parse(h5::File::open_read(dir / "m.h5").attr_string(".", "inputs").value());
  ASSERT_EQ(inputs.size(), 1u);
  EXPECT_EQ(inputs[0]["sha256"], "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad");
}
