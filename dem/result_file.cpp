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
  if (input.controls.type != LabTestType::Biaxial) file_->createGroup("snapshots");
}

void ResultFile::begin_confinement(std::size_t k, double sigma3) {
  group_ = confinement_group(k);
  H5::Group g = file_->createGroup(group_);
  write_scalar_attr<double>(g, "confining_stress_Pa", sigma3);
  g.createGroup("snapshots");
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
  H5::Group g = root.createGroup(snapshot_name(index));
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
    H5::Group s = file_->createGroup("summary");
    write_scalar_attr<double>(s, "cohesion_Pa", series.envelope.cohesion);
    write_scalar_attr<double>(s, "friction_angle_deg",
                              series.envelope.friction_angle * 180 / std::numbers::pi);
    write_scalar_attr<double>(s, "mohr_coulomb_r2", series.envelope.r_squared);
    write_scalar_attr<long>(s, "confinements", static_cast<long>(series.runs.size()));
    write_scalar_attr<double>(s, "wall_time_s", series.wall_time);
    for (std::size_t k = 0; k < series.runs.size(); ++k) {
      const std::string name = confinement_group(k);
      H5::Group g = file_->nameExists(name) ? file_->openGroup(name) : file_->createGroup(name);
      if (!g.attrExists("confining_stress_Pa"))
        write_scalar_attr<double>(g, "confining_stress_Pa", series.runs[k].confining_stress);
      if (!g.nameExists("snapshots")) g.createGroup("snapshots");
      write_run(g, series.runs[k]);
    }
  }
  finish();
}

namespace {

void write_run(H5::Group& where, const LabTestResult& r) {
  {
    H5::Group s = where.createGroup("summary");
    write_scalar_attr<double>(s, "peak_stress_Pa", r.peak_stress);
    write_scalar_attr<double>(s, "peak_force_N_per_m", r.peak_force);
    if (r.type == LabTestType::Uniaxial || r.type == LabTestType::Biaxial) {
      write_scalar_attr<double>(s, "young_modulus_Pa", r.ucs.young_modulus);
      write_scalar_attr<double>(s, "poisson_ratio", r.ucs.poisson_ratio);
      write_scalar_attr<double>(s, "strain_at_half_peak", r.ucs.strain_at_half_peak);
    } else {
      write_scalar_attr<double>(s, "tensile_strength_Pa", r.tensile_strength);
    }
    write_scalar_attr<double>(s, "width_m", r.width);
    write_scalar_attr<double>(s, "height_m", r.height);
    write_scalar_attr<long>(s, "steps", r.steps);
    write_scalar_attr<double>(s, "time_step_s", r.time_step);
    write_scalar_attr<double>(s, "wall_time_s", r.wall_time);
    write_scalar_attr<long>(s, "gauge_discs", static_cast<long>(r.gauge_discs));
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
      write_scalar_attr<double>(s, "characteristic_length_m", b.characteristic_length);
    }
    if (r.type == LabTestType::Biaxial) {
      write_scalar_attr<double>(s, "confining_stress_Pa", r.confining_stress);
      write_scalar_attr<double>(s, "confining_stress_at_peak_Pa", r.confining_stress_at_peak);
      write_scalar_attr<double>(s, "peak_deviator_Pa", r.peak_deviator);
      write_scalar_attr<long>(s, "consolidation_steps", r.consolidation.steps);
      write_scalar_attr<double>(s, "consolidation_worst_error", r.consolidation.worst_error);
    }

    H5::Group g = where.createGroup("genesis");
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
    H5::Group hg = where.createGroup("history");
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
    H5::Group cg = where.createGroup("cracks");
    write_array(cg, "time", t, "s");
    write_array(cg, "x", x, "m");
    write_array(cg, "y", y, "m");
    write_array(cg, "mode", mode, "", "1 = tension, 2 = shear");
    write_array(cg, "class", cls, "", "0 = M (mortar), 1 = ITZ, 2 = A (aggregate)");
    write_array(cg, "first", first, "", "world disc index");
    write_array(cg, "second", second, "", "world disc index");
    write_array(cg, "element", element, "", "flat-joint element 0 .. N_r - 1, -1 = not a flat joint");
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
