#include "lab/result_file.hpp"
#include "core/units.hpp"

#include <H5Cpp.h>

#include <algorithm>
#include <cstdio>
#include <numbers>
#include <sstream>

#include "core/version.hpp"
#include "io/hdf5_write.hpp"

namespace cdem::lab {

using namespace cdem::dem;  // the engine the lab layer drives

namespace {

constexpr const char* kFormat = "cdem-result";
constexpr int kFormatVersion = 1;

using hdf5::write_array;
using hdf5::write_scalar_attr;
using hdf5::write_string_attr;

std::string snapshot_name(std::size_t k) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%06zu", k);
  return buf;
}

std::string confinement_group(std::size_t k) {
  return "/confinement_" + std::to_string(k);
}

// Figures, genesis, histories, cracks, fragments and smooth joints (`sets` as given) of one
// run, under `where`.
void write_run(H5::Group& where, const LabTestResult& r, const std::vector<JointSet>& sets);

// The smooth joints of a run, group "joints" of `where`: the sets as given, their lines as
// installed (cut to the specimen), every joint's pair and its state at the end.
void write_joints(H5::Group& where, const std::vector<JointSet>& sets,
                  const InstalledJoints& installed, const JointStates& s) {
  H5::Group g = hdf5::create_group(where, "joints");
  const std::size_t n = sets.size();
  std::vector<std::int32_t> family(n), bonded_sets(n);
  std::vector<double> dip(n), spacing(n), offset(n), segment, area(n);
  std::vector<std::int64_t> contacts(n), open(n);
  std::vector<double> kn(n), ks(n), tensile(n), cohesion(n), phi(n), mu(n), psi(n), lambda(n);
  for (std::size_t k = 0; k < n; ++k) {
    const JointSet& j = sets[k];
    family[k] = j.family ? 1 : 0;
    dip[k] = j.family ? j.dip / units::degree : 0;
    spacing[k] = j.family ? j.spacing : 0;
    offset[k] = j.family ? j.offset : 0;
    for (double v : {j.segment.ax, j.segment.ay, j.segment.bx, j.segment.by})
      segment.push_back(j.family ? 0.0 : v);
    const SmoothJointParams& p = j.params;
    kn[k] = p.normal_stiffness;
    ks[k] = p.shear_stiffness;
    tensile[k] = p.tensile_strength;
    cohesion[k] = p.cohesion;
    phi[k] = p.friction_angle / units::degree;
    mu[k] = p.friction;
    psi[k] = p.dilation_angle / units::degree;
    lambda[k] = p.radius_multiplier;
    bonded_sets[k] = p.bonded ? 1 : 0;
    contacts[k] = installed.contacts[k];
    open[k] = installed.open[k];
    area[k] = installed.area[k];
  }
  write_array(g, "family", family, "",
              "1 = a family of parallel lines (dip, spacing, offset), 0 = one segment");
  write_array(g, "dip_deg", dip, "deg", "family: dip below the +x axis (0 for a segment)");
  write_array(g, "spacing", spacing, "m", "family: distance between lines (0 for a segment)");
  write_array(g, "offset", offset, "m",
              "family: the lines pass through the specimen's centre + (offset + m spacing) nj");
  write_array(g, "segment", segment, "m", "segment: x1, y1, x2, y2 as given (0 for a family)", 4);
  write_array(g, "normal_stiffness", kn, "Pa/m", "kn, per unit area");
  write_array(g, "shear_stiffness", ks, "Pa/m", "ks, per unit area");
  write_array(g, "tensile_strength", tensile, "Pa", "sigma_c");
  write_array(g, "cohesion", cohesion, "Pa", "c");
  write_array(g, "friction_angle_deg", phi, "deg", "phi of the bonded shear strength");
  write_array(g, "friction", mu, "1", "mu, unbonded Coulomb coefficient");
  write_array(g, "dilation_angle_deg", psi, "deg", "psi");
  write_array(g, "radius_multiplier", lambda, "1", "lambda");
  write_array(g, "installed_bonded", bonded_sets, "", "1 = installed bonded (sj_bonded)");
  write_array(g, "contacts", contacts, "", "joint contacts installed (bonded or touching pairs)");
  write_array(g, "open_pairs", open, "", "unbonded joints installed open on pairs apart");
  write_array(g, "contact_area", area, "m^2", "sum of the joint contacts' areas A");

  std::vector<double> xy;
  std::vector<std::int32_t> line_set, vertices;
  joint_line_table(installed, xy, line_set);
  for (std::size_t l = 0; l < line_set.size(); ++l)
    vertices.insert(vertices.end(),
                    {static_cast<std::int32_t>(2 * l), static_cast<std::int32_t>(2 * l + 1)});
  write_array(g, "line_xy", xy, "m",
              "end points of the joint lines, cut to the specimen's extent (2 rows per line)", 2);
  write_array(g, "line_vertices", vertices, "", "the two rows of line_xy of each line", 2);
  write_array(g, "line_set", line_set, "", "the set of each line");

  write_array(g, "pairs", s.pairs(), "", "the two world discs of each joint", 2);
  write_array(g, "set", s.set, "", "the joint's set");
  write_array(g, "touching", installed.touching, "",
              "1 = a joint contact (bonded or touching at installation), 0 = installed open");
  write_array(g, "nx", s.nx, "1", "joint unit normal, from the first disc's side to the second's");
  write_array(g, "ny", s.ny, "1", "see nx");
  write_array(g, "area", s.area, "m^2", "A = 2 lambda min(R1, R2) t");
  write_array(g, "bonded", s.bonded, "", "at the end: 1 = bond intact, 0 = broken or unbonded");
  write_array(g, "mode", s.mode, "", "failure: 0 = none, 1 = tension, 2 = shear");
  write_array(g, "failure_time", s.time, "s", "loading time of the failure, -1 = none");
  write_array(g, "gap", s.gap, "m", "at the end: opening along nj since installation");
  write_array(g, "normal_force", s.normal_force, "N/m",
              "at the end: on the second disc along nj, compression positive");
  write_array(g, "shear_force", s.shear_force, "N/m",
              "at the end: on the second disc along tj = (-ny, nx)");
  long intact = 0, tension = 0, shear = 0;
  for (std::size_t e = 0; e < s.size(); ++e) {
    intact += s.bonded[e];
    tension += s.mode[e] == 1;
    shear += s.mode[e] == 2;
  }
  write_scalar_attr<long>(g, "sets", static_cast<long>(n));
  write_scalar_attr<long>(g, "joints", static_cast<long>(s.size()));
  write_scalar_attr<long>(g, "bonded_at_end", intact);
  write_scalar_attr<long>(g, "broken_in_tension", tension);
  write_scalar_attr<long>(g, "broken_in_shear", shear);
}

// An SHPB run's set-up, figures and per-step waves and histories, group "shpb" of `where`.
void write_shpb(H5::Group& where, const ShpbResult& r) {
  H5::Group g = hdf5::create_group(where, "shpb");
  const ShpbOptions& o = r.options;
  const ShpbFigures& f = r.analysis.figures;
  for (const auto& [name, value] : std::initializer_list<std::pair<const char*, double>>{
           {"bar_young_modulus_Pa", o.bar.young_modulus},
           {"bar_density_kg_m3", o.bar.density},
           {"bar_length_m", o.bar.length},
           {"bar_width_m", o.bar.width},
           {"bar_wave_speed_m_s", o.bar.wave_speed()},
           {"bar_cell_size_m", r.cell_size},
           {"bar_time_step_s", r.bar_time_step},
           {"incident_gauge_m", o.incident_gauge},
           {"transmitted_gauge_m", o.transmitted_gauge},
           {"pulse_peak_Pa", o.pulse_peak},
           {"pulse_duration_s", o.pulse_duration},
           {"arrival_time_s", r.arrival_time},
           {"specimen_length_m", r.geometry.specimen_length},
           {"specimen_area_m2", r.geometry.specimen_area},
           {"dynamic_strength_Pa", f.peak_stress},
           {"dynamic_strength_one_wave_Pa", f.peak_stress_one_wave},
           {"dynamic_strength_two_wave_Pa", f.peak_stress_two_wave},
           {"time_at_peak_s", f.time_at_peak},
           {"strain_at_peak", f.strain_at_peak},
           {"strain_rate_at_peak_1_s", f.strain_rate_at_peak},
           {"mean_strain_rate_1_s", f.mean_strain_rate},
           {"tangent_modulus_Pa", f.tangent_modulus},
           {"secant_modulus_Pa", f.secant_modulus},
           {"equilibrium_ratio_at_peak", f.equilibrium_at_peak},
           {"equilibrium_ratio_worst", f.equilibrium_worst},
           {"equilibrium_ratio_mean", f.equilibrium_mean},
           {"gauge_length_m", o.gauge_length},
           {"equilibrium_ratio_worst_gauge", f.equilibrium_worst_gauge},
           {"first_failure_stress_Pa", f.first_failure_stress},
           {"time_at_first_failure_s", f.time_at_first_failure},
           {"equilibrium_ratio_worst_to_first_failure", f.equilibrium_worst_first_failure},
           {"equilibrium_ratio_mean_to_first_failure", f.equilibrium_mean_first_failure},
           {"equilibrium_ratio_worst_to_first_failure_gauge",
            f.equilibrium_worst_gauge_first_failure},
           {"bar_poisson_ratio", o.bar_poisson_ratio},
           {"equilibrium_ratio_worst_bar_gauges", f.equilibrium_worst_bar},
           {"equilibrium_ratio_mean_bar_gauges", f.equilibrium_mean_bar},
           {"equilibrium_ratio_worst_to_first_failure_bar_gauges",
            f.equilibrium_worst_bar_first_failure},
           {"equilibrium_ratio_mean_to_first_failure_bar_gauges",
            f.equilibrium_mean_bar_first_failure},
           {"incident_energy_J_per_m", f.incident_energy},
           {"reflected_energy_J_per_m", f.reflected_energy},
           {"transmitted_energy_J_per_m", f.transmitted_energy},
           {"absorbed_energy_J_per_m", f.absorbed_energy},
           {"face_work_J_per_m", r.face_work},
           {"coupling_number", r.coupling_number},
           {"dynamic_tensile_strength_Pa", r.dynamic_tensile_strength}})
    write_scalar_attr<double>(g, name, value);
  write_string_attr(g, "pulse", pulse_name(o.pulse));
  if (o.pulse == ShpbPulse::Ramp) write_scalar_attr<double>(g, "pulse_rise_s", o.pulse_rise);
  write_scalar_attr<long>(g, "bar_cells", r.cells);

  const ShpbWaves& w = r.waves;
  const ShpbHistories& h = r.analysis.histories;
  H5::Group fg = hdf5::create_group(g, "faces");
  write_array(fg, "time", w.time, "s", "since the loading began, one entry per bar step");
  write_array(fg, "incident_strain", w.incident, "1", "eps_i at the face, compression positive");
  write_array(fg, "reflected_strain", w.reflected, "1", "eps_r at the face");
  write_array(fg, "transmitted_strain", w.transmitted, "1", "eps_t at the face");
  write_array(fg, "front_force", h.front_force, "N/m", "E A (eps_i + eps_r)");
  write_array(fg, "back_force", h.back_force, "N/m", "E A eps_t");
  write_array(fg, "strain_rate", h.strain_rate, "1/s", "three-wave, c0/l_s (eps_i-eps_r-eps_t)");
  write_array(fg, "strain", h.strain, "1", "three-wave, integral of strain_rate");
  write_array(fg, "stress", h.stress, "Pa", "three-wave, (front + back) / (2 A_s)");
  write_array(fg, "stress_one_wave", h.stress_one_wave, "Pa", "back force / A_s");
  write_array(fg, "stress_two_wave", h.stress_two_wave, "Pa", "front force / A_s");
  write_array(fg, "strain_rate_reflected", h.strain_rate_reflected, "1/s",
              "one- and two-wave, -2 c0 eps_r / l_s");
  write_array(fg, "strain_reflected", h.strain_reflected, "1", "integral of the above");
  write_array(fg, "front_force_bar_gauges", h.front_force_gauges, "N/m",
              "E A (eps_i + eps_r) as gauges on real round bars read it (dispersed, averaged "
              "over the gauge length)");
  write_array(fg, "back_force_bar_gauges", h.back_force_gauges, "N/m",
              "E A eps_t as gauges on real round bars read it");

  const ShpbGaugeRecords& k = r.gauges;
  H5::Group gg = hdf5::create_group(g, "gauges");
  write_array(gg, "incident_right", k.incident_right, "1",
              "incident gauge, right-going (towards the specimen) strain, one per bar step");
  write_array(gg, "incident_left", k.incident_left, "1", "incident gauge, left-going strain");
  write_array(gg, "transmitted_right", k.transmitted_right, "1",
              "transmitted gauge, right-going (away from the specimen) strain");
  write_array(gg, "transmitted_left", k.transmitted_left, "1",
              "transmitted gauge, left-going strain");
  write_array(gg, "front_face_force", k.front_face_force, "N/m",
              "DEM: the discs on the incident bar's face");
  write_array(gg, "back_face_force", k.back_face_force, "N/m",
              "DEM: the discs on the transmitted bar's face");
}

}  // namespace

ResultFile::ResultFile(std::filesystem::path target, const LabTestInput& input)
    : out_(std::move(target)), joint_sets_(input.controls.joints) {
  file_ = std::make_unique<H5::H5File>(hdf5::create_file_in_memory(out_.temp_path().string()));
  write_string_attr(*file_, "format", kFormat);
  write_scalar_attr<std::int32_t>(*file_, "format_version", kFormatVersion);
  write_string_attr(*file_, "cdem_version", kVersion);
  write_string_attr(*file_, "test", lab_test_name(input.controls.type));
  write_scalar_attr<std::uint64_t>(*file_, "seed", input.seed);
  write_string_attr(*file_, "input_file", input.file);
  write_string_attr(*file_, "input_text", input.text);
  write_string_attr(*file_, "materials_text", input.materials_text);
  write_string_attr(*file_, "specimen_file", input.specimen_path.string());
  if (input.controls.type != LabTestType::Biaxial) hdf5::create_group(*file_, "snapshots");
}

void ResultFile::begin_confinement(std::size_t k, double sigma3) {
  group_ = confinement_group(k);
  H5::Group g = hdf5::create_group(*file_, group_);
  write_scalar_attr<double>(g, "confining_stress_Pa", sigma3);
  hdf5::create_group(g, "snapshots");
}

ResultFile::~ResultFile() {
  // Only on the error path (finish() closed it otherwise); the file is in memory, so nothing is
  // written, but a close must still not throw out of a destructor (std::terminate).
  if (file_) {
    try {
      file_->close();
    } catch (const H5::Exception&) {
    }
  }
}

std::array<std::filesystem::path, 4> ResultFile::xdmf_paths(const std::filesystem::path& target) {
  std::filesystem::path discs = target, bonds = target, cracks = target, joints = target;
  const std::string stem = target.stem().string();
  discs.replace_extension(".xmf");
  bonds.replace_filename(stem + "_bonds.xmf");
  cracks.replace_filename(stem + "_cracks.xmf");
  joints.replace_filename(stem + "_joints.xmf");
  return {discs, bonds, cracks, joints};
}

std::vector<NamedPath> ResultFile::outputs(const std::string& flag,
                                           const std::filesystem::path& target) {
  const auto xdmf = xdmf_paths(target);
  return {{flag, target},
          {flag + " (its XDMF file)", xdmf[0]},
          {flag + " (its bonds XDMF file)", xdmf[1]},
          {flag + " (its cracks XDMF file)", xdmf[2]},
          {flag + " (its joints XDMF file)", xdmf[3]}};
}

void ResultFile::snapshot(const World& world, long step, double time) {
  const Discs& d = world.discs();
  H5::Group root = file_->openGroup(group_).openGroup("snapshots");
  const std::size_t index = static_cast<std::size_t>(
      std::count_if(snapshots_.begin(), snapshots_.end(),
                    [this](const SnapshotIndex& s) { return s.group == group_; }));
  H5::Group g = hdf5::create_group(root, snapshot_name(index));
  write_scalar_attr<long>(g, "step", step);
  write_scalar_attr<double>(g, "time_s", time);
  const auto copy = [&](const auto& v, const char* name, const char* units) {
    scratch_.assign(v.begin(), v.end());
    write_array(g, name, scratch_, units);
  };
  copy(d.x, "x", "m");
  copy(d.y, "y", "m");
  scratch_.resize(2 * d.size());
  for (std::size_t i = 0; i < d.size(); ++i) {
    scratch_[2 * i] = d.x[i];
    scratch_[2 * i + 1] = d.y[i];
  }
  write_array(g, "xy", scratch_, "m", "x, y per disc (the XDMF geometry)", 2);
  copy(d.r, "r", "m");
  copy(d.vx, "vx", "m/s");
  copy(d.vy, "vy", "m/s");
  std::vector<std::int32_t> tag(d.size()), clump(d.size());
  for (std::size_t i = 0; i < d.size(); ++i) {
    tag[i] = static_cast<std::int32_t>(d.material[i]);
    clump[i] = world.bodies().is_clump[d.body[i]] ? d.body[i] : -1;
  }
  write_array(g, "tag", tag, "", "0 = mortar disc, 1 = aggregate pebble");
  write_array(g, "clump", clump, "", "body index of the disc's clump, -1 = a free disc");
  if (index == 0) {  // the discs' indices, the XDMF topology of every snapshot of this run
    std::vector<std::int32_t> vertices(d.size());
    for (std::size_t i = 0; i < d.size(); ++i) vertices[i] = static_cast<std::int32_t>(i);
    write_array(root, "vertices", vertices, "", "disc index (XDMF Polyvertex topology)");
  }
  snapshot_bonds(root, g, world, time);
  bond_count_.assign(d.size(), 0);
  const ContactStore& list = world.contacts();
  for (std::size_t k = 0; k < list.keys.size(); ++k)
    if (list.intact_bonds(k) > 0) {
      ++bond_count_[list.first[k]];
      ++bond_count_[list.second[k]];
    }
  write_array(g, "bonds", bond_count_, "", "intact bonds of the disc");
  const std::size_t joints = world.contacts().smooth_joints.size();
  if (joints > 0) snapshot_joints(root, g, world, time, index == 0);
  snapshots_.push_back({group_, index, step, time, d.size(), bond_keys_.size(), joints});
}

// The bond network at a snapshot. At the run's first snapshot the pairs then bonded become the
// network (their pairs, class and law in `root`); every snapshot stores each one's intact
// bonds (flat joint: bonded elements; 0 = broken) and its latest failure from the crack log.
void ResultFile::snapshot_bonds(H5::Group& root, H5::Group& g, const World& world, double time) {
  const ContactStore& list = world.contacts();
  const auto& cracks = world.cracks().cracks;
  if (bond_group_ != group_) {
    bond_group_ = group_;
    bond_keys_.clear();
    std::vector<std::int32_t> pairs, cls, law;
    for (std::size_t k = 0; k < list.keys.size(); ++k) {
      if (list.intact_bonds(k) == 0) continue;
      bond_keys_.push_back(list.keys[k]);
      pairs.push_back(list.first[k]);
      pairs.push_back(list.second[k]);
      cls.push_back(list.contact_class[k]);
      law.push_back(list.state.bond[k]);
    }
    bond_mode_.assign(bond_keys_.size(), 0);
    bond_time_.assign(bond_keys_.size(), -1.0);
    cracks_seen_ = cracks.size();  // earlier cracks broke bonds that are not in the network
    write_array(root, "bond_pairs", pairs, "", "the two discs of each bond (XDMF lines)", 2);
    write_array(root, "bond_class", cls, "", "0 = M (mortar), 1 = ITZ, 2 = A (aggregate)");
    write_array(root, "bond_law", law, "",
                "1 = contact bond, 2 = parallel bond, 3 = flat joint, 4 = smooth joint");
  }
  // World time of the loading start: crack times are world times until the run ends.
  const double time0 = world.time() - time;
  for (; cracks_seen_ < cracks.size(); ++cracks_seen_) {
    const Crack& c = cracks[cracks_seen_];
    const std::uint64_t key =
        pair_key(static_cast<std::uint32_t>(c.first), static_cast<std::uint32_t>(c.second));
    const auto at = std::lower_bound(bond_keys_.begin(), bond_keys_.end(), key);
    if (at == bond_keys_.end() || *at != key) continue;
    const std::size_t b = static_cast<std::size_t>(at - bond_keys_.begin());
    bond_mode_[b] = static_cast<std::int32_t>(c.mode);
    bond_time_[b] = c.time - time0;
  }
  std::vector<std::int32_t> intact(bond_keys_.size(), 0);
  for (std::size_t b = 0; b < bond_keys_.size(); ++b) {
    const auto at = std::lower_bound(list.keys.begin(), list.keys.end(), bond_keys_[b]);
    if (at != list.keys.end() && *at == bond_keys_[b])
      intact[b] = list.intact_bonds(static_cast<std::size_t>(at - list.keys.begin()));
  }
  write_array(g, "bond_intact", intact, "",
              "intact bonds of the pair (flat joint: bonded elements); 0 = broken");
  write_array(g, "bond_mode", bond_mode_, "", "latest failure: 0 = none, 1 = tension, 2 = shear");
  write_array(g, "bond_time", bond_time_, "s", "loading time of the latest failure, -1 = none");
}

void ResultFile::snapshot_joints(H5::Group& root, H5::Group& g, const World& world, double time,
                                 bool first) {
  const JointStates s = joint_states(world, world.cracks().cracks, world.time() - time);
  if (first) {
    write_array(root, "joint_pairs", s.pairs(), "",
                "the two discs of each smooth joint (XDMF lines)", 2);
    write_array(root, "joint_set", s.set, "", "the smooth joint's [[test.joints]] set");
  }
  write_array(g, "joint_bonded", s.bonded, "", "smooth joint: 1 = bond intact, 0 = broken");
  write_array(g, "joint_mode", s.mode, "",
              "smooth joint failure: 0 = none, 1 = tension, 2 = shear");
  write_array(g, "joint_normal_force", s.normal_force, "N/m",
              "smooth joint normal force, compression positive");
}

void ResultFile::commit(const LabTestResult& r) {
  crack_count_ = r.cracks.size();
  H5::Group root = file_->openGroup("/");
  write_run(root, r, joint_sets_);
  finish();
}

void ResultFile::commit(const BiaxialSeries& series) {
  {
    H5::Group s = hdf5::create_group(*file_, "summary");
    write_scalar_attr<double>(s, "cohesion_Pa", series.envelope.cohesion);
    write_scalar_attr<double>(s, "friction_angle_deg",
                              series.envelope.friction_angle * 180 / std::numbers::pi);
    write_scalar_attr<double>(s, "mohr_coulomb_r2", series.envelope.r_squared);
    write_scalar_attr<long>(s, "confinements", static_cast<long>(series.runs.size()));
    for (std::size_t k = 0; k < series.runs.size(); ++k) {
      const std::string name = confinement_group(k);
      H5::Group g =
          file_->nameExists(name) ? file_->openGroup(name) : hdf5::create_group(*file_, name);
      if (!g.attrExists("confining_stress_Pa"))
        write_scalar_attr<double>(g, "confining_stress_Pa", series.runs[k].confining_stress);
      if (!g.nameExists("snapshots")) hdf5::create_group(g, "snapshots");
      write_run(g, series.runs[k], joint_sets_);
    }
  }
  finish();
}

namespace {

void write_run(H5::Group& where, const LabTestResult& r, const std::vector<JointSet>& sets) {
  if (!sets.empty()) write_joints(where, sets, r.joints, r.joint_states);
  {
    H5::Group s = hdf5::create_group(where, "summary");
    write_scalar_attr<double>(s, "peak_stress_Pa", r.peak_stress);
    write_scalar_attr<double>(s, "peak_force_N_per_m", r.peak_force);
    if (r.type == LabTestType::Uniaxial || r.type == LabTestType::Biaxial) {
      write_scalar_attr<double>(s, "young_modulus_Pa", r.ucs.young_modulus);
      write_scalar_attr<double>(s, "poisson_ratio", r.ucs.poisson_ratio);
      write_scalar_attr<double>(s, "strain_at_half_peak", r.ucs.strain_at_half_peak);
    } else if (r.type != LabTestType::Shpb) {
      write_scalar_attr<double>(s, "tensile_strength_Pa", r.tensile_strength);
    }
    write_scalar_attr<double>(s, "width_m", r.width);
    write_scalar_attr<double>(s, "height_m", r.height);
    write_scalar_attr<long>(s, "steps", r.steps);
    write_scalar_attr<double>(s, "time_step_s", r.time_step);
    write_scalar_attr<long>(s, "gauge_discs", static_cast<long>(r.gauge_discs));
    if (r.type == LabTestType::Shpb) write_shpb(where, r.shpb);
    if (r.type == LabTestType::ThreePointBending) {
      const BendingResult& b = r.bending;
      write_scalar_attr<double>(s, "span_m", b.span);
      write_scalar_attr<double>(s, "notch_depth_m", b.notch_depth);
      write_scalar_attr<double>(s, "peak_load_N_per_m", b.peak_load);
      write_scalar_attr<double>(s, "net_flexural_strength_Pa", b.net_flexural_strength);
      write_scalar_attr<double>(s, "work_of_fracture_J_per_m", b.work_of_fracture);
      write_scalar_attr<double>(s, "final_deflection_m", b.final_deflection);
      write_scalar_attr<double>(s, "self_weight_work_J_per_m", b.self_weight_work);
      write_scalar_attr<double>(s, "fracture_energy_N_per_m", b.fracture_energy);
      write_scalar_attr<double>(s, "stored_energy_at_stop_J_per_m", b.stored_energy);
      write_scalar_attr<double>(s, "dissipated_work_J_per_m", b.dissipated_work);
      write_scalar_attr<double>(s, "dissipated_fracture_energy_N_per_m",
                                b.dissipated_fracture_energy);
      write_scalar_attr<double>(s, "characteristic_length_m", b.characteristic_length);
    }
    if (r.type == LabTestType::Biaxial) {
      write_scalar_attr<double>(s, "confining_stress_Pa", r.confining_stress);
      write_scalar_attr<double>(s, "confining_stress_at_peak_Pa", r.confining_stress_at_peak);
      write_scalar_attr<double>(s, "peak_deviator_Pa", r.peak_deviator);
      write_scalar_attr<long>(s, "consolidation_steps", r.consolidation.steps);
      write_scalar_attr<double>(s, "consolidation_worst_error", r.consolidation.worst_error);
    }

    H5::Group g = hdf5::create_group(where, "genesis");
    write_scalar_attr<long>(g, "discs_in_specimen", r.genesis.discs_in_specimen);
    write_scalar_attr<long>(g, "floating_discs_removed", r.genesis.floating_removed);
    write_scalar_attr<std::int32_t>(g, "removal_passes", r.genesis.removal_passes);
    write_scalar_attr<long>(g, "discs", r.genesis.discs);
    write_scalar_attr<long>(g, "relaxation_steps", r.genesis.relaxation_steps);
    write_scalar_attr<double>(g, "relaxation_unbalanced_ratio",
                              r.genesis.relaxation_unbalanced_ratio);
    write_scalar_attr<long>(g, "relaxation_cracks", r.genesis.relaxation_cracks);
    for (int c = 0; c < 3; ++c)
      write_scalar_attr<long>(g, std::string("bonds_") + contact_class_name(ContactClass(c)),
                              r.genesis.bonds[c]);

    const LabHistory& h = r.history;
    H5::Group hg = hdf5::create_group(where, "history");
    write_array(hg, "step", h.step);
    write_array(hg, "time", h.time, "s");
    write_array(hg, "axial_strain", h.axial_strain, "1",
                "platen (grip) travel / H0, loading sense");
    write_array(hg, "lateral_strain", h.lateral_strain, "1",
                "-du_x/dx of the central region, contraction positive");
    write_array(hg, "axial_stress", h.axial_stress, "Pa",
                "mean platen force / (W t); biaxial: W = side-wall gap");
    write_array(hg, "confining_stress", h.confining_stress, "Pa",
                "sigma_xx of the contacts in the central region (biaxial: side-wall stress), "
                "compression positive");
    write_array(hg, "platen_force", h.platen_force, "N/m", "mean of the two ends");
    write_array(hg, "kinetic_energy", h.kinetic_energy, "J/m");
    write_array(hg, "strain_energy", h.strain_energy, "J/m");
    write_array(hg, "friction_energy", h.friction_energy, "J/m");
    write_array(hg, "breakage_energy", h.breakage_energy, "J/m");
    write_array(hg, "boundary_work", h.boundary_work, "J/m");
    write_array(hg, "bonds_broken", h.bonds_broken);
    if (r.type == LabTestType::ThreePointBending) {
      write_array(hg, "deflection", h.deflection, "m", "load point relative to the supports");
      write_array(hg, "cmod", h.cmod, "m", "crack-mouth opening, opening positive");
      write_array(hg, "support_reaction", h.support_reaction, "N/m", "sum of the two supports");
    }

    std::vector<double> t, x, y, xy, energy, nx, ny, half_width;
    std::vector<std::uint8_t> mode, cls;
    std::vector<std::int32_t> element, vertices;
    std::vector<std::int32_t> first, second;
    for (const Crack& c : r.cracks) {
      vertices.push_back(static_cast<std::int32_t>(t.size()));
      t.push_back(c.time);
      x.push_back(c.x);
      y.push_back(c.y);
      xy.push_back(c.x);
      xy.push_back(c.y);
      energy.push_back(c.energy);
      nx.push_back(c.nx);
      ny.push_back(c.ny);
      half_width.push_back(c.half_width);
      mode.push_back(static_cast<std::uint8_t>(c.mode));
      cls.push_back(static_cast<std::uint8_t>(c.contact_class));
      first.push_back(c.first);
      second.push_back(c.second);
      element.push_back(c.element);
    }
    H5::Group cg = hdf5::create_group(where, "cracks");
    write_array(cg, "time", t, "s");
    write_array(cg, "x", x, "m");
    write_array(cg, "y", y, "m");
    write_array(cg, "mode", mode, "", "1 = tension, 2 = shear");
    write_array(cg, "class", cls, "", "0 = M (mortar), 1 = ITZ, 2 = A (aggregate)");
    write_array(cg, "first", first, "", "world disc index");
    write_array(cg, "second", second, "", "world disc index");
    write_array(cg, "element", element, "",
                "flat-joint element 0 .. N_r - 1, -1 = not a flat joint");
    write_array(cg, "energy", energy, "J/m",
                "strain energy the bond held when it broke (a flat joint's elements breaking in "
                "one pass share it)");
    write_array(cg, "nx", nx, "1",
                "unit normal of the contact plane, from the centre of `first` towards `second` "
                "when the bond broke");
    write_array(cg, "ny", ny, "1", "see nx");
    write_array(cg, "half_width", half_width, "m",
                "half the width of the broken bond across the normal: the crack is the segment "
                "(x, y) +- half_width (-ny, nx)");
    write_array(cg, "xy", xy, "m", "x, y per crack (the XDMF geometry)", 2);
    write_array(cg, "vertices", vertices, "", "crack index (XDMF Polyvertex topology)");
    for (int m = 0; m < 2; ++m)
      for (int c = 0; c < 3; ++c)
        write_scalar_attr<long>(
            cg, std::string(m == 0 ? "tension_" : "shear_") + contact_class_name(ContactClass(c)),
            r.crack_count[m][c]);

    const Fragments& f = r.fragments;
    H5::Group fg = hdf5::create_group(where, "fragments");
    write_array(fg, "fragment_of_disc", f.fragment_of_disc, "",
                "fragment of each world disc at the end, 0 = the heaviest");
    write_array(fg, "mass", f.mass, "kg/m", "per fragment, decreasing");
    write_array(fg, "diameter", f.diameter, "m", "equivalent diameter from area");
    write_array(fg, "sieve", f.sieve, "m", "sieve sizes");
    write_array(fg, "group_mass_fraction", f.group_mass_fraction, "1",
                "mass fraction of the size groups [0, s_1), ..., [s_last, inf)");
    write_scalar_attr<double>(fg, "f_m", f.f_m);
    write_scalar_attr<double>(fg, "largest_fragment_fraction", f.largest_fragment_fraction);
  }
}

}  // namespace

namespace {

// An XDMF DataItem of the HDF5 dataset `path` in `h5` with `dims` ("n" or "n 2").
std::string data_item(const std::string& h5, const std::string& path, const std::string& dims,
                      const char* type, int precision) {
  std::ostringstream s;
  s << "     <DataItem Dimensions=\"" << dims << "\" NumberType=\"" << type << "\" Precision=\""
    << precision << "\" Format=\"HDF\">" << h5 << ":" << path << "</DataItem>\n";
  return s.str();
}

std::string attribute(const char* name, const char* center, const std::string& item) {
  return std::string("    <Attribute Name=\"") + name + "\" AttributeType=\"Scalar\" Center=\"" +
         center + "\">\n" + item + "    </Attribute>\n";
}

}  // namespace

// XDMF 3 companions (docs/result_file.md), each one grid or one temporal collection so that a
// reader of single grids (meshio) opens it: the discs (Polyvertex, XY geometry), the bond
// network (Polyline of two nodes per bond on the discs' positions of each snapshot) and the
// crack log (Polyvertex at the crack positions).
void ResultFile::finish() {
  hdf5::save_and_close(*file_, out_);
  file_.reset();
  out_.commit();

  if (snapshots_.empty()) return;
  const std::string h5 = out_.target().filename().string();
  const auto paths = xdmf_paths(out_.target());
  const char* head = "<?xml version=\"1.0\" ?>\n<Xdmf Version=\"3.0\">\n <Domain>\n";
  const char* tail = " </Domain>\n</Xdmf>\n";
  std::ostringstream x, b;
  x << head;
  b << head << "  <Grid Name=\"bonds\" GridType=\"Collection\" CollectionType=\"Temporal\">\n";
  for (std::size_t k = 0; k < snapshots_.size(); ++k) {
    const SnapshotIndex& s = snapshots_[k];
    if (k == 0 || s.group != snapshots_[k - 1].group) {
      if (k > 0) x << "  </Grid>\n";
      x << "  <Grid Name=\"" << (s.group == "/" ? "discs" : s.group.substr(1))
        << "\" GridType=\"Collection\" CollectionType=\"Temporal\">\n";
    }
    const std::string root = (s.group == "/" ? "" : s.group) + "/snapshots/";
    const std::string path = root + snapshot_name(s.index) + "/";
    const std::string n = std::to_string(s.discs);
    const std::string geometry = "    <Geometry GeometryType=\"XY\">\n" +
                                 data_item(h5, path + "xy", n + " 2", "Float", 8) +
                                 "    </Geometry>\n";
    std::ostringstream header;
    header.precision(17);
    header << "   <Grid Name=\"step " << s.step << "\" GridType=\"Uniform\">\n    <Time Value=\""
           << s.time << "\"/>\n";
    const std::string grid = header.str();
    x << grid << "    <Topology TopologyType=\"Polyvertex\" NumberOfElements=\"" << n
      << "\" NodesPerElement=\"1\">\n"
      << data_item(h5, root + "vertices", n + " 1", "Int", 4) << "    </Topology>\n"
      << geometry;
    for (const char* a : {"r", "vx", "vy"})
      x << attribute(a, "Node", data_item(h5, path + a, n, "Float", 8));
    for (const char* a : {"bonds", "tag", "clump"})
      x << attribute(a, "Node", data_item(h5, path + a, n, "Int", 4));
    x << "   </Grid>\n";
    if (s.group != "/") continue;  // a biaxial series: discs only
    const std::string m = std::to_string(s.bonds);
    b << grid << "    <Topology TopologyType=\"Polyline\" NumberOfElements=\"" << m
      << "\" NodesPerElement=\"2\">\n"
      << data_item(h5, root + "bond_pairs", m + " 2", "Int", 4) << "    </Topology>\n"
      << geometry;
    for (const char* a : {"bond_class", "bond_law"})
      b << attribute(a, "Cell", data_item(h5, root + a, m, "Int", 4));
    for (const char* a : {"bond_intact", "bond_mode"})
      b << attribute(a, "Cell", data_item(h5, path + a, m, "Int", 4));
    b << attribute("bond_time", "Cell", data_item(h5, path + "bond_time", m, "Float", 8))
      << "   </Grid>\n";
  }
  x << "  </Grid>\n" << tail;
  b << "  </Grid>\n" << tail;
  write_text_atomically(paths[0], x.str());
  if (snapshots_.front().group != "/") return;
  write_text_atomically(paths[1], b.str());
  const std::string c = std::to_string(crack_count_);
  std::ostringstream cx;
  cx << head << "  <Grid Name=\"cracks\" GridType=\"Uniform\">\n"
     << "    <Topology TopologyType=\"Polyvertex\" NumberOfElements=\"" << c
     << "\" NodesPerElement=\"1\">\n"
     << data_item(h5, "/cracks/vertices", c + " 1", "Int", 4) << "    </Topology>\n"
     << "    <Geometry GeometryType=\"XY\">\n"
     << data_item(h5, "/cracks/xy", c + " 2", "Float", 8) << "    </Geometry>\n";
  for (const char* a : {"time", "energy", "nx", "ny", "half_width"})
    cx << attribute(a, "Node", data_item(h5, std::string("/cracks/") + a, c, "Float", 8));
  for (const char* a : {"mode", "class"})
    cx << attribute(a, "Node", data_item(h5, std::string("/cracks/") + a, c, "UInt", 1));
  for (const char* a : {"element", "first", "second"})
    cx << attribute(a, "Node", data_item(h5, std::string("/cracks/") + a, c, "Int", 4));
  cx << "  </Grid>\n" << tail;
  write_text_atomically(paths[2], cx.str());
  if (snapshots_.front().joints > 0) write_text_atomically(paths[3], xdmf_joints(h5));
}

// The smooth joints: a temporal collection of Polyline grids, one line of two nodes per joint
// (`joint_pairs`) on the discs' positions of each snapshot.
std::string ResultFile::xdmf_joints(const std::string& h5) const {
  std::ostringstream j;
  j << "<?xml version=\"1.0\" ?>\n<Xdmf Version=\"3.0\">\n <Domain>\n"
    << "  <Grid Name=\"joints\" GridType=\"Collection\" CollectionType=\"Temporal\">\n";
  j.precision(17);
  for (const SnapshotIndex& s : snapshots_) {
    const std::string path = "/snapshots/" + snapshot_name(s.index) + "/";
    const std::string n = std::to_string(s.discs), m = std::to_string(s.joints);
    j << "   <Grid Name=\"step " << s.step << "\" GridType=\"Uniform\">\n    <Time Value=\""
      << s.time << "\"/>\n"
      << "    <Topology TopologyType=\"Polyline\" NumberOfElements=\"" << m
      << "\" NodesPerElement=\"2\">\n"
      << data_item(h5, "/snapshots/joint_pairs", m + " 2", "Int", 4) << "    </Topology>\n"
      << "    <Geometry GeometryType=\"XY\">\n"
      << data_item(h5, path + "xy", n + " 2", "Float", 8) << "    </Geometry>\n"
      << attribute("joint_set", "Cell", data_item(h5, "/snapshots/joint_set", m, "Int", 4));
    j << attribute("joint_bonded", "Cell", data_item(h5, path + "joint_bonded", m, "UInt", 1))
      << attribute("joint_mode", "Cell", data_item(h5, path + "joint_mode", m, "Int", 4))
      << attribute("joint_normal_force", "Cell",
                   data_item(h5, path + "joint_normal_force", m, "Float", 8))
      << "   </Grid>\n";
  }
  j << "  </Grid>\n </Domain>\n</Xdmf>\n";
  return j.str();
}

}  // namespace cdem::lab
