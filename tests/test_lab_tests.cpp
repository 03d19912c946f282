// Lab tests (SPEC 6) on small packed specimens: the UCS runs to its stop rule with finite
// figures, the Brazilian strength follows the platen-force history, direct tension pulls its
// grips, bad inputs are InputErrors, and a failed run leaves no result file. The scaling checks
// are in test_lab_scaling.cpp, the biaxial test in test_lab_biaxial.cpp.
#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <string>

#include <gtest/gtest.h>

#include "core/input_error.hpp"
#include "dem/measure.hpp"
#include "dem/world_from_specimen.hpp"
#include "io/input_table.hpp"
#include "io/specimen_file.hpp"
#include "jostled_lattice.hpp"
#include "lab/lab_test.hpp"
#include "lab/material_genesis.hpp"
#include "lab/material_table.hpp"
#include "lab/result_file.hpp"
#include "lab_test_fixtures.hpp"

namespace {

namespace fs = std::filesystem;
using cdem::Container;
using cdem::ContainerShape;
using cdem::InputError;
using cdem::Specimen;
using namespace cdem::dem;
using namespace cdem::lab;
using cdem::test::c30_materials;
using cdem::test::expect_input_error;
using cdem::test::lab_test_input;
using cdem::test::scratch_dir;
using cdem::test::write_text;

const Specimen& rectangle_specimen() {
  return cdem::test::small_rectangle_specimen();
}

const Specimen& disc_specimen() {  // 20 mm diameter
  return cdem::test::small_disc_specimen();
}

std::string materials() {
  return c30_materials();
}

fs::path scratch(const std::string& name) {
  return scratch_dir("test_lab_tests", name);
}

LabTestInput test_input(const fs::path& dir, const Specimen& s, const std::string& test_table,
                        const std::string& materials_text = materials()) {
  return lab_test_input(dir, s, test_table, materials_text);
}

const std::string kUcs = "[test]\ntype = \"uniaxial\"\nhistory_interval = 20\nmax_steps = 400000\n";

TEST(LabTests, UniaxialRunsToTheStopRuleWithFiniteFigures) {
  const fs::path dir = scratch("ucs");
  const LabTestInput in = test_input(dir, rectangle_specimen(), kUcs);
  const LabTestResult r = run_lab_test(rectangle_specimen(), in);
  EXPECT_TRUE(std::isfinite(r.ucs.peak_stress) && r.ucs.peak_stress > 0);
  EXPECT_TRUE(std::isfinite(r.ucs.young_modulus) && r.ucs.young_modulus > 0);
  EXPECT_TRUE(std::isfinite(r.ucs.poisson_ratio) && r.ucs.poisson_ratio > 0);
  EXPECT_LT(r.ucs.poisson_ratio, 0.5);
  // Stopped by the rule: the last stress is below 0.8 x peak, after the peak.
  const LabHistory& h = r.history;
  EXPECT_LT(h.axial_stress.back(), 0.8 * r.peak_stress);
  EXPECT_GT(r.ucs.peak_index, 0u);
  EXPECT_LT(r.ucs.peak_index, h.size() - 1);
  EXPECT_LT(r.steps, 400000);
  EXPECT_GT(r.genesis.bonds[0], 0);
  long cracks = 0;
  for (const auto& mode : r.crack_count)
    for (long n : mode) cracks += n;
  EXPECT_EQ(cracks, static_cast<long>(r.cracks.size()));
  EXPECT_EQ(h.bonds_broken.back(), cracks);
  // Genesis figures add up.
  EXPECT_EQ(r.genesis.discs, r.genesis.discs_in_specimen - r.genesis.floating_removed);
  // Fragments of the broken specimen: every disc in one, the groups hold all the mass (all
  // discs here are mortar of one density, so the mass is the discs' area times it).
  const Fragments& f = r.fragments;
  ASSERT_GE(f.count(), 1u);
  EXPECT_EQ(f.fragment_of_disc.size(), static_cast<std::size_t>(r.genesis.discs));
  double area = 0, fractions = 0;
  for (std::size_t i = 0; i < f.r.size(); ++i) area += std::numbers::pi * f.r[i] * f.r[i];
  for (const double g : f.group_mass_fraction) fractions += g;
  EXPECT_NEAR(fractions, 1, 1e-12);
  double diameters_area = 0;
  for (const double d : f.diameter) diameters_area += std::numbers::pi * d * d / 4;
  EXPECT_NEAR(diameters_area, area, 1e-9 * area);
  EXPECT_EQ(f.group_mass_fraction.size(), kDefaultFragmentSieve.size() + 1);
}

TEST(LabTests, SameInputSameBitsWithOneOrTwoThreads) {
  const fs::path dir = scratch("determinism");
  const LabTestInput one = test_input(dir, rectangle_specimen(), kUcs);
  const LabTestInput two = test_input(dir, rectangle_specimen(), kUcs + "threads = 2\n");
  const LabTestResult a = run_lab_test(rectangle_specimen(), one);
  const LabTestResult b = run_lab_test(rectangle_specimen(), one);
  const LabTestResult c = run_lab_test(rectangle_specimen(), two);
  for (const LabTestResult* r : {&b, &c}) {
    EXPECT_EQ(r->history.axial_stress, a.history.axial_stress);
    EXPECT_EQ(r->history.lateral_strain, a.history.lateral_strain);
    ASSERT_EQ(r->cracks.size(), a.cracks.size());
    for (std::size_t k = 0; k < a.cracks.size(); ++k) {
      EXPECT_EQ(r->cracks[k].x, a.cracks[k].x);
      EXPECT_EQ(r->cracks[k].time, a.cracks[k].time);
    }
  }
}

TEST(LabTests, BrazilianStrengthFollowsThePlatenForceHistory) {
  const fs::path dir = scratch("brazilian");
  const LabTestInput in =
      test_input(dir, disc_specimen(),
                 "[materials.wall]\nlaw = \"linear\"\nfriction = 0.5\n"
                 "[test]\ntype = \"brazilian\"\nhistory_interval = 20\nmax_steps = 400000\n");
  const LabTestResult r = run_lab_test(disc_specimen(), in);
  double p_max = 0;
  for (double p : r.history.platen_force) p_max = std::max(p_max, p);
  ASSERT_GT(p_max, 0);
  EXPECT_DOUBLE_EQ(r.tensile_strength, 2 * p_max / (std::numbers::pi * 20e-3 * 1.0));
  // The nominal axial stress of the history is P / (D t).
  EXPECT_NEAR(r.peak_stress, p_max / 20e-3, 1e-9 * r.peak_stress);
}

// Curved jaws (ISRM): each placed where it touches the first disc, so the test starts without a
// load (the first record's platen force is that of touching discs, not of jaws pressed in), the
// strain refers to the disc's extent as with flat platens, and the test runs to a confirmed peak
// with sigma_t = 2 P_max / (pi D t).
TEST(LabTests, BrazilianWithCurvedJawsStartsUnloadedAndSplits) {
  const fs::path dir = scratch("brazilian_jaws");
  const std::string test =
      "[test]\ntype = \"brazilian\"\nhistory_interval = 20\nmax_steps = 400000\n";
  const LabTestResult flat = run_lab_test(disc_specimen(), test_input(dir, disc_specimen(), test));
  const LabTestResult jaws = run_lab_test(
      disc_specimen(), test_input(dir, disc_specimen(), test + "platens = \"curved_jaws\"\n"));
  ASSERT_GT(jaws.history.platen_force.size(), 2u);
  double p_max = 0;
  for (double p : jaws.history.platen_force) p_max = std::max(p_max, p);
  EXPECT_LT(std::abs(jaws.history.platen_force.front()), 1e-3 * p_max);
  EXPECT_DOUBLE_EQ(jaws.tensile_strength, 2 * p_max / (std::numbers::pi * 20e-3 * 1.0));
  EXPECT_EQ(jaws.stop_reason, StopReason::PostPeakDrop);
  EXPECT_GT(jaws.crack_count[0][0] + jaws.crack_count[0][1], 10);
  // The jaws spread the load over more discs than flat platens: a different test, same order.
  EXPECT_NE(jaws.tensile_strength, flat.tensile_strength);
  EXPECT_GT(jaws.tensile_strength, 0.5 * flat.tensile_strength);
  EXPECT_LT(jaws.tensile_strength, 2 * flat.tensile_strength);
}

// The split rule wired to the run (lab/stop_rule.hpp): the 20 mm disc with jaws drops to 0.72 x
// its peak at once and widens only 1.4 x faster (it ends on the drop by default), so the rule is
// asked for an opening of 1.1 x with the drop rule out of the way (stop_fraction 0.5). It then
// ends at the split with the history's largest force as the strength, the last record below
// 0.9 x the peak and widening at least 1.1 x as fast as at the peak; with the split rule off the
// same run goes on to the drop below 0.5 x.
TEST(LabTests, ABrazilianDiscEndsAtItsSplit) {
  const fs::path dir = scratch("brazilian_split");
  const std::string test =
      "[test]\ntype = \"brazilian\"\nhistory_interval = 20\nmax_steps = 400000\n"
      "platens = \"curved_jaws\"\nstop_fraction = 0.5\n";
  const LabTestResult split = run_lab_test(
      disc_specimen(), test_input(dir, disc_specimen(), test + "stop_split_opening = 1.1\n"));
  ASSERT_EQ(split.stop_reason, StopReason::Split);
  const LabHistory& h = split.history;
  const auto peak = static_cast<std::size_t>(
      std::max_element(h.platen_force.begin(), h.platen_force.end()) - h.platen_force.begin());
  EXPECT_DOUBLE_EQ(split.tensile_strength,
                   2 * h.platen_force[peak] / (std::numbers::pi * 20e-3 * 1.0));
  const auto widening = [&](std::size_t i) { return -h.lateral_strain[i] / h.axial_strain[i]; };
  EXPECT_LT(h.platen_force.back(), 0.9 * h.platen_force[peak]);
  EXPECT_GE(widening(h.step.size() - 1), 1.1 * widening(peak));
  const LabTestResult off = run_lab_test(
      disc_specimen(), test_input(dir, disc_specimen(), test + "stop_split = false\n"));
  EXPECT_EQ(off.stop_reason, StopReason::PostPeakDrop);
  EXPECT_GT(off.history.step.back(), h.step.back());
}

TEST(LabTests, DirectTensionPullsTheGripsApart) {
  const fs::path dir = scratch("tension");
  const LabTestInput in =
      test_input(dir, rectangle_specimen(),
                 "[test]\ntype = \"direct_tension\"\nhistory_interval = 20\nmax_steps = 400000\n");
  const LabTestResult r = run_lab_test(rectangle_specimen(), in);
  EXPECT_GT(r.tensile_strength, 0);
  EXPECT_DOUBLE_EQ(r.tensile_strength, r.peak_stress);
  EXPECT_GT(r.history.axial_strain.back(), 0);
  EXPECT_LT(r.history.axial_stress.back(), 0.8 * r.peak_stress);
  // Tension cracks dominate.
  EXPECT_GT(r.crack_count[0][0], r.crack_count[1][0]);
}

TEST(LabTests, BadInputsAreInputErrorsNamingTheKey) {
  const fs::path dir = scratch("bad");
  cdem::write_specimen(rectangle_specimen(), dir / "rect.h5");
  cdem::write_specimen(disc_specimen(), dir / "disc.h5");
  const auto read = [&](const std::string& text) {
    write_text(dir / "t.toml", text);
    return read_lab_test(dir / "t.toml");
  };
  const std::string m = materials();
  expect_input_error(
      [&] { read("specimen = \"none.h5\"\n" + m + "[test]\ntype = \"uniaxial\"\n"); }, "specimen");
  expect_input_error(
      [&] { read("specimen = \"rect.h5\"\n" + m + "[test]\ntype = \"triaxial\"\n"); }, "test.type");
  expect_input_error(
      [&] {
        read("specimen = \"rect.h5\"\n" + m +
             "[test]\ntype = \"uniaxial\"\nplaten_velocity_m_s = -0.02\n");
      },
      "test.platen_velocity");
  // A table without ITZ and aggregate classes: read, refused for a specimen with aggregates
  // (3 here; tests/cli_run_errors.sh runs a generated one), accepted for a mortar-only one
  // (issue 17).
  const std::string mortar_only =
      "[materials.mortar]\nlaw = \"linear\"\nemod_GPa = 16\nkratio = 1\nfriction = 0.5\n";
  const LabTestInput no_itz =
      read("specimen = \"rect.h5\"\n" + mortar_only + "[test]\ntype = \"uniaxial\"\n");
  expect_input_error([&] { require_classes(no_itz.materials, 3, "rect.h5"); }, "materials.itz");
  EXPECT_NO_THROW(require_classes(no_itz.materials, 0, "rect.h5"));
  ASSERT_EQ(disc_specimen().clumps.size(), 0u);
  const LabTestInput mortar_disc =
      read("specimen = \"disc.h5\"\n" + mortar_only + "[test]\ntype = \"brazilian\"\n");
  EXPECT_NO_THROW(check_specimen_for_test(disc_specimen(), mortar_disc));
  EXPECT_FALSE(mortar_disc.materials.given[static_cast<int>(ContactClass::Itz)]);
  expect_input_error(
      [&] { read("specimen = \"rect.h5\"\n" + m + "[test]\ntype = \"uniaxial\"\nspeed = 1\n"); },
      "speed");
  expect_input_error(
      [&] {
        read("specimen = \"rect.h5\"\nmaterials = \"none.toml\"\n[test]\ntype = \"uniaxial\"\n");
      },
      "materials");
  // Shape of the specimen against the test.
  const LabTestInput braz_on_rect =
      read("specimen = \"rect.h5\"\n" + m + "[test]\ntype = \"brazilian\"\n");
  expect_input_error([&] { run_lab_test(rectangle_specimen(), braz_on_rect); }, "test.type");
  const LabTestInput ucs_on_disc =
      read("specimen = \"disc.h5\"\n" + m + "[test]\ntype = \"uniaxial\"\n");
  expect_input_error([&] { run_lab_test(disc_specimen(), ucs_on_disc); }, "test.type");
  // The fragment sieve: sizes in mm, positive, increasing, 1 to 16 of them.
  for (const char* sieve :
       {"fragment_sieve = [1, 2]", "fragment_sieve_mm = [2, 1]", "fragment_sieve_mm = [0, 1]",
        "fragment_sieve_mm = []", "fragment_sieve_mm = [1, 1]"})
    expect_input_error(
        [&] {
          read("specimen = \"rect.h5\"\n" + m + "[test]\ntype = \"uniaxial\"\n" + sieve + "\n");
        },
        "test.fragment_sieve");
  EXPECT_EQ(read("specimen = \"rect.h5\"\n" + m +
                 "[test]\ntype = \"uniaxial\"\nfragment_sieve_mm = [0.5, 4]\n")
                .controls.fragment_sieve,
            (std::vector<double>{0.5e-3, 4e-3}));
  // Curved jaws: Brazilian only, two shapes, the radius ratio only with them.
  expect_input_error(
      [&] {
        read("specimen = \"rect.h5\"\n" + m + "[test]\ntype = \"uniaxial\"\nplatens = \"flat\"\n");
      },
      "test.platens");
  expect_input_error(
      [&] {
        read("specimen = \"disc.h5\"\n" + m +
             "[test]\ntype = \"brazilian\"\nplatens = \"round\"\n");
      },
      "test.platens");
  expect_input_error(
      [&] {
        read("specimen = \"disc.h5\"\n" + m +
             "[test]\ntype = \"brazilian\"\njaw_radius_ratio = 1.5\n");
      },
      "test.jaw_radius_ratio");
  expect_input_error(
      [&] {
        read("specimen = \"disc.h5\"\n" + m +
             "[test]\ntype = \"brazilian\"\nplatens = \"curved_jaws\"\njaw_radius_ratio = 1\n");
      },
      "test.jaw_radius_ratio");
  // The split rule's keys: Brazilian only, an opening factor above 1, none with the rule off.
  expect_input_error(
      [&] {
        read("specimen = \"rect.h5\"\n" + m + "[test]\ntype = \"uniaxial\"\nstop_split = true\n");
      },
      "test.stop_split");
  expect_input_error(
      [&] {
        read("specimen = \"disc.h5\"\n" + m +
             "[test]\ntype = \"brazilian\"\nstop_split_opening = 1\n");
      },
      "test.stop_split_opening");
  expect_input_error(
      [&] {
        read("specimen = \"disc.h5\"\n" + m +
             "[test]\ntype = \"brazilian\"\nstop_split = false\nstop_split_fraction = 0.9\n");
      },
      "test.stop_split_fraction");
  // A corrupt HDF5 specimen.
  write_text(dir / "corrupt.h5", "not an HDF5 file");
  EXPECT_THROW(cdem::read_specimen(dir / "corrupt.h5"), InputError);
}

// The relaxation after the bonds are installed reads the per-pair results once per hundred
// steps (the unbalanced-force ratio), and only those steps keep them. The relaxed world, its
// step count and its ratio have the bits of the relaxation as GenesisOptions describes it,
// written out here with the results kept every step (chunks of 100 steps until the ratio is
// reached after at least relax_min_steps), and the steps after it keep them again.
TEST(LabTests, TheGenesisRelaxationKeepsThePairResultsOnlyWhereItReadsThem) {
  WorldSettings settings;
  read_material_table(cdem::InputTable::parse_string(materials(), "materials.toml"))
      .apply(settings);
  const GenesisOptions options;
  GenesisReport report;
  const Specimen cleaned = remove_floating_discs(rectangle_specimen(), settings, options, report);
  World relaxed = world_from_specimen(cleaned, settings);
  World every = world_from_specimen(cleaned, settings);
  install_test_bonds(relaxed, options, report);

  install_bonds(every, BondInstallation{options.bond_gap_ratio});
  double ratio = 0;
  for (;;) {
    every.cycle(100);
    ratio = unbalanced_force_ratio(every);
    if ((every.step_count() >= options.relax_min_steps && ratio <= options.relax_tolerance) ||
        every.step_count() >= options.relax_max_steps)
      break;
  }
  for (std::size_t b = 0; b < every.bodies().size(); ++b)
    every.set_body_velocity(static_cast<int>(b), 0, 0, 0);
  every.clear_cracks();

  ASSERT_GT(report.relaxation_steps, 100);  // more than one request
  EXPECT_EQ(report.relaxation_steps, every.step_count());
  EXPECT_EQ(std::bit_cast<std::uint64_t>(report.relaxation_unbalanced_ratio),
            std::bit_cast<std::uint64_t>(ratio));
  cdem::test::expect_same_bits(cdem::test::world_bits(relaxed), cdem::test::world_bits(every));
  // Two steps without a request: the first, after a whole hundred, keeps the results for the
  // energy check (World::energy_check_due) in any case.
  relaxed.cycle(2);
  every.cycle(2);
  const std::size_t pairs = every.pair_forces().normal.size();
  ASSERT_EQ(relaxed.pair_forces().normal.size(), pairs);
  for (std::size_t k = 0; k < pairs; ++k)
    ASSERT_EQ(std::bit_cast<std::uint64_t>(relaxed.pair_forces().normal[k]),
              std::bit_cast<std::uint64_t>(every.pair_forces().normal[k]))
        << "pair " << k;
}

// Every third mortar disc taken out of a jammed packing: many of the rest lose contacts, the
// floating removal would delete far more than a jammed packing loses, and the genesis stops
// naming the key; with the key at 1 the loose specimen is accepted and the loss reported.
TEST(LabTests, AGenesisThatRemovesTooManyFloatingDiscsStops) {
  const Specimen& jammed = rectangle_specimen();
  Specimen loose = jammed;
  loose.x.clear();
  loose.y.clear();
  loose.r.clear();
  loose.clump.clear();
  loose.contact_active.clear();
  long mortar = 0;
  for (std::size_t i = 0; i < jammed.disc_count(); ++i) {
    if (jammed.clump[i] < 0 && mortar++ % 3 == 0) continue;
    loose.x.push_back(jammed.x[i]);
    loose.y.push_back(jammed.y[i]);
    loose.r.push_back(jammed.r[i]);
    loose.clump.push_back(jammed.clump[i]);
    loose.contact_active.push_back(jammed.contact_active[i]);
  }
  const WorldSettings settings;
  GenesisOptions options;
  GenesisReport report;
  const Specimen kept = remove_floating_discs(jammed, settings, options, report);
  EXPECT_LE(report.floating_area_removed,
            options.max_floating_fraction * report.mortar_area_in_specimen);
  try {
    remove_floating_discs(loose, settings, options, report);
    ADD_FAILURE() << "a loose specimen passed the genesis";
  } catch (const cdem::RunError& e) {
    EXPECT_NE(std::string(e.what()).find("test.max_genesis_floating_fraction"), std::string::npos)
        << e.what();
  }
  options.max_floating_fraction = 1;
  const Specimen cleaned = remove_floating_discs(loose, settings, options, report);
  EXPECT_GT(report.floating_area_removed,
            GenesisOptions{}.max_floating_fraction * report.mortar_area_in_specimen);
  EXPECT_EQ(static_cast<long>(cleaned.disc_count()),
            static_cast<long>(loose.disc_count()) - report.floating_removed);
  EXPECT_GT(kept.disc_count(), cleaned.disc_count());
}

TEST(LabTests, AFailedRunLeavesNoResultFile) {
  const fs::path dir = scratch("failed");
  const LabTestInput in = test_input(dir, rectangle_specimen(),
                                     "[test]\ntype = \"uniaxial\"\nmax_steps = 50\n"
                                     "snapshot_interval = 10\n");
  const fs::path target = dir / "result.h5";
  {
    ResultFile file(target, in);
    LabTestHooks hooks;
    hooks.snapshot = [&file](const World& w, long step, double time) {
      file.snapshot(w, step, time);
    };
    EXPECT_THROW(run_lab_test(rectangle_specimen(), in, hooks), cdem::RunError);
  }
  for (const auto& entry : fs::directory_iterator(dir))
    EXPECT_EQ(entry.path().extension() == ".h5" ? entry.path().filename().string() : "specimen.h5",
              "specimen.h5")
        << "left behind: " << entry.path();
  EXPECT_FALSE(fs::exists(target));
  EXPECT_FALSE(fs::exists(dir / "result.xmf"));
}

TEST(LabTests, ResultFileAndXdmfAreWrittenOnSuccess) {
  const fs::path dir = scratch("result");
  const LabTestInput in =
      test_input(dir, rectangle_specimen(),
                 "[test]\ntype = \"uniaxial\"\nhistory_interval = 50\nsnapshot_interval = 5000\n");
  const fs::path target = dir / "result.h5";
  ResultFile file(target, in);
  LabTestHooks hooks;
  hooks.snapshot = [&file](const World& w, long step, double time) {
    file.snapshot(w, step, time);
  };
  const LabTestResult r = run_lab_test(rectangle_specimen(), in, hooks);
  file.commit(r);
  EXPECT_TRUE(fs::exists(target));
  ASSERT_TRUE(fs::exists(dir / "result.xmf"));
  std::ifstream xmf(dir / "result.xmf");
  const std::string text((std::istreambuf_iterator<char>(xmf)), {});
  EXPECT_NE(text.find("result.h5:/snapshots/000000/x"), std::string::npos);
  EXPECT_NE(text.find("<Grid Name=\"step 0\""), std::string::npos);  // loading steps
  EXPECT_NE(text.find("<Grid Name=\"step " + std::to_string(r.steps) + "\""), std::string::npos);
  EXPECT_NE(text.find("Polyvertex"), std::string::npos);
}

}  // namespace
