// The HDF5 wrapper: datasets of every dtype and rank, strings, attributes, nested groups,
// compression, byte-identical rewrites and one-line errors for unreadable files.
#include <gtest/gtest.h>

#include "core/error.hpp"
#include "core/hdf5_file.hpp"
#include "test_util.hpp"

using namespace finverse;
using test::ScratchDir;

namespace {
void write_sample(const std::filesystem::path& p) {
  auto f = h5::File::create(p);
  f.write("a/b/values", test::wave({300, 20, 3}), {"m", true});
  f.write("ints", test::counting({7}, 5));
  f.write("bytes", NdArray<std::uint8_t>({2, 2}, {1, 2, 3, 4}));
  f.write("big", NdArray<std::int64_t>({3}, {1, -2, std::int64_t(1) << 40}));
  f.write("names", std::vector<std::string>{"alpha", "", "γάμμα"});
  f.write_scalar("scalar", 2.5, "s");
  f.set_attr(".", "schema", std::string("finverse/test"));
  f.set_attr(".", "version", std::int64_t{3});
  f.set_attr("a/b/values", "T", 0.25);
  f.commit();
}
}  // namespace

TEST(Hdf5File, RoundTripsEveryType) {
  ScratchDir dir;
  write_sample(dir / "s.h5");
  const auto f = h5::File::open_read(dir / "s.h5");
  EXPECT_EQ(f.read_f64("a/b/values"), test::wave({300, 20, 3}));
  EXPECT_EQ(f.info("a/b/values").dtype, h5::DType::f64);
  EXPECT_EQ(f.read_i32("ints"), test::counting({7}, 5));
  EXPECT_EQ(f.read_u8("bytes").data, (std::vector<std::uint8_t>{1, 2, 3, 4}));
  EXPECT_EQ(f.read_i64("big").data[2], std::int64_t(1) << 40);
  EXPECT_EQ(f.read_strings("names"), (std::vector<std::string>{"alpha", "", "γάμμα"}));
  EXPECT_EQ(f.read_scalar("scalar"), 2.5);
  EXPECT_TRUE(f.info("scalar").shape.empty());
  EXPECT_EQ(f.attr_string("scalar", "units"), "s");
  EXPECT_EQ(f.attr_string("a/b/values", "units"), "m");
  EXPECT_EQ(f.attr_double("a/b/values", "T"), 0.25);
  EXPECT_EQ(f.attr_int(".", "version"), 3);
  EXPECT_EQ(f.attr_string(".", "schema"), "finverse/test");
  EXPECT_FALSE(f.attr_string(".", "nothing").has_value());
  EXPECT_EQ(f.children(), (std::vector<std::string>{"a", "big", "bytes", "ints", "names", "scalar"}));
  EXPECT_TRUE(f.is_group("a/b"));
  EXPECT_FALSE(f.exists("a/c"));
}

TEST(Hdf5File, CompressionShrinksRegularData) {
  ScratchDir dir;
  NdArray<double> zeros({200, 100, 3}, 0.0);
  {
    auto f = h5::File::create(dir / "z.h5");
    f.write("z", zeros, {"m", true});
    f.commit();
  }
  EXPECT_LT(std::filesystem::file_size(dir / "z.h5"), 200u * 100 * 3 * 8 / 20);
  EXPECT_EQ(h5::File::open_read(dir / "z.h5").read_f64("z"), zeros);
}

TEST(Hdf5File, IdenticalWritesAreByteIdentical) {
  ScratchDir dir;
  write_sample(dir / "one.h5");
  write_sample(dir / "two.h5");
  EXPECT_EQ(test::slurp(dir / "one.h5"), test::slurp(dir / "two.h5"));
}

TEST(Hdf5File, UnreadableFilesGiveOneLineErrors) {
  ScratchDir dir;
  std::ofstream(dir / "text.h5") << "not hdf5\n";
  for (const auto& p : {dir / "missing.h5", dir / "text.h5"}) {
    try {
      h5::File::open_read(p);
      FAIL() << "no error for " << p;
    } catch (const Error& e) {
      const std::string m = e.what();
      EXPECT_NE(m.find(p.string()), std::string::npos) << m;
      EXPECT_EQ(m.find('\n'), std::string::npos) << m;
    }
  }
}

TEST(Hdf5File, ReadingWrongKindNamesTheDataset) {
  ScratchDir dir;
  write_sample(dir / "s.h5");
  const auto f = h5::File::open_read(dir / "s.h5");
  try {
    f.read_f64("names");
    FAIL();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("/names"), std::string::npos) << e.what();
  }
  EXPECT_THROW(f.read_f64("nope"), Error);
}
