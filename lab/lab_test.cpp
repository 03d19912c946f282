#include "lab/lab_test.hpp"
#include "core/units.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <limits>
#include <numbers>
#include <optional>
#include <sstream>
#include <stdexcept>

#include <toml++/toml.h>

#include "core/input_error.hpp"
#include "dem/contact_energy.hpp"
#include "dem/measure.hpp"
#include "dem/strain_measure.hpp"
#include "dem/world_from_specimen.hpp"
#include "lab/biaxial_test.hpp"
#include "lab/loading_arc.hpp"
#include "lab/test_presets.hpp"

namespace cdem::lab {

using namespace cdem::dem;  // the engine the lab layer drives

const char* lab_test_name(LabTestType type) {
  switch (type) {
    case LabTestType::Uniaxial:
      return "uniaxial";
    case LabTestType::Brazilian:
      return "brazilian";
    case LabTestType::DirectTension:
      return "direct_tension";
    case LabTestType::Biaxial:
      return "biaxial";
    case LabTestType::Shpb:
      return "shpb";
    case LabTestType::ThreePointBending:
      return "three_point_bending";
  }
  return "?";
}

namespace {

// The keys of a three-point bending test (docs/lab_tests.md "Three-point bending"); the sizes
// that depend on the beam are checked against it by check_specimen_for_test.
void read_bending_controls(const InputTable& t, LabTestControls& c) {
  for (const char* key : {"stop_fraction", "max_strain", "stop_damage_span"})
    if (t.has(key))
      t.fail(key,
             "not used by three-point bending (stop_load_fraction and max_deflection end it; "
             "its cracks must span half the ligament)");
  // The preset's (or the default) velocity is the compression tests': a notched beam peaks at
  // about a tenth of their platen travel, so at the same velocity it would be loaded in a
  // tenth of the steps, faster than it can carry the load to its supports (measured on the C30
  // beam at 0.005 m/s: supports 57 % of the platen load at the peak).
  if (!t.has("platen_velocity")) c.platen_velocity *= kBendingVelocityFactor;
  c.span = t.quantity("span", Dimension::Length, Range::left_open(0, 10));
  c.bearing_width =
      t.quantity_or("bearing_width", Dimension::Length, 0, Range::left_open(0, c.span / 2));
  c.stop.stop_fraction =
      t.number_or("stop_load_fraction", kDefaultStopLoadFraction, Range::open(0, 1));
  c.max_deflection = t.quantity_or("max_deflection", Dimension::Length, 0, Range::left_open(0, 1));
  c.pin_friction = t.number_or("pin_friction", c.pin_friction, Range::left_open(0, 10));
  c.cmod_control = t.string_or("control", "displacement", {"displacement", "cmod"}) == "cmod";
  if (t.has("cmod_rate") && !c.cmod_control)
    t.fail("cmod_rate", "only used with control = \"cmod\"");
  if (c.cmod_control && t.has("platen_velocity"))
    t.fail("platen_velocity", "control = \"cmod\" drives the platen by cmod_rate");
  c.cmod_rate =
      t.quantity_or("cmod_rate", Dimension::Velocity, c.platen_velocity, Range::positive());
  if (t.has("young_modulus") != t.has("tensile_strength"))
    t.fail(t.has("young_modulus") ? "tensile_strength" : "young_modulus",
           "the characteristic length E G_F / f_t^2 needs both young_modulus and "
           "tensile_strength");
  c.young_modulus = t.quantity_or("young_modulus", Dimension::Stress, 0, Range::left_open(0, 1e13));
  c.tensile_strength =
      t.quantity_or("tensile_strength", Dimension::Stress, 0, Range::left_open(0, 1e10));
}

LabTestControls read_controls(const InputTable& t) {
  t.reject_unknown_keys({"type",
                         "platen_velocity",
                         "stop_fraction",
                         "stop_strain_margin",
                         "stop_confirm_records",
                         "stop_min_cracks",
                         "stop_damage_span",
                         "stop_split",
                         "stop_split_fraction",
                         "stop_split_opening",
                         "max_strain",
                         "local_damping",
                         "time_step_safety",
                         "density_scaling",
                         "scaled_time_step",
                         "density_scaling_step_factor",
                         "history_interval",
                         "snapshot_interval",
                         "max_steps",
                         "grip_fraction",
                         "gauge_fraction",
                         "platen_overhang",
                         "platens",
                         "jaw_radius_ratio",
                         "loading_arc_deg",
                         "threads",
                         "lanes",
                         "min_contacts",
                         "bond_gap_ratio",
                         "max_genesis_broken_fraction",
                         "max_genesis_floating_fraction",
                         "confining_stresses",
                         "preset",
                         "shpb",
                         "span",
                         "bearing_width",
                         "stop_load_fraction",
                         "max_deflection",
                         "young_modulus",
                         "tensile_strength",
                         "pin_friction",
                         "control",
                         "cmod_rate",
                         "fragment_sieve",
                         "joints"});
  LabTestControls c;
  c.joints = read_joint_sets(t);
  apply_test_preset(t, c);  // speed knobs of the preset; the keys below override them
  const std::string type = t.string("type", {"uniaxial", "brazilian", "direct_tension", "biaxial",
                                             "shpb", "three_point_bending"});
  c.type = type == "uniaxial"         ? LabTestType::Uniaxial
           : type == "brazilian"      ? LabTestType::Brazilian
           : type == "direct_tension" ? LabTestType::DirectTension
           : type == "biaxial"        ? LabTestType::Biaxial
           : type == "shpb"           ? LabTestType::Shpb
                                      : LabTestType::ThreePointBending;
  if (c.type == LabTestType::Shpb)
    read_shpb_controls(t, c);
  else if (t.has("shpb"))
    t.fail("shpb", "only used by type = \"shpb\"");
  c.platen_velocity =
      t.quantity_or("platen_velocity", Dimension::Velocity, c.platen_velocity, Range::positive());
  StopRuleOptions& stop = c.stop;
  stop.stop_fraction = t.number_or("stop_fraction", stop.stop_fraction, Range::open(0, 1));
  stop.strain_margin = t.number_or("stop_strain_margin", stop.strain_margin, Range::closed(0, 10));
  stop.confirm_records = t.integer_or("stop_confirm_records", stop.confirm_records, 1, 1'000'000);
  stop.min_cracks = t.integer_or("stop_min_cracks", stop.min_cracks, 0, 1'000'000'000);
  stop.damage_span = t.number_or("stop_damage_span", stop.damage_span, Range::closed(0, 1));
  stop.max_strain = t.number_or("max_strain", stop.max_strain, Range::left_open(0, 1));
  for (const char* key : {"stop_split", "stop_split_fraction", "stop_split_opening"})
    if (c.type != LabTestType::Brazilian && t.has(key))
      t.fail(key, "only used by type = \"brazilian\" (the split of the disc)");
  stop.split.enabled = c.type == LabTestType::Brazilian && t.boolean_or("stop_split", true);
  if (!stop.split.enabled && (t.has("stop_split_fraction") || t.has("stop_split_opening")))
    t.fail(t.has("stop_split_fraction") ? "stop_split_fraction" : "stop_split_opening",
           "not used with stop_split = false");
  stop.split.fraction = t.number_or("stop_split_fraction", stop.split.fraction, Range::open(0, 1));
  // A factor of 1 or less holds at the peak itself: no opening.
  stop.split.opening =
      t.number_or("stop_split_opening", stop.split.opening, Range::left_open(1, 1000));
  c.local_damping = t.number_or("local_damping", c.local_damping, Range::right_open(0, 1));
  c.time_step_safety = t.number_or("time_step_safety", c.time_step_safety, Range::left_open(0, 1));
  c.density_scaling = t.boolean_or("density_scaling", c.density_scaling);
  c.scaled_time_step =
      t.quantity_or("scaled_time_step", Dimension::Time, c.scaled_time_step, Range::positive());
  if (t.has("scaled_time_step") && !c.density_scaling)
    t.fail("scaled_time_step", "only meaningful with density_scaling = true");
  if (t.has("density_scaling_step_factor")) {
    if (t.has("scaled_time_step"))
      t.fail("density_scaling_step_factor",
             "give either scaled_time_step (absolute) or density_scaling_step_factor (relative)");
    if (t.has("density_scaling"))
      t.fail("density_scaling_step_factor", "sets density scaling itself; drop density_scaling");
    c.density_step_factor = t.number("density_scaling_step_factor", Range::left_open(0, 1000));
  } else if (t.has("density_scaling") || t.has("scaled_time_step")) {
    c.density_step_factor = 0;  // the explicit keys override a preset's relative scaling
  }
  c.history_interval = t.integer_or("history_interval", c.history_interval, 1, 1'000'000'000);
  c.snapshot_interval = t.integer_or("snapshot_interval", c.snapshot_interval, 0, 1'000'000'000);
  c.max_steps = t.integer_or("max_steps", c.max_steps, 1, 1'000'000'000'000);
  c.grip_fraction = t.number_or("grip_fraction", c.grip_fraction, Range::open(0, 0.25));
  if (t.has("grip_fraction") && c.type != LabTestType::DirectTension)
    t.fail("grip_fraction", "only used by type = \"direct_tension\"");
  c.gauge_fraction = t.number_or("gauge_fraction", c.gauge_fraction, Range::left_open(0, 1));
  c.platen_overhang = t.number_or("platen_overhang", c.platen_overhang, Range::closed(0, 10));
  if (t.has("platens")) {
    if (c.type != LabTestType::Brazilian) t.fail("platens", "only used by type = \"brazilian\"");
    const std::string platens = t.string("platens", {"flat", "curved_jaws", "loading_arc"});
    c.platens = platens == "curved_jaws"   ? BrazilianPlatens::CurvedJaws
                : platens == "loading_arc" ? BrazilianPlatens::LoadingArc
                                           : BrazilianPlatens::Flat;
  }
  if (t.has("jaw_radius_ratio") && c.platens != BrazilianPlatens::CurvedJaws)
    t.fail("jaw_radius_ratio", "only used with platens = \"curved_jaws\"");
  c.jaw_radius_ratio = t.number_or("jaw_radius_ratio", c.jaw_radius_ratio, Range::closed(1.05, 10));
  if (t.has("loading_arc_deg") && c.platens != BrazilianPlatens::LoadingArc)
    t.fail("loading_arc_deg", "only used with platens = \"loading_arc\"");
  // The whole arc 2 alpha, in degrees: ISRM's jaws load about 10 degrees at failure, the
  // flattened Brazilian disc 20-30; beyond 60 the load is no longer a diametral line load.
  if (t.has("loading_arc_deg"))
    c.loading_arc = t.number("loading_arc_deg", Range::closed(1, 60)) * units::degree;
  c.threads = static_cast<int>(t.integer_or("threads", c.threads, 1, 1024));
  c.lanes = t.boolean_or("lanes", c.lanes);
  c.genesis.min_contacts =
      static_cast<int>(t.integer_or("min_contacts", c.genesis.min_contacts, 0, 12));
  c.genesis.bond_gap_ratio =
      t.number_or("bond_gap_ratio", c.genesis.bond_gap_ratio, Range::closed(0, 0.1));
  c.genesis.max_broken_fraction = t.number_or("max_genesis_broken_fraction",
                                              c.genesis.max_broken_fraction, Range::closed(0, 1));
  c.genesis.max_floating_fraction = t.number_or(
      "max_genesis_floating_fraction", c.genesis.max_floating_fraction, Range::closed(0, 1));
  if (c.type == LabTestType::ThreePointBending) read_bending_controls(t, c);
  for (const char* key :
       {"span", "bearing_width", "stop_load_fraction", "max_deflection", "young_modulus",
        "tensile_strength", "pin_friction", "control", "cmod_rate"})
    if (c.type != LabTestType::ThreePointBending && t.has(key))
      t.fail(key, "only used by type = \"three_point_bending\"");
  if (t.has("fragment_sieve_mm")) {
    c.fragment_sieve = t.numbers("fragment_sieve_mm", Range::positive());
    if (c.fragment_sieve.empty() || c.fragment_sieve.size() > 16)
      t.fail("fragment_sieve_mm",
             "needs 1 to 16 sizes, got " + std::to_string(c.fragment_sieve.size()));
    for (std::size_t i = 1; i < c.fragment_sieve.size(); ++i)
      if (!(c.fragment_sieve[i] > c.fragment_sieve[i - 1]))
        t.fail("fragment_sieve_mm", "sizes must increase (entry " + std::to_string(i) + ")");
    for (double& size : c.fragment_sieve) size *= units::mm;
  } else if (t.has("fragment_sieve")) {  // another unit suffix, or none: name the key given
    std::string key = "fragment_sieve";
    for (const char* other : {"fragment_sieve_m", "fragment_sieve_cm", "fragment_sieve_um"})
      if (t.has(other)) key = other;
    t.fail(key, "the sieve is read in mm only: fragment_sieve_mm = [1, 2, 5, 10, 15]");
  }
  if (c.type == LabTestType::Biaxial)
    c.confining_stresses = read_confining_stresses(t);
  else if (t.has("confining_stresses"))  // any unit suffix
    t.fail("confining_stresses", "only used by type = \"biaxial\"");
  return c;
}

// The generator file an inline [specimen] table stands for: its plain keys (shape, sizes) form
// the generator's [specimen], its sub-tables ([specimen.gradation], ...) the generator's root
// tables. toml++ writes floating-point values so that they read back to the same bits.
std::string generator_text(const toml::table& inline_spec) {
  toml::table generator, container;
  for (const auto& [key, value] : inline_spec) {
    if (value.is_table())
      generator.insert(key, value);
    else
      container.insert(key, value);
  }
  generator.insert("specimen", std::move(container));
  std::ostringstream text;
  text << generator << "\n";
  return text.str();
}

}  // namespace

LabTestControls read_lab_test_controls(const InputTable& test) {
  return read_controls(test);
}

LabTestInput read_lab_test(const InputTable& input, const std::filesystem::path& base_dir) {
  input.reject_unknown_keys({"seed", "specimen", "materials", "test"});
  LabTestInput out;
  out.file = input.file();
  out.text = input.source_text();
  out.seed = static_cast<std::uint64_t>(
      input.integer_or("seed", 0, 0, std::numeric_limits<long long>::max()));

  // The specimen: a file written by `cdem generate`, or an inline generator table.
  const toml::table root = toml::parse(input.source_text());
  if (const toml::table* inline_spec = root["specimen"].as_table()) {
    out.specimen_path = input.file() + " [specimen]";
    out.specimen_generator = generator_text(*inline_spec);
  } else {
    const std::filesystem::path specimen = input.string("specimen");
    out.specimen_path = specimen.is_absolute() ? specimen : base_dir / specimen;
    if (!std::filesystem::is_regular_file(out.specimen_path))
      input.fail("specimen", "file " + out.specimen_path.string() +
                                 " not found (a specimen HDF5 written by `cdem generate`)");
  }

  // Materials: inline [materials.*] tables or the name of a file holding them.
  const toml::node* materials = root.get("materials");
  if (!materials)
    input.fail("materials",
               "missing: give [materials.mortar], [materials.itz], "
               "[materials.aggregate] tables or materials = \"file.toml\"");
  if (materials->is_string()) {
    const std::filesystem::path name = input.string("materials");
    const std::filesystem::path file = name.is_absolute() ? name : base_dir / name;
    if (!std::filesystem::is_regular_file(file))
      input.fail("materials", "file " + file.string() + " not found");
    const InputTable table = InputTable::parse_file(file);
    out.materials = read_material_table(table);
    out.materials_text = table.source_text();
  } else {
    out.materials = read_material_table(input);
  }
  out.controls = read_controls(input.table("test"));
  return out;
}

LabTestInput read_lab_test(const std::filesystem::path& file) {
  if (!std::filesystem::is_regular_file(file))
    throw InputError(file.string(), "", "test file not found");
  return read_lab_test(InputTable::parse_file(file), file.parent_path());
}

double bearing_width(const LabTestControls& c, const Container& beam) {
  return c.bearing_width > 0 ? c.bearing_width : kDefaultBearingFraction * beam.height;
}

void check_specimen_for_test(const Specimen& specimen, const LabTestInput& input) {
  require_classes(input.materials, specimen.clumps.size(), input.specimen_path.string());
  const bool disc = specimen.container.shape == ContainerShape::Disc;
  const LabTestType type = input.controls.type;
  if (type == LabTestType::Brazilian && !disc)
    throw InputError(input.file, "test.type",
                     "a Brazilian test needs a disc specimen; " + input.specimen_path.string() +
                         " is a rectangle");
  if (type != LabTestType::Brazilian && type != LabTestType::Shpb && disc)
    throw InputError(input.file, "test.type",
                     std::string("a ") + lab_test_name(type) +
                         " test needs a rectangular "
                         "specimen; " +
                         input.specimen_path.string() + " is a disc (use \"brazilian\")");
  if (specimen.disc_count() == 0)
    throw InputError(input.specimen_path.string(), "", "the specimen holds no discs");
  const Container& beam = specimen.container;
  if (type != LabTestType::ThreePointBending) {
    if (beam.notched())
      throw InputError(input.file, "test.type",
                       std::string("a ") + lab_test_name(type) + " test needs an unnotched " +
                           "specimen; " + input.specimen_path.string() +
                           " is a notched beam (use \"three_point_bending\")");
    return;
  }
  // The supports' plates must lie under the beam, and clear of the notch.
  const LabTestControls& c = input.controls;
  const double plate = bearing_width(c, beam);
  std::ostringstream range;
  range << "the supports (plates " << plate * 1e3 << " mm long at mid-span +- S/2) must lie "
        << "under the " << beam.width * 1e3 << " mm beam and clear of the notch: S in ("
        << (beam.notched() ? beam.notch_width : 0) * 1e3 + plate * 1e3 << ", "
        << (beam.width - plate) * 1e3 << "] mm, got " << c.span * 1e3 << " mm";
  if (c.span > beam.width - plate || c.span - plate <= (beam.notched() ? beam.notch_width : 0))
    throw InputError(input.file, "test.span", range.str());
}

void LabHistory::reserve(std::size_t n) {
  step.reserve(n);
  for (auto* v : {&time, &axial_strain, &lateral_strain, &axial_stress, &confining_stress,
                  &platen_force, &kinetic_energy, &strain_energy, &friction_energy,
                  &breakage_energy, &boundary_work, &deflection, &cmod, &support_reaction})
    v->reserve(n);
  bonds_broken.reserve(n);
}

void LabHistory::push_energies(const World& world, double boundary_work_so_far) {
  const ContactEnergy energy = contact_energy(world);
  kinetic_energy.push_back(cdem::dem::kinetic_energy(world));
  strain_energy.push_back(energy.strain());
  friction_energy.push_back(energy.friction);
  breakage_energy.push_back(energy.bond_breakage);
  boundary_work.push_back(boundary_work_so_far);
  bonds_broken.push_back(static_cast<long>(world.cracks().size()));
}

namespace {

// How the specimen is loaded: two platens (walls), two bands of prescribed bodies (the grips of
// direct tension, or a Brazilian disc's loading arcs), or (three-point bending) two fixed
// supports under the beam (bottom_wall and right_support) and the loading platen (top_wall) on
// it.
struct Loading {
  bool grips = false;  // the ends are the bands bottom_grip and top_grip
  // +1: the bands pull the specimen apart (direct tension), -1: they push it together (loading
  // arcs), so that force and travel are positive in the sense of the test.
  double band_sense = 1;
  bool bending = false;
  int bottom_wall = -1, top_wall = -1, right_support = -1;
  std::vector<std::int32_t> bottom_grip, top_grip;  // bodies
  double top_y0 = 0, bottom_y0 = 0;                 // m, reference of the travel
  double gauge_length = 0;                          // m, length the axial strain refers to
  // m, the force (N/m) over this length and the thickness is the nominal stress: W (or D), or
  // 2 H^2 / (3 S) of a beam (the flexural stress 3 P S / (2 t H^2))
  double section = 0;

  // Force of the specimen on the loading pair, mean of the two ends (N per m), positive in the
  // sense of the test (compression for platens, tension for grips); a beam: the platen's load P.
  double force(const World& w) const {
    if (bending) return w.walls().fy[top_wall];
    if (!grips) return 0.5 * (w.walls().fy[top_wall] - w.walls().fy[bottom_wall]);
    double top = 0, bottom = 0;
    // Body by body, not bodies(): that would catch up every body each step (dem/world.hpp).
    for (const std::int32_t b : top_grip) top += w.body_motion(b).fy;
    for (const std::int32_t b : bottom_grip) bottom += w.body_motion(b).fy;
    return 0.5 * band_sense * (bottom - top);
  }
  // Sum of the supports' reactions on a beam (N per m), upward positive.
  double support_reaction(const World& w) const {
    return -(w.walls().fy[bottom_wall] + w.walls().fy[right_support]);
  }
  // Change of the distance between the two ends (m), positive in the sense of the test; a beam:
  // the load point's deflection (the supports stand still).
  double travel(const World& w) const {
    if (!grips) return (top_y0 - bottom_y0) - (w.walls().ay[top_wall] - w.walls().ay[bottom_wall]);
    return band_sense * ((w.body_motion(top_grip.front()).y - top_y0) -
                         (w.body_motion(bottom_grip.front()).y - bottom_y0));
  }
  // Work done on the specimen by the loading ends over one step of length dt (J per m).
  double work(const World& w, double dt) const {
    double p = 0;
    if (!grips) {
      for (const int k : {bottom_wall, top_wall, right_support})
        if (k >= 0) p -= w.walls().fx[k] * w.walls().vx[k] + w.walls().fy[k] * w.walls().vy[k];
    } else {
      for (const auto* band : {&bottom_grip, &top_grip})
        for (const std::int32_t b : *band) {
          const BodyMotion m = w.body_motion(b);
          p -= m.fx * m.vx + m.fy * m.vy;
        }
    }
    return p * dt;
  }
};

struct Extent {
  double xmin = std::numeric_limits<double>::infinity(), ymin = xmin;
  double xmax = -std::numeric_limits<double>::infinity(), ymax = xmax;
};

Extent disc_extent(const World& w) {
  Extent e;
  const Discs& s = w.discs();
  for (std::size_t i = 0; i < s.size(); ++i) {
    e.xmin = std::min(e.xmin, s.x[i] - s.r[i]);
    e.xmax = std::max(e.xmax, s.x[i] + s.r[i]);
    e.ymin = std::min(e.ymin, s.y[i] - s.r[i]);
    e.ymax = std::max(e.ymax, s.y[i] + s.r[i]);
  }
  return e;
}

// The curved jaws of a Brazilian test (ISRM suggested method: jaw radius 1.5 x the disc's),
// bottom then top: arcs about the disc's vertical axis covering +- jaw_cover of its boundary,
// each placed where it touches the first disc of the relaxed specimen (the closest disc centre
// to the jaw's circle, at r_i inside it: a jaw circle of radius R_j about (x_c, y_j) holds disc
// i when |c_i - (x_c, y_j)| <= R_j - r_i).
Walls make_jaws(const LabTestControls& c, const Discs& d, const Extent& e) {
  const double radius = 0.5 * (e.xmax - e.xmin), xc = 0.5 * (e.xmin + e.xmax);
  const double rj = c.jaw_radius_ratio * radius;
  const double half_angle = std::asin(std::sin(c.jaw_cover) / c.jaw_radius_ratio);
  const double reach = rj * std::sin(half_angle);  // m, half the chord
  double y_bottom = std::numeric_limits<double>::infinity(), y_top = -y_bottom;
  for (std::size_t i = 0; i < d.size(); ++i) {
    const double dx = d.x[i] - xc;
    if (std::abs(dx) > reach) continue;
    const double h = std::sqrt((rj - d.r[i]) * (rj - d.r[i]) - dx * dx);
    y_bottom = std::min(y_bottom, d.y[i] + h);  // bottom jaw: its centre above the disc
    y_top = std::max(y_top, d.y[i] - h);
  }
  const double pi = std::numbers::pi;
  Walls jaws;
  jaws.add_arc(xc, y_bottom, rj, -0.5 * pi, half_angle);
  jaws.add_arc(xc, y_top, rj, 0.5 * pi, half_angle);
  jaws.vy[0] = c.platen_velocity;
  jaws.vy[1] = -c.platen_velocity;
  return jaws;
}

// The platens of a uniaxial or Brazilian test, as walls not yet in a world: bottom then top,
// tangent to the outermost discs of the relaxed specimen (the mould faces were flat and every
// boundary disc touched them, so a uniaxial specimen's ends are flat to within the relaxation),
// wider than the specimen so a bulging specimen stays on them; or the curved jaws
// (none for grips, loading arcs and three-point bending).
Walls make_platens(const LabTestControls& c, const Discs& d, const Extent& e) {
  Walls platens;
  if (c.type == LabTestType::DirectTension || c.type == LabTestType::ThreePointBending ||
      c.platens == BrazilianPlatens::LoadingArc)
    return platens;
  if (c.platens == BrazilianPlatens::CurvedJaws) return make_jaws(c, d, e);
  const double y0 = e.ymin, y1 = e.ymax, x0 = e.xmin, x1 = e.xmax;
  const double over = c.platen_overhang * (x1 - x0);
  platens.add(x0 - over, y0, x1 + over, y0);
  platens.add(x1 + over, y1, x0 - over, y1);
  platens.vy[0] = c.platen_velocity;
  platens.vy[1] = -c.platen_velocity;
  return platens;
}

// Height (m) at which a horizontal plate over [xa, xb] first touches the discs coming from
// above (`from_above`, the loading platen: the highest touching height) or from below (a
// support: the lowest). The beam's faces are rough at the scale of a disc, so a short plate
// set at the specimen's extent could hang a fraction of a radius clear of the discs under it.
double plate_height(const World& world, double xa, double xb, bool from_above) {
  const Discs& d = world.discs();
  double best = from_above ? -std::numeric_limits<double>::infinity()
                           : std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < d.size(); ++i) {
    if (!d.active[i]) continue;
    const double dx = std::max({xa - d.x[i], d.x[i] - xb, 0.0});
    if (dx >= d.r[i]) continue;
    const double reach = std::sqrt(d.r[i] * d.r[i] - dx * dx);
    best = from_above ? std::max(best, d.y[i] + reach) : std::min(best, d.y[i] - reach);
  }
  return best;
}

// Three-point bending: short flat plates (walls) of length bearing_width, two supports under
// the beam at mid-span +- S/2 and the loading platen on it at mid-span, each touching the
// first disc in its way, the platen moving down at the platen velocity. The left support is
// the pin of RILEM's pin-and-roller arrangement, a plate with friction pin_friction: the only
// horizontal restraint, without which the 2D beam on frictionless plates is a mechanism that
// drifts sideways off the platen (measured on a 40 x 160 mm beam: 0.5 mm/s, contact lost
// within 6,000 steps). The other support and the platen take materials.wall. A wall's contact
// includes its end points, so a plate's ends act as rounded edges (docs/lab_tests.md
// "Three-point bending" says why plates and not rollers).
Loading set_up_bending(World& world, const Specimen& specimen, const LabTestControls& c) {
  const Container& beam = specimen.container;
  const double xc = 0.5 * beam.width, half_span = 0.5 * c.span;
  const double half_plate = 0.5 * bearing_width(c, beam);
  Loading l;
  l.bending = true;
  const auto support = [&](double x) {
    const double y = plate_height(world, x - half_plate, x + half_plate, false);
    return world.add_wall(x - half_plate, y, x + half_plate, y);
  };
  l.bottom_wall = support(xc - half_span);
  world.set_wall_friction(l.bottom_wall, c.pin_friction);
  l.right_support = support(xc + half_span);
  const double top = plate_height(world, xc - half_plate, xc + half_plate, true);
  l.top_wall = world.add_wall(xc + half_plate, top, xc - half_plate, top);
  world.set_wall_velocity(l.top_wall, 0, -c.platen_velocity);
  l.bottom_y0 = world.walls().ay[l.bottom_wall];
  l.top_y0 = top;
  l.gauge_length = beam.height;
  l.section = 2 * beam.height * beam.height / (3 * c.span);
  return l;
}

Loading set_up_loading(World& world, const Specimen& specimen, const LabTestInput& input,
                       const Walls& platens, const Extent& e) {
  const LabTestControls& c = input.controls;
  Loading l;
  const double v = c.platen_velocity;
  if (c.type == LabTestType::ThreePointBending) return set_up_bending(world, specimen, c);
  const bool arcs = c.platens == BrazilianPlatens::LoadingArc;
  if (c.type != LabTestType::DirectTension && !arcs) {
    l.bottom_wall = world.append_wall(platens, 0);
    l.top_wall = world.append_wall(platens, 1);
    // The platens' displacements are those of any of their points (they translate); the gauge
    // is the specimen's extent between them, where flat platens sit.
    l.bottom_y0 = platens.ay[0];
    l.top_y0 = platens.ay[1];
    l.gauge_length = e.ymax - e.ymin;
    l.section = specimen.container.width;
    return l;
  }
  l.grips = true;
  const double height = e.ymax - e.ymin;
  if (arcs) {
    // The disc's circle is that of the relaxed specimen's extent; the strain refers to D as
    // with platens.
    const DiscCircle circle{0.5 * (e.xmin + e.xmax), 0.5 * (e.ymin + e.ymax),
                            0.25 * ((e.xmax - e.xmin) + height)};
    LoadingArcBodies a = loading_arc_bodies(world, circle, 0.5 * c.loading_arc);
    l.bottom_grip = std::move(a.bottom);
    l.top_grip = std::move(a.top);
    l.band_sense = -1;
    l.gauge_length = height;
    if (l.bottom_grip.empty() || l.top_grip.empty()) {
      std::ostringstream msg;
      msg << "a loading arc of " << c.loading_arc / units::degree
          << " degrees holds no boundary disc of the " << 2e3 * circle.radius
          << " mm disc; widen it (allowed 1 to 60 degrees)";
      throw InputError(input.file, "test.loading_arc_deg", msg.str());
    }
  } else {
    // Grip bands: every body whose centroid lies within grip_fraction x H of an end moves with
    // that end (a clump reaching into the band moves whole).
    const double band = c.grip_fraction * height;
    for (std::size_t b = 0; b < world.bodies().size(); ++b) {
      const double y = world.bodies().y[b];
      if (y <= e.ymin + band)
        l.bottom_grip.push_back(static_cast<std::int32_t>(b));
      else if (y >= e.ymax - band)
        l.top_grip.push_back(static_cast<std::int32_t>(b));
    }
    if (l.bottom_grip.empty() || l.top_grip.empty())
      throw InputError(input.file, "test.grip_fraction", "a grip band holds no disc; widen it");
    l.gauge_length = height - 2 * band;
  }
  const double v_top = l.band_sense * v;  // m/s, up for grips, down for loading arcs
  for (const auto& [band_bodies, vy] :
       {std::pair{&l.bottom_grip, -v_top}, std::pair{&l.top_grip, v_top}})
    for (const std::int32_t b : *band_bodies) {
      world.set_prescribed(b, true);
      world.set_body_velocity(b, 0, vy, 0);
    }
  l.bottom_y0 = world.bodies().y[l.bottom_grip.front()];
  l.top_y0 = world.bodies().y[l.top_grip.front()];
  l.section = specimen.container.width;
  return l;
}

// Three-point bending ending at max_deflection: below this fraction of the peak load the beam
// has failed (a softening tail), above it the peak is not confirmed and the run is an error.
constexpr double kTailLoadFraction = 0.5;

// The RILEM figures of a finished three-point bending test from its history.
BendingResult analyse_bending(const LabHistory& h, const Specimen& beam, const LabTestControls& c,
                              double plate, const World& world) {
  BendingResult b;
  const Container& mould = beam.container;
  b.span = c.span;
  b.depth = mould.height;
  b.notch_depth = mould.notch_depth;
  b.length = mould.width;
  b.bearing_width = plate;
  const std::size_t peak = static_cast<std::size_t>(
      std::max_element(h.platen_force.begin(), h.platen_force.end()) - h.platen_force.begin());
  b.peak_load = h.platen_force[peak];
  b.deflection_at_peak = h.deflection[peak];
  b.cmod_at_peak = h.cmod[peak];
  b.reaction_at_peak = h.support_reaction[peak];
  const double ligament = b.depth - b.notch_depth;
  b.flexural_strength = flexural_strength(b.peak_load, b.span, b.depth, kThickness);
  b.net_flexural_strength = flexural_strength(b.peak_load, b.span, ligament, kThickness);
  b.work_of_fracture = work_under_curve(h.deflection, h.platen_force);
  b.final_deflection = h.deflection.back();
  b.final_load = h.platen_force.back();
  double mass = 0;  // kg/m, physical masses (density scaling leaves them)
  for (const double m : world.bodies().mass) mass += m;
  b.mass_between_supports = mass * b.span / b.length;
  b.self_weight_work = b.mass_between_supports * kStandardGravity * b.final_deflection;
  b.fracture_energy = rilem_fracture_energy(b.work_of_fracture, b.mass_between_supports,
                                            b.final_deflection, ligament, kThickness);
  b.fracture_energy_no_weight =
      rilem_fracture_energy(b.work_of_fracture, 0, 0, ligament, kThickness);
  b.stored_energy = h.strain_energy.back() - h.strain_energy.front();
  b.dissipated_work = (h.boundary_work.back() - h.boundary_work.front()) - b.stored_energy -
                      (h.kinetic_energy.back() - h.kinetic_energy.front());
  b.dissipated_fracture_energy =
      rilem_fracture_energy(b.dissipated_work, 0, 0, ligament, kThickness);
  if (c.young_modulus > 0 && c.tensile_strength > 0)
    b.characteristic_length =
        characteristic_length(c.young_modulus, b.fracture_energy, c.tensile_strength);
  return b;
}

// A run where no bond has broken by this fraction of max_steps is warned about: the C30 UCS
// breaks its first bond at about 60 % of its 82,000 loading steps, 1 % of the default bound, so a
// run that reaches 10 % without one is loading far more slowly, or far more gently, than meant.
constexpr double kQuietFraction = 0.1;

// The largest density-scaling step factor measured (docs/speed_vs_error.md, C30 UCS, 3 seeds).
constexpr double kMeasuredStepFactor = 8;

// Density scaling with a step beyond the measured factors changes the figures by an amount
// nobody has measured. `factor`: the scaled step over the true-mass step.
void warn_density_scaling(LabTestResult& res, const LabTestHooks& hooks, double factor) {
  if (!(factor > kMeasuredStepFactor)) return;
  std::ostringstream msg;
  msg << "density scaling with the step at " << factor
      << " x the true-mass step, beyond the measured range (docs/speed_vs_error.md, C30 UCS: "
         "4x gave sigma_u -0.7 +- 2.2 %, 8x +3.2 +- 1.1 %, 16x with 0.02 m/s platens "
         "+8.9 +- 3.1 %, E within 1.1 %); the error of this run is not known";
  warn(res, hooks, msg.str());
}

// Loading arcs that drive fewer discs than this at a pole load the disc nearly at a point, as a
// flat platen's first contact does (the validation's 15 degree arcs drive about 4 to 11 discs
// on D 50 mm discs of R_min 0.3 mm, docs/lab_tests.md "Loading arcs").
constexpr std::size_t kFewArcDiscs = 3;

void warn_few_arc_discs(LabTestResult& res, const LabTestHooks& hooks, const Loading& loading,
                        const LabTestControls& c) {
  const std::size_t bottom = loading.bottom_grip.size(), top = loading.top_grip.size();
  if (std::min(bottom, top) >= kFewArcDiscs) return;
  std::ostringstream msg;
  msg << "the loading arcs of " << c.loading_arc / units::degree << " degrees drive " << bottom
      << " disc(s) at the bottom and " << top << " at the top: fewer than " << kFewArcDiscs
      << " load the disc nearly at a point, as a flat platen's first contacts do "
         "(docs/lab_tests.md \"Loading arcs\"); widen test.loading_arc_deg";
  warn(res, hooks, msg.str());
}

// Relative density scaling (test.density_scaling_step_factor): the automatic step of the true
// masses with the test's walls in place, times the factor, becomes the scaled step; every body's
// inertia is then set for it at the next rebuild. Velocities are zero here (end of genesis), so
// no kinetic energy changes with the masses.
void scale_density_from_here(World& world, double factor) {
  world.refresh_neighbors();
  world.set_density_scaling(true, factor * world.time_step());
}

}  // namespace

StopRuleOptions loading_stop_options(const LabTestControls& c, const Container& specimen) {
  StopRuleOptions stop = c.stop;
  if (c.type != LabTestType::ThreePointBending) return stop;
  // The stop rule follows deflection / H as its strain.
  const double depth = specimen.height;
  stop.max_strain =
      (c.max_deflection > 0 ? c.max_deflection : kDefaultMaxDeflectionFraction * depth) / depth;
  // The crack grows from the notch tip: a failure is a crack across half the ligament (the
  // bands of the notch itself can hold none).
  stop.damage_span = 0.5 * (depth - specimen.notch_depth) / depth;
  return stop;
}

namespace {

// The fragments of the world at the end of a run, with the aggregates' outlines for the picture
// (`specimen`: the one the world was built from, `index` where its parts went).
Fragments fragments_at_end(const World& world, const Specimen& specimen, const WorldIndex& index,
                           const LabTestControls& c) {
  Fragments f = find_fragments(world, specimen.aggregate_density, c.fragment_sieve);
  add_clump_outlines(f, world, specimen, index.clump_body);
  return f;
}

}  // namespace

void warn(LabTestResult& res, const LabTestHooks& hooks, const std::string& message) {
  res.warnings.push_back(message);
  if (hooks.warning)
    hooks.warning(message);
  else
    std::fprintf(stderr, "cdem: warning: %s\n", message.c_str());
}

void tally_cracks(LabTestResult& res, const CrackLog& log, double time0) {
  res.cracks = log.cracks;
  for (Crack& k : res.cracks) k.time -= time0;
  for (const Crack& k : res.cracks) {
    const int mode = static_cast<int>(k.mode) - 1, cls = static_cast<int>(k.contact_class);
    if (mode >= 0 && mode < 2 && cls >= 0 && cls < 3) ++res.crack_count[mode][cls];
  }
}

LabTestResult run_lab_test(const Specimen& specimen, const LabTestInput& input,
                           const LabTestHooks& hooks) {
  check_specimen_for_test(specimen, input);
  const auto wall_start = std::chrono::steady_clock::now();
  const LabTestControls& c = input.controls;
  const bool bending = c.type == LabTestType::ThreePointBending;
  WorldSettings settings;
  input.materials.apply(settings);
  settings.local_damping = c.local_damping;
  settings.time_step_safety = c.time_step_safety;
  settings.density_scaling = c.density_scaling;
  settings.scaled_time_step = c.scaled_time_step;
  settings.threads = c.threads;
  settings.lanes = c.lanes ? dem::LaneIsa::Avx512 : dem::LaneIsa::None;

  LabTestResult res;
  res.type = c.type;
  const Specimen cleaned = remove_floating_discs(specimen, settings, c.genesis, res.genesis);
  WorldIndex index;
  World world = world_from_specimen(cleaned, settings, &index);
  install_test_bonds(world, c.genesis, res.genesis);
  res.joints = install_test_joints(world, c.joints, c.genesis.bond_gap_ratio, input.file);
  // The relaxed state is the reference: displacements, strains, time and steps count from here.
  const Extent e = disc_extent(world);
  clip_joint_lines(res.joints, e.xmin, e.ymin, e.xmax, e.ymax);
  if (c.type == LabTestType::Shpb) {
    run_shpb_test(world, Box{e.xmin, e.ymin, e.xmax, e.ymax},
                  specimen.container.shape == ContainerShape::Disc, input, hooks, res);
    res.fragments = fragments_at_end(world, cleaned, index, c);
    res.joint_states = joint_states(world, res.cracks, 0);
    res.wall_time =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count();
    return res;
  }
  const Walls platens = make_platens(c, world.discs(), e);
  Loading loading = set_up_loading(world, cleaned, input, platens, e);
  if (c.platens == BrazilianPlatens::LoadingArc) warn_few_arc_discs(res, hooks, loading, c);
  if (c.density_step_factor > 0) {
    scale_density_from_here(world, c.density_step_factor);
    warn_density_scaling(res, hooks, c.density_step_factor);
  } else if (c.density_scaling) {
    World true_masses = world;  // the absolute step against the step the true masses allow
    true_masses.set_density_scaling(false, true_masses.settings().scaled_time_step);
    true_masses.refresh_neighbors();
    warn_density_scaling(res, hooks, c.scaled_time_step / true_masses.time_step());
  }
  // Biaxial: side walls, isotropic consolidation at sigma_3, then the platens load from the
  // consolidated state, which becomes the reference of strains, time and steps.
  std::optional<Confinement> confinement;
  if (c.type == LabTestType::Biaxial && c.confining_stress > 0) {
    confinement.emplace(world, c.confining_stress, c.platen_velocity, loading.bottom_wall,
                        loading.top_wall, e.xmin, e.xmax, e.ymin, e.ymax, c.confinement);
    res.consolidation = confinement->consolidate(world);
    loading.bottom_y0 = world.walls().ay[loading.bottom_wall];
    loading.top_y0 = world.walls().ay[loading.top_wall];
    loading.gauge_length = loading.top_y0 - loading.bottom_y0;
    world.set_wall_velocity(loading.bottom_wall, 0, c.platen_velocity);
    world.set_wall_velocity(loading.top_wall, 0, -c.platen_velocity);
  }
  res.confining_stress = c.type == LabTestType::Biaxial ? c.confining_stress : 0;
  const long step0 = world.step_count();
  const double time0 = world.time();
  world.refresh_neighbors();
  res.time_step = world.time_step();
  res.walls = world.walls();
  res.width =
      c.type == LabTestType::Brazilian || bending ? specimen.container.width : loading.section;
  res.height = c.type == LabTestType::Brazilian ? specimen.container.width : loading.gauge_length;

  // Lateral strain and confining stress from the central region (middle gauge_fraction of H).
  const double ymid = 0.5 * (e.ymin + e.ymax), half = 0.5 * c.gauge_fraction * (e.ymax - e.ymin);
  const Box gauge_box{e.xmin, ymid - half, e.xmax, ymid + half};
  const StrainGauge gauge(world, gauge_box);
  res.gauge_discs = gauge.disc_count();

  LabHistory& h = res.history;
  const long max_records = c.max_steps / c.history_interval + 2;
  h.reserve(static_cast<std::size_t>(std::min<long>(max_records, 1'000'000)));
  const bool biaxial = c.type == LabTestType::Biaxial;
  double boundary_work = 0;
  // Bonds intact when the loading starts: installed, less those the relaxation and (biaxial)
  // the consolidation broke.
  long installed = 0;
  for (const long b : res.genesis.bonds) installed += b;
  const long intact_bonds =
      installed - res.genesis.relaxation_cracks - static_cast<long>(world.cracks().size());
  if (installed > 0 && intact_bonds <= 0)
    warn(res, hooks,
         "every bond broke before the loading (genesis relaxation or consolidation): the "
         "test loads a cohesionless packing, and its peak is friction's");
  std::optional<CmodGauge> cmod;
  const StopRuleOptions stop_options = loading_stop_options(c, cleaned.container);
  std::optional<CmodServo> servo;
  if (bending && c.cmod_control)
    servo = CmodServo{.cmod_rate = c.cmod_rate,
                      .max_velocity = kCmodServoSpeedCap * c.cmod_rate,
                      .hold_fraction = c.stop.stop_fraction};
  if (bending) cmod.emplace(world, cleaned.container, e.ymin);
  PeakStopRule stop(stop_options, e.xmin, e.ymin, e.xmax, e.ymax, intact_bonds,
                    world.cracks().size());
  const long quiet_steps = static_cast<long>(kQuietFraction * static_cast<double>(c.max_steps));
  bool quiet_warned = false;
  // The stress (Pa) the peak and the stop rule follow: axial, or the deviator of a biaxial test.
  const auto last_loading_stress = [&] {
    return biaxial ? h.axial_stress.back() - h.confining_stress.back() : h.axial_stress.back();
  };
  const auto record = [&](bool at_max_steps) {
    const double force = loading.force(world);
    const double section = confinement ? confinement->width(world) : loading.section;
    h.step.push_back(world.step_count() - step0);
    h.time.push_back(world.time() - time0);
    h.axial_strain.push_back(loading.travel(world) / loading.gauge_length);
    h.lateral_strain.push_back(-gauge.gradient(world)(0, 0));
    h.axial_stress.push_back(force / (section * kThickness));
    h.confining_stress.push_back(confinement ? confinement->side_stress(world)
                                 : biaxial   ? 0.0
                                             : contact_stress(world, gauge_box)(0, 0));
    h.platen_force.push_back(force);
    h.push_energies(world, boundary_work);
    if (bending) {
      h.deflection.push_back(loading.travel(world));
      h.cmod.push_back(cmod->opening(world));
      h.support_reaction.push_back(loading.support_reaction(world));
    }
    const StopReason reason = stop.observe(h.axial_strain.back(), last_loading_stress(),
                                           h.lateral_strain.back(), world.cracks(), at_max_steps);
    if (hooks.progress) hooks.progress(h, stop.peak(), c.max_steps);
    if (reason == StopReason::None && hooks.should_stop && hooks.should_stop(world, h)) {
      warn(res, hooks,
           "stopped by the caller before the stop rule confirmed a peak: the peak stress "
           "is the largest so far, not a strength");
      return StopReason::StoppedByUser;
    }
    if (!quiet_warned && stop.cracks() == 0 && intact_bonds > 0 &&
        h.step.back() >= std::max(quiet_steps, 1L)) {
      quiet_warned = true;
      std::ostringstream msg;
      msg << "no bond broke in the first " << 100 * kQuietFraction << " % of max_steps ("
          << h.step.back() << " steps, axial strain " << h.axial_strain.back() << ", stress "
          << last_loading_stress() * 1e-6
          << " MPa): bonds far stronger than the contact forces this loading reaches, or a "
             "platen that does not load the specimen";
      warn(res, hooks, msg.str());
    }
    return reason;
  };

  // The steps after which the loop records and snapshots: only they read the per-pair results
  // (the confining stress, the energies, the snapshots), so only they keep them (32 bytes per
  // pair and step; docs/performance.md "Session 28").
  const auto records_after = [&](long s) {
    return s % c.history_interval == 0 || s >= c.max_steps;
  };
  const bool snapshots = hooks.snapshot && c.snapshot_interval > 0;
  const auto snapshots_after = [&](long s) { return snapshots && s % c.snapshot_interval == 0; };
  const PairResultsOnRequestScope on_request(world);

  StopReason reason = record(false);
  if (snapshots) hooks.snapshot(world, world.step_count() - step0, world.time() - time0);
  while (reason == StopReason::None) {
    if (confinement) confinement->update_targets(world);
    if (servo)
      world.set_wall_velocity(loading.top_wall, 0,
                              -servo->platen_velocity(cmod->opening(world), world.time() - time0,
                                                      world.time_step(), loading.force(world)));
    const long s = world.step_count() - step0 + 1;  // after this step
    if (records_after(s) || snapshots_after(s)) world.request_pair_results();
    world.step();
    boundary_work += loading.work(world, world.time_step());
    if (records_after(s)) reason = record(s >= c.max_steps);
    if (reason != StopReason::None) break;
    if (snapshots_after(s)) hooks.snapshot(world, world.step_count() - step0, world.time() - time0);
  }
  // A beam whose load has passed its peak and fallen well below it but still carries a tail at
  // max_deflection ends there with its figures; the work of the missing tail is not counted.
  if (bending && reason == StopReason::MaxStrain &&
      h.platen_force.back() <
          kTailLoadFraction * *std::max_element(h.platen_force.begin(), h.platen_force.end()))
    reason = StopReason::MaxDeflection;
  const bool bending_tail = reason == StopReason::MaxDeflection;
  if (reason != StopReason::PostPeakDrop && reason != StopReason::Split &&
      reason != StopReason::StoppedByUser && !bending_tail) {
    std::ostringstream msg;
    msg << "the " << lab_test_name(c.type) << " test stopped at "
        << (reason == StopReason::MaxSteps ? "max_steps = " + std::to_string(c.max_steps)
            : bending
                ? "max_deflection = " +
                      std::to_string(stop_options.max_strain * cleaned.container.height * 1e3) +
                      " mm"
                : "max_strain = " + std::to_string(c.stop.max_strain))
        << " (stop_reason " << stop_reason_name(reason)
        << ") without a confirmed peak, so no strength is reported: "
        << stop.missing_conditions(h.axial_strain.back(), last_loading_stress()) << ". Largest "
        << (biaxial ? "deviator" : "stress") << " so far " << stop.peak() * 1e-6 << " MPa, last "
        << last_loading_stress() * 1e-6 << " MPa, axial strain " << h.axial_strain.back() << ", "
        << stop.cracks() << " bonds broken during the loading, " << h.step.back() << " steps. "
        << (reason == StopReason::MaxSteps
                ? "Raise test.max_steps (or the platen velocity) if the stress was still rising"
                : "A specimen still loading at this strain has bonds far stronger than its "
                  "contacts can load; raise test.max_strain only if such strains are meant");
    throw RunError(msg.str());
  }
  res.stop_reason = reason;
  if (stop.unconfirmed_split_peak() > 0) {
    // The rule's stresses are P / (D t) (Pa); the strengths 2 P / (pi D t), in MPa.
    const double d = specimen.container.width;
    const auto strength = [&](double stress) {
      return brazilian_strength(stress * d * kThickness, d, kThickness) * 1e-6;
    };
    std::ostringstream msg;
    msg << "the disc opened across its loaded diameter after a peak of sigma_t = "
        << strength(stop.unconfirmed_split_peak()) << " MPa (axial strain "
        << stop.unconfirmed_split_strain() << ") and its load fell below " << c.stop.split.fraction
        << " x that peak, but the load rose again to the larger peak "
        << "reported (" << strength(stop.peak())
        << " MPa): if the disc split at the first peak, that one is its splitting strength and "
           "the reported one its halves' (docs/lab_tests.md \"Stop rule\")";
    warn(res, hooks, msg.str());
  }
  if (hooks.snapshot && c.snapshot_interval > 0)
    hooks.snapshot(world, world.step_count() - step0, world.time() - time0);  // the last state

  res.steps = world.step_count() - step0;
  tally_cracks(res, world.cracks(), time0);
  res.fragments = fragments_at_end(world, cleaned, index, c);
  res.joint_states = joint_states(world, res.cracks, 0);
  const auto peak_at = std::max_element(h.axial_stress.begin(), h.axial_stress.end());
  res.peak_stress = *peak_at;
  res.peak_force = h.platen_force[static_cast<std::size_t>(peak_at - h.axial_stress.begin())];
  switch (c.type) {
    case LabTestType::Uniaxial:
      try {
        res.ucs = analyse_ucs(h.axial_strain, h.axial_stress, h.lateral_strain);
      } catch (const std::invalid_argument& e) {
        throw RunError(std::string("uniaxial test analysis: ") + e.what());
      }
      break;
    case LabTestType::Brazilian:
      res.tensile_strength = brazilian_strength(res.peak_force, specimen.container.width);
      break;
    case LabTestType::DirectTension:
      res.tensile_strength = res.peak_stress;
      break;
    case LabTestType::Biaxial:
      analyse_biaxial(res);
      break;
    case LabTestType::Shpb:
      break;  // returned above
    case LabTestType::ThreePointBending:
      res.bending = analyse_bending(h, cleaned, c, bearing_width(c, cleaned.container), world);
      res.tensile_strength = res.bending.flexural_strength;
      if (bending_tail) {
        std::ostringstream msg;
        msg << "the beam still carried " << h.platen_force.back() / res.bending.peak_load
            << " x its peak load at max_deflection = " << res.bending.final_deflection * 1e3
            << " mm (stop_load_fraction " << c.stop.stop_fraction
            << "): W0 and G_F leave out the work of the rest of the tail and are low, and "
            << res.bending.stored_energy << " J/m of W0 = " << res.bending.work_of_fracture
            << " J/m is strain energy still stored in the beam (work dissipated to the stop "
            << res.bending.dissipated_fracture_energy << " N/m of ligament)";
        warn(res, hooks, msg.str());
      }
      break;
  }
  res.wall_time =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count();
  return res;
}

}  // namespace cdem::lab
