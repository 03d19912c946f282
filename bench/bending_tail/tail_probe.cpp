// Looks inside a three-point bending run (issue 14, "what carries the G_F tail"): runs the test
// of a `cdem run` file exactly as `cdem run` does (same specimen, genesis, loading; the probe
// only reads the world at history records, so the run's numbers are the command's) and, when
// the load-point deflection first reaches each of the given values, writes the state a
// load-path analysis needs (bench/bending_tail/analyse_tail.py):
//   OUT/history.csv          every record: step, deflection (m), P (N/m), supports (N/m), CMOD
//                            (m), strain and kinetic energy, the platen's work (J/m); flushed
//                            at every record, so a run still going (or stopped) can be read;
//                            the last record (the stop's) is added when the run ends
//   OUT/beam.csv             at the first record: S, H, a0, L (m), the mass between the
//                            supports (kg/m, as the summary's: every body's mass x S / L)
//   OUT/figures.csv          at the end: the run's RILEM and energy figures (SI), stop reason
//   OUT/discs_K.csv          per disc: position now and at the first record (m), radius (m),
//                            body, 1 if the body is an aggregate clump
//   OUT/contacts_K.csv       per disc-disc pair in contact or bonded: discs, class (0 M, 1 ITZ,
//                            2 A), bond kind now (0 none), bonded flat-joint elements now, 1 if
//                            the pair was bonded at the first record, normal force (N/m,
//                            repulsive positive), force on the second disc (N/m)
//   OUT/walls_K.csv          per disc-wall contact: disc, wall, force on the disc (N/m), contact
//                            point (m); wall 0 the pin, 1 the roller, 2 the platen
//   OUT/cracks_K.csv         every bond failure so far: x, y (m), mode, class, first, second
//   OUT/record_K.csv         the history record of the dump: step, deflection (m), P, supports
//                            (N/m), CMOD (m)
// K counts the deflections from 0. Usage:
//   tail_probe TEST.toml OUT_DIR DEFLECTION_MM...
#include <algorithm>
#include <bit>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <set>
#include <string>
#include <vector>

#include "core/input_error.hpp"
#include "io/specimen_file.hpp"
#include "lab/lab_test.hpp"

namespace {

using namespace cdem;
using namespace cdem::dem;
using namespace cdem::lab;

struct Probe {
  std::filesystem::path dir;
  std::vector<double> targets;  // m, ascending
  std::size_t next = 0;
  std::vector<double> x0, y0;  // m, disc centres at the first record
  std::set<std::uint64_t> bonded0;

  void start(const World& w) {
    x0.assign(w.discs().x.begin(), w.discs().x.end());
    y0.assign(w.discs().y.begin(), w.discs().y.end());
    const ContactStore& nl = w.contacts();
    for (std::size_t k = 0; k < nl.keys.size(); ++k)
      if (nl.state.bond[k] != 0) bonded0.insert(nl.keys[k]);
  }

  std::ofstream open(const std::string& name) const {
    std::ofstream f(dir / name);
    f.precision(12);
    return f;
  }

  // Writes the history record `i` of h (header and one row, or the row alone).
  static void record(std::ofstream& f, const LabHistory& h, std::size_t i, bool header) {
    if (header)
      f << "step,deflection,load,supports,cmod,strain_energy,kinetic_energy,boundary_work\n";
    f << h.step[i] << ',' << h.deflection[i] << ',' << h.platen_force[i] << ','
      << h.support_reaction[i] << ',' << h.cmod[i] << ',' << h.strain_energy[i] << ','
      << h.kinetic_energy[i] << ',' << h.boundary_work[i] << '\n';
  }

  // The beam's geometry (m) and its mass between the supports (kg/m), as analyse_bending
  // computes it.
  void beam(const World& w, const Container& mould, double span) const {
    double mass = 0;  // kg/m
    for (const double m : w.bodies().mass) mass += m;
    std::ofstream f = open("beam.csv");
    f << "span,depth,notch_depth,length,mass_between_supports\n"
      << span << ',' << mould.height << ',' << mould.notch_depth << ',' << mould.width << ','
      << mass * span / mould.width << '\n';
  }

  void dump(const World& w, const LabHistory& h, std::size_t k) const {
    const std::string tag = '_' + std::to_string(k).append(".csv");
    std::ofstream fr = open("record" + tag);
    record(fr, h, h.size() - 1, true);
    const Discs& d = w.discs();
    std::ofstream fd = open("discs" + tag);
    fd << "disc,x,y,x0,y0,r,body,clump\n";
    for (std::size_t i = 0; i < d.x.size(); ++i)
      fd << i << ',' << d.x[i] << ',' << d.y[i] << ',' << x0[i] << ',' << y0[i] << ',' << d.r[i]
         << ',' << d.body[i] << ',' << int(w.bodies().is_clump[d.body[i]]) << '\n';
    const ContactStore& nl = w.contacts();
    const ContactForces& pf = w.pair_forces();
    std::ofstream fc = open("contacts" + tag);
    fc << "first,second,class,bond,elements,bonded0,overlap,normal,fx,fy\n";
    for (std::size_t p = 0; p < nl.keys.size(); ++p) {
      const bool bonded = nl.state.bond[p] != 0;
      if (!bonded && pf.overlap[p] <= 0) continue;
      const std::int32_t j = nl.state.joint[p];
      const int elements =
          bonded && j >= 0 ? std::popcount(nl.flat_joints.bonded[static_cast<std::size_t>(j)]) : 0;
      fc << nl.first[p] << ',' << nl.second[p] << ',' << int(nl.contact_class[p]) << ','
         << int(nl.state.bond[p]) << ',' << elements << ',' << bonded0.count(nl.keys[p]) << ','
         << pf.overlap[p] << ',' << pf.normal[p] << ',' << pf.fx[p] << ',' << pf.fy[p] << '\n';
    }
    const ContactForces& wf = w.wall_forces();
    std::ofstream fw = open("walls" + tag);
    fw << "disc,wall,fx,fy,cx,cy\n";
    for (std::size_t p = 0; p < nl.wall_keys.size(); ++p)
      if (wf.overlap[p] > 0)
        fw << nl.wall_disc[p] << ',' << nl.wall_index[p] << ',' << wf.fx[p] << ',' << wf.fy[p]
           << ',' << wf.cx[p] << ',' << wf.cy[p] << '\n';
    std::ofstream fk = open("cracks" + tag);
    fk << "x,y,mode,class,first,second\n";
    for (const Crack& c : w.cracks().cracks)
      fk << c.x << ',' << c.y << ',' << int(c.mode) << ',' << int(c.contact_class) << ',' << c.first
         << ',' << c.second << '\n';
  }
};

}  // namespace

int main(int argc, char** argv) {
  if (argc < 4) {
    std::cerr << "usage: tail_probe TEST.toml OUT_DIR DEFLECTION_MM...\n";
    return 1;
  }
  try {
    const LabTestInput input = read_lab_test(argv[1]);
    if (input.controls.type != LabTestType::ThreePointBending || !input.specimen_generator.empty())
      throw InputError(argv[1], "test.type",
                       "three_point_bending with a specimen file (no inline [specimen])");
    const Specimen specimen = read_specimen(input.specimen_path);
    check_specimen_for_test(specimen, input);
    Probe probe;
    probe.dir = argv[2];
    std::filesystem::create_directories(probe.dir);
    for (int a = 3; a < argc; ++a) probe.targets.push_back(std::stod(argv[a]) * 1e-3);
    std::sort(probe.targets.begin(), probe.targets.end());
    std::ofstream hist = probe.open("history.csv");
    std::size_t written = 0;  // history records in history.csv
    LabTestHooks hooks;
    hooks.should_stop = [&](const World& w, const LabHistory& h) {
      if (h.size() == 1) {
        probe.start(w);
        probe.beam(w, specimen.container, input.controls.span);
      }
      Probe::record(hist, h, h.size() - 1, h.size() == 1);
      hist.flush();
      written = h.size();
      for (; probe.next < probe.targets.size() && h.deflection.back() >= probe.targets[probe.next];
           ++probe.next)
        probe.dump(w, h, probe.next);
      return false;
    };
    const LabTestResult r = run_lab_test(specimen, input, hooks);
    // The hook is not called at the record that stops the run: add it (and any other unwritten).
    for (std::size_t i = written; i < r.history.size(); ++i)
      Probe::record(hist, r.history, i, i == 0);
    const BendingResult& b = r.bending;
    std::ofstream fig = probe.open("figures.csv");
    fig << "peak_load,deflection_at_peak,final_deflection,final_load,work_of_fracture,"
           "fracture_energy,fracture_energy_no_weight,stored_energy,dissipated_fracture_energy,"
           "stop_reason\n"
        << b.peak_load << ',' << b.deflection_at_peak << ',' << b.final_deflection << ','
        << b.final_load << ',' << b.work_of_fracture << ',' << b.fracture_energy << ','
        << b.fracture_energy_no_weight << ',' << b.stored_energy << ','
        << b.dissipated_fracture_energy << ',' << stop_reason_name(r.stop_reason) << '\n';
    std::printf("P_max %.4f kN/m at %.5f mm, W0 %.5f J/m, G_F %.3f N/m, stop at %.5f mm\n",
                r.bending.peak_load * 1e-3, r.bending.deflection_at_peak * 1e3,
                r.bending.work_of_fracture, r.bending.fracture_energy,
                r.bending.final_deflection * 1e3);
    return 0;
  } catch (const std::exception& e) {
    std::cerr << "tail_probe: " << e.what() << '\n';
    return 2;
  }
}
