#pragma once
// The pieces every stability case shares (docs/stability.md): small specimens made through the
// library and cached in the build tree, the C30 contact laws with a case's overrides, a lab test
// run that samples the world's energy balance and writes its result file with the real writer,
// and the checks: a completed run is finite, closes its energy ledger and gives sensible figures;
// a stopped run names the step and the cause; no output file holds a non-finite number.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include <H5Cpp.h>
#include <gtest/gtest.h>

#include "core/input_error.hpp"
#include "core/rng.hpp"
#include "dem/energy.hpp"
#include "io/specimen_file.hpp"
#include "lab/lab_test.hpp"
#include "lab/result_file.hpp"
#include "mesogen/generate.hpp"
#include "mesogen/mortar_packing.hpp"
#include "tests/lab_test_fixtures.hpp"

namespace cdem::stability {

namespace fs = std::filesystem;

inline fs::path cache_dir() {
  const fs::path dir = fs::path(CDEM_BINARY_DIR) / "stability";
  fs::create_directories(dir);
  return dir;
}

// A mortar-only rectangle packed at sigma0 by pack_mortar, cached as `name`.h5 (same seed, same
// specimen; the file is written atomically, so two test processes may race harmlessly).
inline fs::path mortar_specimen(const std::string& name, double width_mm, double height_mm,
                                double r_mean_mm, double r_ratio, std::uint64_t seed,
                                long expansion_steps = 500) {
  const fs::path file = cache_dir() / (name + ".h5");
  if (fs::exists(file)) return file;
  mesogen::MortarPackingControls controls;
  controls.r_mean = r_mean_mm * 1e-3;
  controls.r_ratio = r_ratio;
  controls.expansion_steps = expansion_steps;
  const Container mould{ContainerShape::Rectangle, width_mm * 1e-3, height_mm * 1e-3};
  Rng rng(seed);
  write_specimen(test::mortar_only_specimen(mould, mesogen::pack_mortar(mould, controls, rng)),
                 file);
  return file;
}

// A concrete section from the generator (run_generate: aggregates as clumps, ITZ tagged),
// cached as `name`.h5; `generator_toml` is the generator input.
inline fs::path generated_specimen(const std::string& name, const std::string& generator_toml,
                                   std::uint64_t seed) {
  const fs::path file = cache_dir() / (name + ".h5");
  if (fs::exists(file)) return file;
  const fs::path input = cache_dir() / (name + "_" + std::to_string(::getpid()) + ".toml");
  std::ofstream(input) << generator_toml;
  mesogen::run_generate({input, file, seed, std::nullopt, std::nullopt, false});
  fs::remove(input);
  return file;
}

// A 20 x 40 mm concrete section: 3-6 mm Walraven aggregates (P_k 0.75) in 0.4 mm mortar discs,
// packed with contacts of modulus `packing_emod_GPa` (the overlap locked in at sigma0 scales
// with 1 / E*: pack with the stiffest class's modulus, or its contacts start far above sigma0).
inline fs::path small_concrete(double packing_emod_GPa = 16) {
  const std::string name =
      "concrete_20x40" + (packing_emod_GPa == 16
                              ? std::string()
                              : "_pack" + std::to_string(static_cast<long>(packing_emod_GPa)));
  return generated_specimen(name,
                            R"(
[specimen]
shape = "rectangle"
width_mm = 20
height_mm = 40
[gradation]
type = "walraven"
p_k = 0.75
d_min_mm = 3
d_max_mm = 6
bins_mm = [3, 4.5, 6]
[aggregates]
min_gap_mm = 0.4
boundary_clearance_mm = 0.4
[mortar]
r_mean_mm = 0.4
r_ratio = 2.5
porosity = 0.12
sigma0_MPa = 0.1
packing_emod_GPa = )" + std::to_string(packing_emod_GPa) +
                                "\n",
                            5);
}

// The contact law of one class; strengths of 0 make it linear (no bond).
struct ClassLaw {
  double emod_GPa, kratio, friction, tensile_MPa = 0, cohesion_MPa = 0;
};
struct Laws {
  ClassLaw mortar{16, 1.45, 0.5, 10, 30};
  ClassLaw itz{8, 1.45, 0.5, 5, 15};
  ClassLaw aggregate{20, 2, 1.0};
};

inline std::string materials_toml(const Laws& laws) {
  std::ostringstream out;
  out.precision(17);
  const auto table = [&](const char* name, const ClassLaw& c) {
    out << "[materials." << name << "]\n";
    out << "law = \"" << (c.tensile_MPa > 0 ? "parallel_bond" : "linear") << "\"\n";
    out << "emod_GPa = " << c.emod_GPa << "\nkratio = " << c.kratio << "\nfriction = " << c.friction
        << "\n";
    if (c.tensile_MPa > 0)
      out << "pb_tensile_strength_MPa = " << c.tensile_MPa
          << "\npb_cohesion_MPa = " << c.cohesion_MPa << "\n";
  };
  table("mortar", laws.mortar);
  table("itz", laws.itz);
  table("aggregate", laws.aggregate);
  return out.str();
}

struct CaseRun {
  bool completed = false;
  std::string error;  // RunError text when the run stopped
  lab::LabTestResult result;
  double worst_energy_error = 0;  // largest |balance| / energy over the samples
  long energy_samples = 0;
  fs::path result_file;
  double wall_time = 0;  // s
};

// One lab test: `test_keys` is the body of the [test] table. The world's energy balance
// (dem/energy.hpp: input = stored + dissipated, damping included) is sampled at every snapshot;
// snapshots and results go to the result file through lab::ResultFile, committed only when the
// run completes. A line for docs/stability.md is printed either way.
inline CaseRun run_case(const std::string& name, const fs::path& specimen_file, const Laws& laws,
                        const std::string& test_keys) {
  const fs::path dir = cache_dir() / "cases" / name;
  fs::remove_all(dir);
  fs::create_directories(dir);
  std::ofstream(dir / "test.toml") << "seed = 1\nspecimen = \"" << specimen_file.string() << "\"\n"
                                   << materials_toml(laws) << "\n[test]\n"
                                   << test_keys;
  const lab::LabTestInput input = lab::read_lab_test(dir / "test.toml");
  const Specimen specimen = read_specimen(specimen_file);
  CaseRun run;
  run.result_file = dir / "result.h5";
  const auto start = std::chrono::steady_clock::now();
  {
    lab::ResultFile file(run.result_file, input);
    lab::LabTestHooks hooks;
    hooks.snapshot = [&](const dem::World& world, long step, double time) {
      file.snapshot(world, step, time);
      if (world.energy().reference_pending) return;  // restarted at the next energy check
      run.worst_energy_error =
          std::max(run.worst_energy_error, dem::energies(world).relative_error());
      ++run.energy_samples;
    };
    try {
      run.result = lab::run_lab_test(specimen, input, hooks);
      file.commit(run.result);
      run.completed = true;
    } catch (const RunError& e) {
      run.error = e.what();
    }
  }
  run.wall_time = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const lab::LabTestResult& r = run.result;
  if (run.completed)
    std::printf(
        "[stability] %s: completed, discs %ld, relaxation cracks %ld, steps %ld, dt %.3g s, peak "
        "%.4g MPa, E %.4g GPa, nu %.4f, cracks %zu, energy error %.3g (%ld samples), %.1f s\n",
        name.c_str(), r.genesis.discs, r.genesis.relaxation_cracks, r.steps, r.time_step,
        r.peak_stress * 1e-6, r.ucs.young_modulus * 1e-9, r.ucs.poisson_ratio, r.cracks.size(),
        run.worst_energy_error, run.energy_samples, run.wall_time);
  else
    std::printf("[stability] %s: stopped, %.1f s: %s\n", name.c_str(), run.wall_time,
                run.error.c_str());
  return run;
}

// Every floating-point value of every dataset and attribute in an HDF5 file; returns the
// number of non-finite values and names the first offender in `where`.
inline long non_finite_values(const fs::path& file, std::string& where) {
  struct Scan {
    long bad = 0;
    long values = 0;
    std::string where;
    void check(const std::vector<double>& v, const std::string& name) {
      values += static_cast<long>(v.size());
      for (double x : v)
        if (!std::isfinite(x)) {
          if (bad++ == 0) where = name;
        }
    }
  } scan;
  const auto attributes = [&](H5::H5Object& object, const std::string& name) {
    for (int a = 0; a < object.getNumAttrs(); ++a) {
      H5::Attribute attr = object.openAttribute(static_cast<unsigned>(a));
      if (attr.getTypeClass() != H5T_FLOAT) continue;
      std::vector<double> v(static_cast<std::size_t>(attr.getSpace().getSimpleExtentNpoints()));
      attr.read(H5::PredType::NATIVE_DOUBLE, v.data());
      scan.check(v, name + "@" + attr.getName());
    }
  };
  H5::H5File h5(file.string(), H5F_ACC_RDONLY);
  std::vector<std::string> groups{"/"};
  while (!groups.empty()) {
    const std::string path = groups.back();
    groups.pop_back();
    H5::Group group = h5.openGroup(path);
    attributes(group, path);
    for (hsize_t k = 0; k < group.getNumObjs(); ++k) {
      const std::string child = (path == "/" ? "/" : path + "/") + group.getObjnameByIdx(k);
      const H5G_obj_t type = group.getObjTypeByIdx(k);
      if (type == H5G_GROUP) {
        groups.push_back(child);
      } else if (type == H5G_DATASET) {
        H5::DataSet set = h5.openDataSet(child);
        attributes(set, child);
        if (set.getTypeClass() != H5T_FLOAT) continue;
        std::vector<double> v(static_cast<std::size_t>(set.getSpace().getSimpleExtentNpoints()));
        if (!v.empty()) set.read(v.data(), H5::PredType::NATIVE_DOUBLE);
        scan.check(v, child);
      }
    }
  }
  where = scan.where;
  return scan.values > 0 ? scan.bad : -1;
}

// Tolerance on the energy ledger of a completed run: |input - stored - dissipated| over the
// energy, at every snapshot. The scheme's error at bond failures and slip onsets is O(dt) per
// event (docs/dem_design.md: 2.4e-2 on a jostling bonded lattice without damping at safety 0.8).
constexpr double kEnergyTolerance = 0.05;

// A completed run: result file committed and finite throughout, energy ledger closed, and a
// positive peak below `peak_bound` (Pa).
inline void expect_completed_and_finite(const CaseRun& run, double peak_bound) {
  ASSERT_TRUE(run.completed) << run.error;
  std::string where;
  EXPECT_EQ(non_finite_values(run.result_file, where), 0) << "non-finite value in " << where;
  EXPECT_GT(run.energy_samples, 0);
  EXPECT_LT(run.worst_energy_error, kEnergyTolerance);
  EXPECT_GT(run.result.peak_stress, 0);
  EXPECT_LT(run.result.peak_stress, peak_bound);
}

// A uniaxial run that completed: as above, plus a positive E and a Poisson's ratio in
// (nu_min, nu_max): by default (-0.1, 0.5) (2D bonded discs: below 1/3 in lattice theory,
// negative only when ks > kn; 0.5 leaves room for dilatancy from cracking before 50 % of peak).
inline void expect_sensible_ucs(const CaseRun& run, double peak_bound, double nu_min = -0.1,
                                double nu_max = 0.5) {
  expect_completed_and_finite(run, peak_bound);
  if (!run.completed) return;
  const lab::UcsResult& u = run.result.ucs;
  EXPECT_TRUE(std::isfinite(u.young_modulus) && u.young_modulus > 0) << u.young_modulus;
  EXPECT_TRUE(std::isfinite(u.poisson_ratio)) << u.poisson_ratio;
  EXPECT_GT(u.poisson_ratio, nu_min);
  EXPECT_LT(u.poisson_ratio, nu_max);
}

// A run stopped by the instability guard: RunError naming the step and a likely cause, and no
// result file left behind.
inline void expect_stopped_with_diagnostic(const CaseRun& run) {
  ASSERT_FALSE(run.completed);
  EXPECT_NE(run.error.find("step"), std::string::npos) << run.error;
  EXPECT_NE(run.error.find("likely cause"), std::string::npos) << run.error;
  EXPECT_FALSE(fs::exists(run.result_file));
}

}  // namespace cdem::stability
