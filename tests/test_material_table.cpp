// The contact material table: the C30 sample gives the SPEC 8 numbers in SI, and every kind of
// bad input is an InputError naming its key.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>

#include "calibrate/calibrate_input.hpp"
#include "io/input_table.hpp"
#include "lab/material_keys.hpp"
#include "lab/material_table.hpp"

namespace {

using namespace cdem::dem;

using namespace cdem::lab;
using cdem::InputError;
using cdem::InputTable;

const LinearContact& linear(const MaterialTable& t, ContactClass c) {
  return t.linear[static_cast<int>(c)];
}
const BondModel& bond(const MaterialTable& t, ContactClass c) {
  return t.bonds[static_cast<int>(c)];
}

TEST(MaterialTable, C30SampleGivesSpec8Numbers) {
  const MaterialTable t =
      read_material_table(std::filesystem::path(CDEM_SOURCE_DIR) / "samples/c30_materials.toml");
  // Mortar-mortar: parallel bond, E* = Eb = 16 GPa, kn/ks = 1.45, sigma_b 10, c_b 30 MPa, mu 0.5.
  EXPECT_EQ(linear(t, ContactClass::Mortar).emod, 16e9);
  EXPECT_EQ(linear(t, ContactClass::Mortar).kappa, 1.45);
  EXPECT_EQ(linear(t, ContactClass::Mortar).mu, 0.5);
  const BondModel& m = bond(t, ContactClass::Mortar);
  EXPECT_EQ(m.kind, BondKind::Parallel);
  EXPECT_EQ(m.parallel.modulus, 16e9);
  EXPECT_EQ(m.parallel.stiffness_ratio, 1.45);
  EXPECT_EQ(m.parallel.tensile_strength, 10e6);
  EXPECT_EQ(m.parallel.cohesion, 30e6);
  EXPECT_EQ(m.parallel.friction_angle, 0);
  EXPECT_EQ(m.parallel.radius_multiplier, 1);
  EXPECT_EQ(m.parallel.moment_factor, 1);
  // ITZ: 8 GPa, 1.45, 5 and 15 MPa, mu 0.5.
  EXPECT_EQ(linear(t, ContactClass::Itz).emod, 8e9);
  EXPECT_EQ(linear(t, ContactClass::Itz).mu, 0.5);
  const BondModel& itz = bond(t, ContactClass::Itz);
  EXPECT_EQ(itz.kind, BondKind::Parallel);
  EXPECT_EQ(itz.parallel.modulus, 8e9);
  EXPECT_EQ(itz.parallel.stiffness_ratio, 1.45);
  EXPECT_EQ(itz.parallel.tensile_strength, 5e6);
  EXPECT_EQ(itz.parallel.cohesion, 15e6);
  // Aggregate-aggregate: linear, 20 GPa, kn/ks 2, mu 1.
  EXPECT_EQ(bond(t, ContactClass::Aggregate).kind, BondKind::None);
  EXPECT_EQ(linear(t, ContactClass::Aggregate).emod, 20e9);
  EXPECT_EQ(linear(t, ContactClass::Aggregate).kappa, 2);
  EXPECT_EQ(linear(t, ContactClass::Aggregate).mu, 1.0);
  // Wall: mortar E* and kn/ks, mu = 0.
  EXPECT_EQ(bond(t, ContactClass::Wall).kind, BondKind::None);
  EXPECT_EQ(linear(t, ContactClass::Wall).emod, 16e9);
  EXPECT_EQ(linear(t, ContactClass::Wall).kappa, 1.45);
  EXPECT_EQ(linear(t, ContactClass::Wall).mu, 0);

  WorldSettings s;
  t.apply(s);
  EXPECT_EQ(s.laws[static_cast<int>(ContactClass::Itz)].emod, 8e9);
  EXPECT_EQ(s.bonds[static_cast<int>(ContactClass::Itz)].parallel.cohesion, 15e6);
}

const std::string kValid = R"(
[materials.mortar]
law = "parallel_bond"
emod_GPa = 16
kratio = 1.45
friction = 0.5
pb_emod = "12 GPa"
pb_kratio = 2
pb_tensile_strength_MPa = 10
pb_cohesion_MPa = 30
pb_friction_angle_deg = 30
pb_radius_multiplier = 0.8
pb_moment_factor = 0.5
[materials.itz]
law = "parallel_bond"
emod_GPa = 8
kratio = 1.45
friction = 0.5
pb_tensile_strength_MPa = 5
pb_cohesion_MPa = 15
[materials.aggregate]
law = "contact_bond"
emod_GPa = 20
kratio = 2
friction = 1.0
cb_tensile_strength_MPa = 40
cb_shear_strength_MPa = 60
)";

MaterialTable parse(const std::string& text) {
  return read_material_table(InputTable::parse_string(text, "materials.toml"));
}

TEST(MaterialTable, OptionalBondKeysAndContactBond) {
  const MaterialTable t = parse(kValid);
  const ParallelBondParams& p = bond(t, ContactClass::Mortar).parallel;
  EXPECT_EQ(p.modulus, 12e9);
  EXPECT_EQ(p.stiffness_ratio, 2);
  EXPECT_NEAR(p.friction_angle, std::numbers::pi / 6, 1e-15);
  EXPECT_EQ(p.radius_multiplier, 0.8);
  EXPECT_EQ(p.moment_factor, 0.5);
  const BondModel& a = bond(t, ContactClass::Aggregate);
  EXPECT_EQ(a.kind, BondKind::Contact);
  EXPECT_EQ(a.contact.normal_strength, 40e6);
  EXPECT_EQ(a.contact.shear_strength, 60e6);
  // No wall table: mortar E* and kn/ks, mu = 0.
  EXPECT_EQ(linear(t, ContactClass::Wall).emod, 16e9);
  EXPECT_EQ(linear(t, ContactClass::Wall).mu, 0);
}

// Replaces the first occurrence of `from` in the valid text and expects an InputError whose
// key is `key`.
void expect_error(const std::string& from, const std::string& to, const std::string& key) {
  std::string text = kValid;
  const auto at = text.find(from);
  ASSERT_NE(at, std::string::npos) << from;
  text.replace(at, from.size(), to);
  try {
    parse(text);
    ADD_FAILURE() << "no error for '" << to << "'";
  } catch (const InputError& e) {
    EXPECT_EQ(e.key(), key) << e.what();
    EXPECT_NE(std::string(e.what()).find("materials.toml"), std::string::npos) << e.what();
  }
}

TEST(MaterialTable, BadInputNamesTheKey) {
  expect_error("[materials.itz]", "[materials.itx]", "materials.itx");  // unknown class
  expect_error("law = \"contact_bond\"", "law = \"smooth_joint\"", "materials.aggregate.law");
  expect_error("pb_cohesion_MPa = 30\n", "", "materials.mortar.pb_cohesion");   // missing
  expect_error("emod_GPa = 8", "", "materials.itz.emod");                       // missing
  expect_error("emod_GPa = 16", "emod_GPa = 0", "materials.mortar.emod_GPa");   // zero stiffness
  expect_error("\nkratio = 2", "\nkratio = -2", "materials.aggregate.kratio");  // negative
  expect_error("pb_kratio = 2", "pb_kratio = 0", "materials.mortar.pb_kratio");
  expect_error("pb_tensile_strength_MPa = 5", "pb_tensile_strength_MPa = 0",
               "materials.itz.pb_tensile_strength_MPa");
  expect_error("pb_cohesion_MPa = 15", "pb_cohesion_MPa = -15", "materials.itz.pb_cohesion_MPa");
  expect_error("cb_shear_strength_MPa = 60", "cb_shear_strength_MPa = 0",
               "materials.aggregate.cb_shear_strength_MPa");
  expect_error("friction = 1.0", "friction = -0.1", "materials.aggregate.friction");
  expect_error("pb_friction_angle_deg = 30", "pb_friction_angle_deg = 90",
               "materials.mortar.pb_friction_angle_deg");
  expect_error("pb_moment_factor = 0.5", "pb_moment_factor = 1.5",
               "materials.mortar.pb_moment_factor");
  // A bond key under a law that has no such bond is a mistake, not silently ignored.
  expect_error("cb_tensile_strength_MPa = 40", "pb_tensile_strength_MPa = 40",
               "materials.aggregate.pb_tensile_strength_MPa");
  expect_error("emod_GPa = 16", "emod = 16", "materials.mortar.emod");  // no unit
  // The wall is linear only.
  expect_error("[materials.itz]", "[materials.wall]\nlaw = \"parallel_bond\"\n[materials.itz]",
               "materials.wall.law");
  try {
    parse("[materials.mortar]\nlaw = \"linear\"\n");
    ADD_FAILURE();
  } catch (const InputError& e) {
    EXPECT_EQ(e.key(), "materials.mortar.emod");
  }
}

TEST(MaterialTable, FlatJointKeysInSI) {
  const MaterialTable t = read_material_table(InputTable::parse_string(R"(
[materials.mortar]
law = "flat_joint"
emod_GPa = 16
kratio = 1.45
friction = 0.5
fj_tensile_strength_MPa = 7
fj_cohesion_MPa = 21
fj_friction_angle_deg = 30
fj_elements = 4
fj_radius_multiplier = 0.8
fj_slit_fraction = 0.2
[materials.itz]
law = "flat_joint"
emod_GPa = 8
kratio = 1.45
friction = 0.5
fj_tensile_strength_MPa = 3
fj_cohesion_MPa = 9
[materials.aggregate]
law = "linear"
emod_GPa = 20
kratio = 2
friction = 1
)",
                                                                       "fj.toml"));
  const BondModel& m = bond(t, ContactClass::Mortar);
  EXPECT_EQ(m.kind, BondKind::FlatJoint);
  EXPECT_EQ(m.flat_joint.tensile_strength, 7e6);
  EXPECT_EQ(m.flat_joint.cohesion, 21e6);
  EXPECT_NEAR(m.flat_joint.friction_angle, std::numbers::pi / 6, 1e-15);
  EXPECT_EQ(m.flat_joint.elements, 4);
  EXPECT_EQ(m.flat_joint.radius_multiplier, 0.8);
  EXPECT_EQ(m.flat_joint.slit_fraction, 0.2);
  EXPECT_EQ(linear(t, ContactClass::Mortar).mu, 0.5);  // residual friction
  // Defaults: N_r = 2, lambda = 1, phi = 0, no slit.
  const FlatJointParams& itz = bond(t, ContactClass::Itz).flat_joint;
  EXPECT_EQ(itz.elements, 2);
  EXPECT_EQ(itz.radius_multiplier, 1);
  EXPECT_EQ(itz.friction_angle, 0);
  EXPECT_EQ(itz.slit_fraction, 0);
  // The shipped flat-joint samples (the fast and the paper calibrations) parse.
  for (const char* file :
       {"samples/materials/c30_flat_joint.toml", "samples/materials/c30_flat_joint_paper.toml"}) {
    const MaterialTable sample = read_material_table(std::filesystem::path(CDEM_SOURCE_DIR) / file);
    EXPECT_EQ(bond(sample, ContactClass::Mortar).kind, BondKind::FlatJoint) << file;
    EXPECT_EQ(bond(sample, ContactClass::Itz).kind, BondKind::FlatJoint) << file;
  }
}
}  // namespace

namespace {

// The material key table (lab/material_keys.hpp) is the one list: the reader's known keys per
// law come from it, calibration's roles come from it, and a key is listed once.
TEST(MaterialKeys, OneListForTheReaderAndTheCalibration) {
  for (std::size_t i = 0; i < std::size(kMaterialKeys); ++i)
    for (std::size_t j = i + 1; j < std::size(kMaterialKeys); ++j)
      EXPECT_NE(kMaterialKeys[i].name, kMaterialKeys[j].name);
  // Every class reads the linear keys; a flat-jointed one also fj_*, never pb_*.
  const std::vector<std::string> fj = material_keys_of(MaterialLaw::FlatJoint);
  for (const char* key : {"emod", "kratio", "friction", "fj_tensile_strength", "fj_cohesion"})
    EXPECT_NE(std::find(fj.begin(), fj.end(), key), fj.end()) << key;
  EXPECT_EQ(std::find(fj.begin(), fj.end(), "pb_cohesion"), fj.end());
  // A class of each law has at most one key per role (else "the key of role R" is ambiguous).
  for (const MaterialLaw law : {MaterialLaw::Linear, MaterialLaw::ContactBond,
                                MaterialLaw::ParallelBond, MaterialLaw::FlatJoint})
    for (const MaterialRole role : {MaterialRole::Modulus, MaterialRole::StiffnessRatio,
                                    MaterialRole::TensileStrength, MaterialRole::ShearStrength}) {
      int own = 0;
      for (const MaterialKey& k : kMaterialKeys) own += k.law == law && k.role == role;
      EXPECT_LE(own, 1) << material_law_name(law);
    }
  // The key of a role in a class of a law: the law's own, else the linear part's (SPEC 8).
  EXPECT_EQ(material_key_for(MaterialLaw::ParallelBond, MaterialRole::Modulus), "pb_emod");
  EXPECT_EQ(material_key_for(MaterialLaw::ContactBond, MaterialRole::Modulus), "emod");
  EXPECT_EQ(material_key_for(MaterialLaw::ContactBond, MaterialRole::TensileStrength),
            "cb_tensile_strength");
  EXPECT_EQ(material_key_for(MaterialLaw::FlatJoint, MaterialRole::ShearStrength), "fj_cohesion");
  EXPECT_EQ(material_key_for(MaterialLaw::Linear, MaterialRole::TensileStrength), "");
  // The law names the reader accepts, and back.
  for (const MaterialLaw law : {MaterialLaw::Linear, MaterialLaw::ContactBond,
                                MaterialLaw::ParallelBond, MaterialLaw::FlatJoint})
    EXPECT_EQ(find_material_law(material_law_name(law)), law);
  EXPECT_EQ(material_law_name(MaterialLaw::ParallelBond), "parallel_bond");
  EXPECT_FALSE(find_material_law("parallel"));
  // The roles SPEC 8 gives the keys, read from a calibration's dotted, unit-suffixed keys.
  using cdem::calib::parameter_role;
  EXPECT_EQ(parameter_role("materials.mortar.emod_GPa"), MaterialRole::Modulus);
  EXPECT_EQ(parameter_role("materials.itz.pb_kratio"), MaterialRole::StiffnessRatio);
  EXPECT_EQ(parameter_role("materials.mortar.pb_tensile_strength_MPa"),
            MaterialRole::TensileStrength);
  EXPECT_EQ(parameter_role("materials.itz.cb_shear_strength_kPa"), MaterialRole::ShearStrength);
  EXPECT_EQ(parameter_role("materials.mortar.fj_cohesion_Pa"), MaterialRole::ShearStrength);
  EXPECT_EQ(parameter_role("materials.mortar.fj_elements"), MaterialRole::Other);
  EXPECT_EQ(parameter_role("materials.mortar.not_a_key_MPa"), MaterialRole::Other);
  // Unit suffixes: the longest known one is cut ("_mm_s" is a velocity, not "_s" of a time).
  EXPECT_EQ(cdem::key_without_unit("emod_GPa"), "emod");
  EXPECT_EQ(cdem::key_without_unit("platen_velocity_mm_s"), "platen_velocity");
  EXPECT_EQ(cdem::key_without_unit("fj_elements"), "fj_elements");
  EXPECT_EQ(cdem::key_without_unit("kratio"), "kratio");
}

}  // namespace
