// The HDF5 specimen file (io/specimen_file.hpp, docs/specimen_file.md): round trip, errors
// that name the file, and atomic writing.
#include <gtest/gtest.h>

#include <H5Cpp.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <string>

#include "core/input_error.hpp"
#include "core/rng.hpp"
#include "io/specimen_file.hpp"

#include "scratch_dir.hpp"

namespace fs = std::filesystem;
using cdem::Specimen;

namespace {

fs::path scratch_dir(const std::string& test) {
  return cdem::test::scratch_dir("specimen_file", test);
}

// Three mortar discs, two clumps (a triangle and a square) with two pebbles each, one pebble
// dropped from contact detection. Values chosen so that no field equals its default.
Specimen synthetic_specimen() {
  Specimen s;
  s.container = {cdem::ContainerShape::Rectangle, 0.1, 0.2};
  s.x = {0.010, 0.020, 0.030, 0.041, 0.043, 0.070, 0.072};
  s.y = {0.011, 0.012, 0.013, 0.050, 0.052, 0.150, 0.151};
  s.r = {4.1e-4, 5.2e-4, 3.3e-4, 4.4e-4, 6.5e-4, 2.6e-4, 5.7e-4};
  s.clump = {-1, -1, -1, 0, 0, 1, 1};
  s.contact_active = {1, 1, 1, 1, 0, 1, 1};
  cdem::Clump tri;
  tri.vertices = {{0.035, 0.045}, {0.050, 0.045}, {0.040, 0.060}};
  tri.centroid = {0.125 / 3, 0.150 / 3};
  tri.mass = 0.2981;
  tri.inertia = 1.234e-6;
  tri.equivalent_diameter = 0.0138;
  tri.bin = 2;
  cdem::Clump sq;
  sq.vertices = {{0.065, 0.145}, {0.077, 0.145}, {0.077, 0.157}, {0.065, 0.157}};
  sq.centroid = {0.071, 0.151};
  sq.mass = 0.3816;
  sq.inertia = 9.158e-6;
  sq.equivalent_diameter = 0.01354;
  sq.bin = 4;
  s.clumps = {tri, sq};
  s.mortar_density = 2100;
  s.aggregate_density = 2700;
  s.attributes = {{"seed", "42"}, {"porosity_reached", "0.1234"}, {"generator", "mesogen test"}};
  return s;
}

void expect_equal(const Specimen& a, const Specimen& b) {
  EXPECT_EQ(a.container.shape, b.container.shape);
  EXPECT_EQ(a.container.width, b.container.width);
  EXPECT_EQ(a.container.height, b.container.height);
  EXPECT_EQ(a.x, b.x);
  EXPECT_EQ(a.y, b.y);
  EXPECT_EQ(a.r, b.r);
  EXPECT_EQ(a.clump, b.clump);
  EXPECT_EQ(a.contact_active, b.contact_active);
  EXPECT_EQ(a.mortar_density, b.mortar_density);
  EXPECT_EQ(a.aggregate_density, b.aggregate_density);
  EXPECT_EQ(a.attributes, b.attributes);
  ASSERT_EQ(a.clumps.size(), b.clumps.size());
  for (std::size_t k = 0; k < a.clumps.size(); ++k) {
    const cdem::Clump& p = a.clumps[k];
    const cdem::Clump& q = b.clumps[k];
    ASSERT_EQ(p.vertices.size(), q.vertices.size()) << "clump " << k;
    for (std::size_t v = 0; v < p.vertices.size(); ++v) EXPECT_EQ(p.vertices[v], q.vertices[v]);
    EXPECT_EQ(p.centroid, q.centroid);
    EXPECT_EQ(p.mass, q.mass);
    EXPECT_EQ(p.inertia, q.inertia);
    EXPECT_EQ(p.equivalent_diameter, q.equivalent_diameter);
    EXPECT_EQ(p.bin, q.bin);
  }
}

// Runs f, expects an InputError whose message names `file` and contains `fragment`.
template <class F>
void expect_input_error(F&& f, const fs::path& file, const std::string& fragment) {
  try {
    f();
    ADD_FAILURE() << "expected cdem::InputError for " << file;
  } catch (const cdem::InputError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find(file.string()), std::string::npos) << what;
    EXPECT_NE(what.find(fragment), std::string::npos) << what;
    EXPECT_EQ(e.file(), file.string());
  }
}

bool only_entry_is(const fs::path& dir, const fs::path& name) {
  std::size_t n = 0;
  for (const auto& entry : fs::directory_iterator(dir)) {
    ++n;
    if (entry.path().filename() != name) return false;
  }
  return n == 1;
}

}  // namespace

TEST(SpecimenFile, RoundTripRectangle) {
  const fs::path file = scratch_dir("round_trip_rect") / "specimen.h5";
  const Specimen s = synthetic_specimen();
  cdem::write_specimen(s, file);
  expect_equal(cdem::read_specimen(file), s);
  EXPECT_TRUE(only_entry_is(file.parent_path(), "specimen.h5"));  // no temporary left
}

TEST(SpecimenFile, RoundTripDiscContainerAndRandomValues) {
  const fs::path file = scratch_dir("round_trip_disc") / "brazilian.h5";
  Specimen s = synthetic_specimen();
  s.container = {cdem::ContainerShape::Disc, 0.05, 0.05};
  // Full-precision doubles: the file must keep every bit.
  cdem::Rng rng(17);
  // Positions inside the 25 mm radius of the disc mould (the reader refuses discs and clumps
  // outside it): a random point of the 20 mm disc about the centre.
  for (std::size_t i = 0; i < s.x.size(); ++i) {
    const double rho = 0.02 * std::sqrt(rng.uniform()),
                 angle = rng.uniform(0, 2 * std::numbers::pi);
    s.x[i] = 0.025 + rho * std::cos(angle);
    s.y[i] = 0.025 + rho * std::sin(angle);
  }
  for (auto& clump : s.clumps) clump.centroid = {rng.uniform(0.02, 0.03), rng.uniform(0.02, 0.03)};
  for (double& v : s.r) v = rng.uniform(2e-4, 5e-4);
  s.clumps[1].inertia = rng.uniform();
  cdem::write_specimen(s, file);
  expect_equal(cdem::read_specimen(file), s);
}

TEST(SpecimenFile, RoundTripNoClumpsNoDiscs) {
  const fs::path file = scratch_dir("round_trip_empty") / "empty.h5";
  Specimen s;
  s.container = {cdem::ContainerShape::Rectangle, 0.1, 0.2};
  cdem::write_specimen(s, file);
  expect_equal(cdem::read_specimen(file), s);
}

TEST(SpecimenFile, MissingFileNamesTheFile) {
  const fs::path file = scratch_dir("missing") / "no_such_specimen.h5";
  expect_input_error([&] { cdem::read_specimen(file); }, file, "not found");
}

TEST(SpecimenFile, RandomBytesAreNotASpecimen) {
  const fs::path file = scratch_dir("random_bytes") / "noise.h5";
  {
    cdem::Rng rng(1);
    std::ofstream f(file, std::ios::binary);
    for (int i = 0; i < 4096; ++i) f.put(static_cast<char>(rng.integer(0, 255)));
  }
  expect_input_error([&] { cdem::read_specimen(file); }, file, "not an HDF5 file");
}

TEST(SpecimenFile, MissingDatasetIsNamed) {
  const fs::path file = scratch_dir("missing_dataset") / "specimen.h5";
  cdem::write_specimen(synthetic_specimen(), file);
  {
    H5::H5File f(file.string(), H5F_ACC_RDWR);
    f.unlink("/discs/r");
  }
  expect_input_error([&] { cdem::read_specimen(file); }, file, "discs/r");
}

TEST(SpecimenFile, MissingGroupIsNamed) {
  const fs::path file = scratch_dir("missing_group") / "specimen.h5";
  cdem::write_specimen(synthetic_specimen(), file);
  {
    H5::H5File f(file.string(), H5F_ACC_RDWR);
    f.unlink("/clumps");
  }
  expect_input_error([&] { cdem::read_specimen(file); }, file, "clumps");
}

TEST(SpecimenFile, HdfFileOfAnotherKind) {
  const fs::path file = scratch_dir("other_hdf5") / "other.h5";
  {
    H5::H5File f(file.string(), H5F_ACC_TRUNC);
    f.createGroup("data");
  }
  expect_input_error([&] { cdem::read_specimen(file); }, file, "not a cdem specimen");
}

TEST(SpecimenFile, FailedWriteLeavesNoFile) {
  const fs::path dir = scratch_dir("failed_write");
  const fs::path file = dir / "specimen.h5";
  // Arrays of different lengths: refused before anything is written.
  Specimen ragged = synthetic_specimen();
  ragged.r.pop_back();
  EXPECT_THROW(cdem::write_specimen(ragged, file), std::invalid_argument);
  EXPECT_FALSE(fs::exists(file));
  // An attribute that collides with the file's own (HDF5 would fail half-way through the
  // file): refused up front, naming the attribute.
  Specimen clash = synthetic_specimen();
  clash.attributes["format"] = "mine";
  try {
    cdem::write_specimen(clash, file);
    ADD_FAILURE() << "expected std::invalid_argument for a reserved attribute name";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("'format'"), std::string::npos) << e.what();
  }
  EXPECT_FALSE(fs::exists(file));
  EXPECT_TRUE(fs::is_empty(dir)) << "a temporary file was left behind";
  // A failed write does not disturb a previous good file.
  const Specimen good = synthetic_specimen();
  cdem::write_specimen(good, file);
  Specimen bad_clump = synthetic_specimen();
  bad_clump.clump[0] = 7;
  EXPECT_THROW(cdem::write_specimen(bad_clump, file), std::invalid_argument);
  expect_equal(cdem::read_specimen(file), good);
  EXPECT_TRUE(only_entry_is(dir, "specimen.h5"));
}

// An I/O failure (here: the parent "directory" is a regular file; root ignores permissions, so
// a read-only directory would not do) is a RunError naming the target, not a raw H5::Exception
// that no caller of std::exception would catch.
TEST(SpecimenFile, UnwritableTargetIsARunError) {
  const fs::path dir = scratch_dir("unwritable");
  const fs::path not_a_dir = dir / "plain_file";
  std::ofstream(not_a_dir) << "x";
  const fs::path file = not_a_dir / "specimen.h5";
  try {
    cdem::write_specimen(synthetic_specimen(), file);
    ADD_FAILURE() << "expected a write failure";
  } catch (const cdem::RunError& e) {
    EXPECT_NE(std::string(e.what()).find(file.string()), std::string::npos) << e.what();
  }
  EXPECT_FALSE(fs::exists(file));
}
