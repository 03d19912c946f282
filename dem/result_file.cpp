#include "dem/result_file.hpp"

#include <H5Cpp.h>

#include <algorithm>
#include <cstdio>
#include <numbers>
#include <sstream>

#include "core/hdf5_write.hpp"
#include "core/version.hpp"

namespace cdem::dem {

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

// Figures, genesis, histories and cracks of one run, under `where`.
void write_run(H5::Group& where, const LabTestResult& r);

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
           {"incident_energy_J_per_m", f.incident_energy},
           {"reflected_energy_J_per_m", f.reflected_energy},
           {"transmitted_energy_J_per_m", f.transmitted_energy},
           {"absorbed_energy_J_per_m", f.absorbed_energy},
           {"face_work_J_per_m", r.face_work},
           {"coupling_number", r.coupling_number},
           {"dynamic_tensile_strength_Pa", r.dynamic_tensile_strength}})
    write_scalar_attr<double>(g, name, value);
  write_string_attr(g, "pulse", o.pulse == ShpbPulse::Rectangle ? "rectangle" : "half_sine");
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
    : out_(std::move(target)) {
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

std::filesystem::path ResultFile::xdmf_path() const {
  std::filesystem::path p = out_.target();
  return p.replace_extension(".xmf");
}

void ResultFile::snapshot(const World& world, long step, double time) {
  const Discs& d = world.discs;
  H5::Group root = file_->openGroup(group_).openGroup("snapshots");
  const std::size_t index = static_cast<std::size_t>(
      std::count_if(snapshots_.begin(), snapshots_.end(),
                    [this](const SnapshotIndex& s) { return s.group == group_; }));
  H5::Group g = hdf5::create_group(root, snapshot_name(index));
  write_scalar_attr<long>(g, "step", step);
  write_scalar_attr<double>(g, "time_s", time);
  const auto copy = [&](const std::vector<double>& v, const char* name, const char* units) {
    scratch_.assign(v.begin(), v.end());
    write_array(g, name, scratch_, units);
  };
  copy(d.x, "x", "m");
  copy(d.y, "y", "m");
  copy(d.r, "r", "m");
  copy(d.vx, "vx", "m/s");
  copy(d.vy, "vy", "m/s");
  bond_count_.assign(d.size(), 0);
  const NeighborList& list = world.neighbors;
  for (std::size_t k = 0; k < list.keys.size(); ++k)
    if (list.intact_bonds(k) > 0) {
      ++bond_count_[list.first[k]];
      ++bond_count_[list.second[k]];
    }
  write_array(g, "bonds", bond_count_, "", "intact bonds of the disc");
  snapshots_.push_back({group_, index, step, time, d.size()});
}

void ResultFile::commit(const LabTestResult& r) {
  H5::Group root = file_->openGroup("/");
  write_run(root, r);
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
      write_run(g, series.runs[k]);
    }
  }
  finish();
}

namespace {

void write_run(H5::Group& where, const LabTestResult& r) {
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

    std::vector<double> t, x, y;
    std::vector<std::uint8_t> mode, cls;
    std::vector<std::int32_t> element;
    std::vector<std::int32_t> first, second;
    for (const Crack& c : r.cracks) {
      t.push_back(c.time);
      x.push_back(c.x);
      y.push_back(c.y);
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
    for (int m = 0; m < 2; ++m)
      for (int c = 0; c < 3; ++c)
        write_scalar_attr<long>(
            cg, std::string(m == 0 ? "tension_" : "shear_") + contact_class_name(ContactClass(c)),
            r.crack_count[m][c]);
  }
}

}  // namespace

void ResultFile::finish() {
  hdf5::save_and_close(*file_, out_);
  file_.reset();
  out_.commit();

  if (snapshots_.empty()) return;
  const std::string h5 = out_.target().filename().string();
  std::ostringstream x;
  x << "<?xml version=\"1.0\" ?>\n<Xdmf Version=\"3.0\">\n <Domain>\n";
  for (std::size_t k = 0; k < snapshots_.size(); ++k) {
    const std::string& group = snapshots_[k].group;
    if (k == 0 || group != snapshots_[k - 1].group) {
      if (k > 0) x << "  </Grid>\n";
      x << "  <Grid Name=\"" << (group == "/" ? "discs" : group.substr(1))
        << "\" GridType=\"Collection\" CollectionType=\"Temporal\">\n";
    }
    const std::string path = h5 + ":" + (group == "/" ? "" : group) + "/snapshots/" +
                             snapshot_name(snapshots_[k].index) + "/";
    const std::size_t n = snapshots_[k].discs;
    const auto item = [&](const char* name, const char* type, int precision) {
      std::ostringstream s;
      s << "     <DataItem Dimensions=\"" << n << "\" NumberType=\"" << type << "\" Precision=\""
        << precision << "\" Format=\"HDF\">" << path << name << "</DataItem>\n";
      return s.str();
    };
    x << "   <Grid Name=\"step " << snapshots_[k].step << "\" GridType=\"Uniform\">\n"
      << "    <Time Value=\"" << snapshots_[k].time << "\"/>\n"
      << "    <Topology TopologyType=\"Polyvertex\" NumberOfElements=\"" << n << "\"/>\n"
      << "    <Geometry GeometryType=\"X_Y\">\n"
      << item("x", "Float", 8) << item("y", "Float", 8) << "    </Geometry>\n";
    for (const char* a : {"r", "vx", "vy"})
      x << "    <Attribute Name=\"" << a << "\" AttributeType=\"Scalar\" Center=\"Node\">\n"
        << item(a, "Float", 8) << "    </Attribute>\n";
    x << "    <Attribute Name=\"bonds\" AttributeType=\"Scalar\" Center=\"Node\">\n"
      << item("bonds", "Int", 4) << "    </Attribute>\n   </Grid>\n";
  }
  x << "  </Grid>\n </Domain>\n</Xdmf>\n";
  write_text_atomically(xdmf_path(), x.str());
}

}  // namespace cdem::dem
