// The smooth joints in the result file (docs/result_file.md "/joints"): a jointed block run to
// failure with snapshots, its file read back and checked against the run. The counts are the
// run's own bookkeeping, cross-checked by relations that hold whatever the numbers: every
// joint's pair crosses a line of its set, a joint breaks once and logs one crack, the joints
// still bonded are the bonded ones installed less the broken ones.
#include <H5Cpp.h>

#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "io/hdf5_write.hpp"
#include "lab/lab_test.hpp"
#include "lab/result_file.hpp"
#include "lab_test_fixtures.hpp"

namespace {

namespace fs = std::filesystem;
using namespace cdem::dem;
using namespace cdem::lab;
using cdem::test::scratch_dir;

template <class T>
std::vector<T> read(const H5::Group& g, const std::string& name) {
  H5::DataSet ds = g.openDataSet(name);
  H5::DataSpace space = ds.getSpace();
  hsize_t dims[2] = {0, 1};
  space.getSimpleExtentDims(dims);
  std::vector<T> v(
      static_cast<std::size_t>(dims[0] * (space.getSimpleExtentNdims() == 2 ? dims[1] : 1)));
  if (!v.empty()) ds.read(v.data(), cdem::hdf5::type_of<T>());
  return v;
}

long read_long(const H5::Group& g, const std::string& name) {
  long v = -1;
  g.openAttribute(name).read(H5::PredType::NATIVE_LONG, &v);
  return v;
}

// A 10 x 20 mm mortar block (bonds ten times C30, so it fails on its joints) with a family of
// dip 45 degrees, spacing 6 mm (lines through the centre and 6 mm either side), bonded, and
// one horizontal frictional segment across its upper part.
TEST(LabJointRecord, ResultFileListsTheJointSetsAndEveryJointsState) {
  const fs::path dir = scratch_dir("test_lab_joint_record", "block");
  const cdem::Specimen& specimen = cdem::test::small_rectangle_specimen();
  const std::string test =
      "[test]\ntype = \"uniaxial\"\nhistory_interval = 20\nmax_steps = 400000\n"
      "snapshot_interval = 2000\n"
      "[[test.joints]]\ndip_deg = 45\nspacing_mm = 6\n"
      "sj_normal_stiffness_GPa_m = 100\nsj_shear_stiffness_GPa_m = 69\n"
      "sj_tensile_strength_MPa = 2\nsj_cohesion_MPa = 2\nsj_friction_angle_deg = 15\n"
      "sj_friction = 0.268\n"
      "[[test.joints]]\npoints_mm = [[-1, 16], [11, 16]]\n"
      "sj_normal_stiffness_GPa_m = 100\nsj_shear_stiffness_GPa_m = 69\nsj_friction = 0.5\n"
      "sj_bonded = false\n";
  const LabTestInput in =
      cdem::test::lab_test_input(dir, specimen, test, cdem::test::c30_materials(1, 10));
  ResultFile file(dir / "result.h5", in);
  LabTestHooks hooks;
  hooks.snapshot = [&](const World& w, long step, double time) { file.snapshot(w, step, time); };
  const LabTestResult r = run_lab_test(specimen, in, hooks);
  file.commit(r);
  ASSERT_EQ(r.joints.contacts.size(), 2u);

  H5::H5File f((dir / "result.h5").string(), H5F_ACC_RDONLY);
  const H5::Group g = f.openGroup("joints");
  EXPECT_EQ(read_long(g, "sets"), 2);

  // The sets as given.
  EXPECT_EQ(read<std::int32_t>(g, "family"), (std::vector<std::int32_t>{1, 0}));
  EXPECT_DOUBLE_EQ(read<double>(g, "dip_deg")[0], 45);
  EXPECT_DOUBLE_EQ(read<double>(g, "spacing")[0], 6e-3);
  const std::vector<double> segment = read<double>(g, "segment");
  ASSERT_EQ(segment.size(), 8u);
  EXPECT_DOUBLE_EQ(segment[4], -1e-3);
  EXPECT_DOUBLE_EQ(segment[5], 16e-3);
  EXPECT_DOUBLE_EQ(segment[6], 11e-3);
  EXPECT_EQ(read<std::int32_t>(g, "installed_bonded"), (std::vector<std::int32_t>{1, 0}));
  EXPECT_DOUBLE_EQ(read<double>(g, "normal_stiffness")[1], 100e9);
  EXPECT_DOUBLE_EQ(read<double>(g, "friction")[1], 0.5);

  // The lines, cut to the specimen: the family's fall at 45 degrees, the segment is horizontal
  // at y = 16 mm; each end point on the specimen's extent.
  const std::vector<double> xy = read<double>(g, "line_xy");
  const std::vector<std::int32_t> line_set = read<std::int32_t>(g, "line_set");
  ASSERT_EQ(xy.size(), 4 * line_set.size());
  long family_lines = 0, segment_lines = 0;
  for (std::size_t l = 0; l < line_set.size(); ++l) {
    const double ax = xy[4 * l], ay = xy[4 * l + 1], bx = xy[4 * l + 2], by = xy[4 * l + 3];
    if (line_set[l] == 0) {
      ++family_lines;
      EXPECT_NEAR((by - ay) / (bx - ax), -1.0, 1e-9);
    } else {
      ++segment_lines;
      EXPECT_DOUBLE_EQ(ay, 16e-3);
      EXPECT_DOUBLE_EQ(by, 16e-3);
      EXPECT_LT(bx - ax, 11e-3);  // cut to the block, about 10 mm wide
    }
  }
  // Lines through the centre and +-6 mm along the normal: the block's corners are
  // (5 + 10) / sqrt(2) = 10.6 mm from the centre's line along nj, so all three cross it.
  EXPECT_EQ(family_lines, 3);
  EXPECT_EQ(segment_lines, 1);

  // Every joint: the counts per set and touching/open as installed.
  const std::vector<std::int32_t> pairs = read<std::int32_t>(g, "pairs");
  const std::vector<std::int32_t> set = read<std::int32_t>(g, "set");
  const std::vector<std::uint8_t> touching = read<std::uint8_t>(g, "touching");
  const std::vector<std::uint8_t> bonded = read<std::uint8_t>(g, "bonded");
  const std::vector<std::int32_t> mode = read<std::int32_t>(g, "mode");
  const std::vector<double> failure_time = read<double>(g, "failure_time");
  const std::vector<double> normal_force = read<double>(g, "normal_force");
  const std::size_t n = set.size();
  ASSERT_EQ(pairs.size(), 2 * n);
  ASSERT_EQ(touching.size(), n);
  EXPECT_EQ(static_cast<long>(n), read_long(g, "joints"));
  const std::vector<std::int64_t> contacts = read<std::int64_t>(g, "contacts");
  const std::vector<std::int64_t> open = read<std::int64_t>(g, "open_pairs");
  for (std::size_t s = 0; s < 2; ++s) {
    EXPECT_EQ(contacts[s], r.joints.contacts[s]);
    EXPECT_EQ(open[s], r.joints.open[s]);
    long in_set = 0, touching_in_set = 0;
    for (std::size_t e = 0; e < n; ++e)
      if (set[e] == static_cast<std::int32_t>(s)) {
        ++in_set;
        touching_in_set += touching[e];
      }
    EXPECT_EQ(touching_in_set, contacts[s]) << "set " << s;
    EXPECT_EQ(in_set, contacts[s] + open[s]) << "set " << s;
  }
  EXPECT_GT(contacts[0], 10);
  EXPECT_GT(contacts[1], 5);

  // Each joint's pair crosses a line of its set (disc centres at the first snapshot, the start
  // of loading: the joints were installed on that configuration).
  const std::vector<double> disc_xy = read<double>(f.openGroup("snapshots/000000"), "xy");
  for (std::size_t e = 0; e < n; ++e) {
    const auto i = static_cast<std::size_t>(pairs[2 * e]);
    const auto j = static_cast<std::size_t>(pairs[2 * e + 1]);
    bool crossed = false;
    for (std::size_t l = 0; l < line_set.size(); ++l)
      crossed = crossed ||
                (line_set[l] == set[e] &&
                 crosses({xy[4 * l], xy[4 * l + 1], xy[4 * l + 2], xy[4 * l + 3]}, disc_xy[2 * i],
                         disc_xy[2 * i + 1], disc_xy[2 * j], disc_xy[2 * j + 1]));
    EXPECT_TRUE(crossed) << "joint " << e;
  }

  // States at the end. A joint breaks once and logs one crack of kind SmoothJoint; only the
  // bonded set's joint contacts were bonded, so the bonded ones left are those less the broken.
  long joint_cracks = 0, broken = 0, bonded_now = 0;
  for (const Crack& c : r.cracks) joint_cracks += c.bond == BondKind::SmoothJoint;
  for (std::size_t e = 0; e < n; ++e) {
    broken += mode[e] != 0;
    bonded_now += bonded[e];
    if (mode[e] != 0) {
      EXPECT_EQ(bonded[e], 0) << "joint " << e;
      EXPECT_EQ(set[e], 0) << "joint " << e;  // the frictional set has no bond to break
      EXPECT_GE(failure_time[e], 0);
      EXPECT_LE(failure_time[e], r.history.time.back());
    } else {
      EXPECT_EQ(failure_time[e], -1);
    }
    if (!bonded[e]) {
      EXPECT_GE(normal_force[e], 0) << "an unbonded joint carries no tension";
    }
  }
  EXPECT_GT(joint_cracks, 0);
  EXPECT_EQ(broken, joint_cracks);
  EXPECT_EQ(bonded_now, contacts[0] - joint_cracks);
  EXPECT_EQ(read_long(g, "bonded_at_end"), bonded_now);
  EXPECT_EQ(read_long(g, "broken_in_tension") + read_long(g, "broken_in_shear"), joint_cracks);

  // The snapshots: the joints' pairs once, their state at each; the last is the end state.
  const H5::Group snaps = f.openGroup("snapshots");
  EXPECT_EQ(read<std::int32_t>(snaps, "joint_pairs"), pairs);
  std::size_t last = 0;
  while (snaps.nameExists(std::string(6 - std::to_string(last + 1).size(), '0') +
                          std::to_string(last + 1)))
    ++last;
  ASSERT_GT(last, 0u);
  const std::string last_name =
      std::string(6 - std::to_string(last).size(), '0') + std::to_string(last);
  EXPECT_EQ(read<std::uint8_t>(snaps.openGroup(last_name), "joint_bonded"), bonded);
  EXPECT_EQ(read<std::int32_t>(snaps.openGroup(last_name), "joint_mode"), mode);
  const std::vector<std::uint8_t> first_bonded =
      read<std::uint8_t>(snaps.openGroup("000000"), "joint_bonded");
  long bonded_at_start = 0;
  for (const std::uint8_t b : first_bonded) bonded_at_start += b;
  EXPECT_EQ(bonded_at_start, contacts[0]);

  // The XDMF companion: one Polyline grid of n lines per snapshot.
  std::ifstream xmf(dir / "result_joints.xmf");
  ASSERT_TRUE(xmf.good());
  std::stringstream text;
  text << xmf.rdbuf();
  const std::string polyline =
      "TopologyType=\"Polyline\" NumberOfElements=\"" + std::to_string(n) + "\"";
  std::size_t grids = 0;
  for (std::size_t at = text.str().find(polyline); at != std::string::npos;
       at = text.str().find(polyline, at + 1))
    ++grids;
  EXPECT_EQ(grids, last + 1);
}

// Without [[test.joints]] the file has no /joints and no joints XDMF.
TEST(LabJointRecord, NoJointsNoGroup) {
  const fs::path dir = scratch_dir("test_lab_joint_record", "none");
  const LabTestInput in = cdem::test::lab_test_input(
      dir, cdem::test::small_rectangle_specimen(),
      "[test]\ntype = \"uniaxial\"\nhistory_interval = 20\nmax_steps = 400000\n"
      "snapshot_interval = 5000\n");
  ResultFile file(dir / "result.h5", in);
  LabTestHooks hooks;
  hooks.snapshot = [&](const World& w, long step, double time) { file.snapshot(w, step, time); };
  file.commit(run_lab_test(cdem::test::small_rectangle_specimen(), in, hooks));
  H5::H5File f((dir / "result.h5").string(), H5F_ACC_RDONLY);
  EXPECT_FALSE(f.nameExists("joints"));
  EXPECT_FALSE(f.nameExists("snapshots/joint_pairs"));
  EXPECT_FALSE(fs::exists(dir / "result_joints.xmf"));
  EXPECT_TRUE(fs::exists(dir / "result_bonds.xmf"));
}

}  // namespace
