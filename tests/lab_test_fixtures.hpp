#pragma once
// Small specimens, materials and test files shared by the lab-test suites
// (test_lab_tests, test_lab_biaxial, test_lab_scaling).
#include <filesystem>
#include <fstream>
#include <string>

#include <gtest/gtest.h>

#include "core/input_error.hpp"
#include "core/rng.hpp"
#include "core/specimen.hpp"
#include "io/specimen_file.hpp"
#include "lab/lab_test.hpp"
#include "mesogen/mortar_packing.hpp"
#include "scratch_dir.hpp"

namespace cdem::test {

// The specimen of a mortar packing without aggregates: every disc free and in contact.
inline Specimen mortar_only_specimen(const Container& mould, const mesogen::MortarPacking& p) {
  Specimen s;
  s.container = mould;
  s.x = p.x;
  s.y = p.y;
  s.r = p.r;
  s.clump.assign(p.r.size(), -1);
  s.contact_active.assign(p.r.size(), 1);
  return s;
}

// A mortar-only specimen packed at sigma0 in a mould (no aggregates), discs of mean radius
// 0.4 mm: a 10 x 20 mm rectangle holds about 320 discs after genesis.
inline Specimen packed_specimen(const Container& mould, std::uint64_t seed) {
  mesogen::MortarPackingControls controls;
  controls.r_mean = 0.4e-3;
  Rng rng(seed);
  return mortar_only_specimen(mould, mesogen::pack_mortar(mould, controls, rng));
}

// The 10 mm wide, 20 mm high specimen of the small tests (packed once per process).
inline const Specimen& small_rectangle_specimen() {
  static const Specimen s = packed_specimen({ContainerShape::Rectangle, 10e-3, 20e-3}, 7);
  return s;
}

// The 20 mm disc of the small Brazilian tests (packed once per process).
inline const Specimen& small_disc_specimen() {
  static const Specimen s = packed_specimen({ContainerShape::Disc, 20e-3, 20e-3}, 8);
  return s;
}

// Expects `f` to throw an InputError whose message names `key` (and the file).
template <class F>
void expect_input_error(F&& f, const std::string& key) {
  try {
    f();
    FAIL() << "no InputError for " << key;
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find(key), std::string::npos) << e.what();
  }
}

// The C30 contact laws (SPEC 8) with every modulus and every strength scaled.
inline std::string c30_materials(double modulus_factor = 1, double strength_factor = 1) {
  const auto num = [](double v) { return std::to_string(v); };
  return "[materials.mortar]\nlaw = \"parallel_bond\"\nemod_GPa = " + num(16 * modulus_factor) +
         "\nkratio = 1.45\nfriction = 0.5\npb_tensile_strength_MPa = " + num(10 * strength_factor) +
         "\npb_cohesion_MPa = " + num(30 * strength_factor) +
         "\n[materials.itz]\nlaw = \"parallel_bond\"\nemod_GPa = " + num(8 * modulus_factor) +
         "\nkratio = 1.45\nfriction = 0.5\npb_tensile_strength_MPa = " + num(5 * strength_factor) +
         "\npb_cohesion_MPa = " + num(15 * strength_factor) +
         "\n[materials.aggregate]\nlaw = \"linear\"\nemod_GPa = " + num(20 * modulus_factor) +
         "\nkratio = 2\nfriction = 1.0\n";
}

inline void write_text(const std::filesystem::path& file, const std::string& text) {
  std::ofstream(file) << text;
}

// Writes the specimen and a test file into `dir` and reads the test back.
inline lab::LabTestInput lab_test_input(const std::filesystem::path& dir, const Specimen& s,
                                        const std::string& test_table,
                                        const std::string& materials_text = c30_materials()) {
  write_specimen(s, dir / "specimen.h5");
  write_text(dir / "test.toml",
             "seed = 3\nspecimen = \"specimen.h5\"\n" + materials_text + "\n" + test_table);
  return lab::read_lab_test(dir / "test.toml");
}

}  // namespace cdem::test
