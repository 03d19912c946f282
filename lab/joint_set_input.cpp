#include "lab/joint_set_input.hpp"

#include <cmath>
#include <numbers>

#include "core/units.hpp"

namespace cdem::lab {

using namespace cdem::dem;  // the engine the lab layer drives

namespace {

constexpr double kGPaPerM = 1e9;  // Pa/m

// The stiffness keys carry their unit, GPa per m of displacement, in the name.
constexpr const char* kNormalStiffness = "sj_normal_stiffness_GPa_m";
constexpr const char* kShearStiffness = "sj_shear_stiffness_GPa_m";

SmoothJointParams read_properties(const InputTable& t) {
  SmoothJointParams p;
  for (const char* key : {"sj_normal_stiffness", "sj_shear_stiffness"})
    if (t.has(key) && !t.has(std::string(key) + "_GPa_m"))
      t.fail(key, "needs its unit in the key: " + std::string(key) + "_GPa_m (GPa per m)");
  p.normal_stiffness = t.number(kNormalStiffness, Range::positive()) * kGPaPerM;
  p.shear_stiffness = t.number(kShearStiffness, Range::positive()) * kGPaPerM;
  p.tensile_strength =
      t.quantity_or("sj_tensile_strength", Dimension::Stress, 0.0, Range::non_negative());
  p.cohesion = t.quantity_or("sj_cohesion", Dimension::Stress, 0.0, Range::non_negative());
  p.friction_angle =
      t.number_or("sj_friction_angle_deg", 0.0, Range::right_open(0, 90)) * units::degree;
  p.friction = t.number_or("sj_friction", 0.0, Range::closed(0, 10));
  p.dilation_angle =
      t.number_or("sj_dilation_angle_deg", 0.0, Range::right_open(0, 90)) * units::degree;
  p.radius_multiplier = t.number_or("sj_radius_multiplier", 1.0, Range::left_open(0, 10));
  p.bonded = t.boolean_or("sj_bonded", true);
  return p;
}

}  // namespace

std::vector<JointSet> read_joint_sets(const InputTable& test) {
  std::vector<JointSet> sets;
  for (const InputTable& t : test.tables("joints")) {
    t.reject_unknown_keys({"dip_deg", "spacing", "offset", "points", "sj_normal_stiffness_GPa_m",
                           "sj_shear_stiffness_GPa_m", "sj_tensile_strength", "sj_cohesion",
                           "sj_friction_angle_deg", "sj_friction", "sj_dilation_angle_deg",
                           "sj_radius_multiplier", "sj_bonded"});
    JointSet set;
    set.params = read_properties(t);
    const bool family = t.has("dip_deg"), points = t.has("points");
    if (family == points)
      t.fail("dip_deg",
             "give either dip_deg with spacing_mm (a family of parallel lines) or "
             "points_mm = [[x1, y1], [x2, y2]] (one segment)");
    set.family = family;
    if (family) {
      set.dip = t.number("dip_deg", Range::right_open(0, 180)) * units::degree;
      set.spacing = t.quantity("spacing", Dimension::Length, Range::positive());
      set.offset = t.quantity_or("offset", Dimension::Length, 0.0, Range::any());
    } else {
      if (t.has("spacing") || t.has("offset"))
        t.fail(t.has("spacing") ? "spacing" : "offset", "only used with dip_deg");
      if (!t.has("points_mm")) t.fail("points", "needs its unit in the key: points_mm");
      const std::vector<std::vector<double>> rows = t.number_rows("points_mm", 2, Range::any());
      if (rows.size() != 2)
        t.fail("points_mm",
               "needs exactly 2 points [[x1, y1], [x2, y2]], got " + std::to_string(rows.size()));
      set.segment = {rows[0][0] * units::mm, rows[0][1] * units::mm, rows[1][0] * units::mm,
                     rows[1][1] * units::mm};
      if (set.segment.ax == set.segment.bx && set.segment.ay == set.segment.by)
        t.fail("points_mm", "the two points must differ");
    }
    sets.push_back(set);
  }
  return sets;
}

InstalledJoints install_test_joints(World& world, const std::vector<JointSet>& sets,
                                    double gap_ratio, const std::string& file) {
  InstalledJoints installed = install_smooth_joints(world, sets, gap_ratio);
  for (std::size_t s = 0; s < sets.size(); ++s)
    if (installed.contacts[s] == 0)
      throw InputError(file, "test.joints[" + std::to_string(s) + "]",
                       "its lines cross no bonded or touching pair: they miss the specimen "
                       "(a family's lines run through the specimen's centre + offset + m "
                       "spacing; points_mm are in the specimen's frame, mm)");
  return installed;
}

}  // namespace cdem::lab
