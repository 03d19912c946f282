#include "lab/shpb_test.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numbers>
#include <sstream>
#include <stdexcept>

#include "core/input_error.hpp"
#include "dem/measure.hpp"
#include "dem/servo.hpp"
#include "dem/strain_measure.hpp"
#include "dem/world.hpp"
#include "lab/lab_analysis.hpp"
#include "lab/lab_test.hpp"

namespace cdem::lab {

using namespace cdem::dem;  // the engine the lab layer drives

const char* pulse_name(ShpbPulse pulse) {
  switch (pulse) {
    case ShpbPulse::Rectangle:
      return "rectangle";
    case ShpbPulse::Ramp:
      return "ramp";
    case ShpbPulse::HalfSine:
      break;
  }
  return "half_sine";
}

double ShpbOptions::pulse_stress(double t) const {
  if (t < 0 || t > pulse_duration) return 0;
  switch (pulse) {
    case ShpbPulse::Rectangle:
      return pulse_peak;
    case ShpbPulse::Ramp:
      return pulse_peak * std::min({1.0, t / pulse_rise, (pulse_duration - t) / pulse_rise});
    case ShpbPulse::HalfSine:
      break;
  }
  return pulse_peak * std::sin(std::numbers::pi * t / pulse_duration);
}

ShpbOptions read_shpb_options(const InputTable& t) {
  t.reject_unknown_keys({"bar_young_modulus", "bar_density", "bar_length", "bar_width",
                         "bar_poisson_ratio", "incident_gauge", "transmitted_gauge", "gauge_length",
                         "pulse", "pulse_peak", "pulse_duration", "pulse_rise", "after_pulse"});
  ShpbOptions o;
  BarProperties& b = o.bar;
  b.young_modulus =
      t.quantity_or("bar_young_modulus", Dimension::Stress, b.young_modulus, Range::positive());
  b.density = t.quantity_or("bar_density", Dimension::Density, b.density, Range::positive());
  b.length = t.quantity_or("bar_length", Dimension::Length, b.length, Range::positive());
  b.width = t.quantity_or("bar_width", Dimension::Length, b.width, Range::positive());
  o.bar_poisson_ratio = t.number_or("bar_poisson_ratio", o.bar_poisson_ratio, Range::open(0, 0.5));
  // Gauges: on the bar, from its specimen face (0) to its far end (L).
  o.incident_gauge = t.quantity_or("incident_gauge", Dimension::Length, 0.5 * b.length,
                                   Range::closed(0, b.length));
  o.transmitted_gauge = t.quantity_or("transmitted_gauge", Dimension::Length, 0.5 * b.length,
                                      Range::closed(0, b.length));
  o.gauge_length = t.quantity_or("gauge_length", Dimension::Length, o.gauge_length,
                                 Range::closed(0, 0.1 * b.length));
  const std::string pulse = t.string_or("pulse", "half_sine", {"half_sine", "rectangle", "ramp"});
  for (const ShpbPulse p : {ShpbPulse::HalfSine, ShpbPulse::Rectangle, ShpbPulse::Ramp})
    if (pulse == pulse_name(p)) o.pulse = p;
  o.pulse_peak = t.quantity("pulse_peak", Dimension::Stress, Range::positive());
  // The wave the specimen reflects returns from the loading end (and the transmitted wave from
  // the transmitted bar's free end) 2 L / c0 after the pulse's front reached the specimen; a
  // longer pulse would meet its own echo there.
  const double transit = 2 * b.length / b.wave_speed();
  o.pulse_duration = t.quantity_or("pulse_duration", Dimension::Time, o.pulse_duration,
                                   Range::left_open(0, transit));
  if (o.pulse == ShpbPulse::Ramp)
    o.pulse_rise = t.quantity_or("pulse_rise", Dimension::Time, 0.5 * o.pulse_duration,
                                 Range::left_open(0, 0.5 * o.pulse_duration));
  else if (t.has("pulse_rise"))
    t.fail("pulse_rise", "only for pulse = \"ramp\"");
  // The record ends before those echoes reach the specimen's faces.
  const double room = transit - o.pulse_duration;
  o.after_pulse = t.quantity_or("after_pulse", Dimension::Time,
                                std::min(0.25 * o.pulse_duration, room), Range::closed(0, room));
  return o;
}

void read_shpb_controls(const InputTable& t, LabTestControls& c) {
  for (const char* key :
       {"preset", "density_scaling", "scaled_time_step", "density_scaling_step_factor",
        "platen_velocity", "platens", "jaw_radius_ratio", "stop_fraction", "stop_strain_margin",
        "stop_confirm_records", "stop_min_cracks", "stop_damage_span", "max_strain"})
    if (t.has(key))
      t.fail(key,
             "not used by type = \"shpb\" (true masses, the bars load the specimen, the run "
             "ends when the pulse has passed)");
  c.density_scaling = false;
  c.density_step_factor = 0;
  c.local_damping = 0;
  c.shpb = read_shpb_options(t.table("shpb"));
}

ShpbBars::ShpbBars(const ShpbOptions& options, long cells, int incident_face, int transmitted_face)
    : o_(options),
      incident_(options.bar, cells),
      transmitted_(options.bar, cells),
      incident_face_(incident_face),
      transmitted_face_(transmitted_face),
      // The incident bar runs from its loaded end (x = 0) to the specimen (x = L); the
      // transmitted bar from the specimen (x = 0) to its free end.
      incident_gauge_(incident_.node_at(options.bar.length - options.incident_gauge)),
      transmitted_gauge_(transmitted_.node_at(options.transmitted_gauge)) {}

long ShpbBars::cells_for(const BarProperties& bar, double max_step) {
  if (!(max_step > 0)) throw std::invalid_argument("ShpbBars: the DEM step must be > 0");
  return std::max(1L, static_cast<long>(std::ceil(bar.length / (bar.wave_speed() * max_step))));
}

void ShpbBars::couple(World& world) {
  const Walls& walls = world.walls();
  const double area = o_.bar.area();
  incident_.advance();
  transmitted_.advance();
  incident_.set_end_stress(BarEnd::Left, o_.pulse_stress(incident_.time()));
  // The discs push the incident face down (fy < 0) and the transmitted face up when they are
  // compressed.
  incident_.set_end_stress(BarEnd::Right, -walls.fy[incident_face_] / area);
  transmitted_.set_end_stress(BarEnd::Left, walls.fy[transmitted_face_] / area);
  transmitted_.set_end_stress(BarEnd::Right, 0);  // free end
  world.set_wall_velocity(incident_face_, 0, incident_.end_velocity(BarEnd::Right));
  world.set_wall_velocity(transmitted_face_, 0, transmitted_.end_velocity(BarEnd::Left));
}

void ShpbGaugeRecords::reserve(std::size_t n) {
  for (auto* v : {&incident_right, &incident_left, &transmitted_right, &transmitted_left,
                  &front_face_force, &back_face_force})
    v->reserve(n);
}

double ShpbBars::coupling_number(const World& world) const {
  // Before the first force pass of the neighbour list there are no contact forces to count.
  if (world.wall_forces().overlap.size() != world.contacts().wall_keys.size()) return 0;
  const double kn =
      world.settings().laws[static_cast<int>(ContactClass::Wall)].wall_normal_stiffness();
  const long contacts = std::max(wall_contact_count(world, incident_face_),
                                 wall_contact_count(world, transmitted_face_));
  return time_step() * static_cast<double>(contacts) * kn / (o_.bar.impedance() * o_.bar.area());
}

void ShpbGaugeRecords::record(const ShpbBars& bars, const Walls& walls) {
  const int incident_face = bars.incident_face(), transmitted_face = bars.transmitted_face();
  const double e = bars.incident().properties().young_modulus;
  const long gi = bars.incident_gauge_node(), gt = bars.transmitted_gauge_node();
  incident_right.push_back(bars.incident().right_going(gi) / e);
  incident_left.push_back(bars.incident().left_going(gi) / e);
  transmitted_right.push_back(bars.transmitted().right_going(gt) / e);
  transmitted_left.push_back(bars.transmitted().left_going(gt) / e);
  front_face_force.push_back(-walls.fy[incident_face]);
  back_face_force.push_back(walls.fy[transmitted_face]);
}

ShpbBars attach_shpb_bars(World& world, const Box& e, const ShpbOptions& o) {
  // Incident face below, transmitted above, each with the discs on its left (dem/servo.hpp).
  const double xc = 0.5 * (e.xmin + e.xmax), half = 0.5 * o.bar.width;
  const int incident = world.add_wall(xc - half, e.ymin, xc + half, e.ymin);
  const int transmitted = world.add_wall(xc + half, e.ymax, xc - half, e.ymax);
  world.set_fixed_time_step(0);
  world.refresh_neighbors();
  ShpbBars bars(o, ShpbBars::cells_for(o.bar, world.time_step()), incident, transmitted);
  world.set_fixed_time_step(bars.time_step());
  world.refresh_neighbors();
  return bars;
}

ShpbWaves face_waves(const ShpbGaugeRecords& r, const ShpbBars& bars) {
  const long di = bars.incident_gauge_lag(), dt = bars.transmitted_gauge_lag();
  const long records = static_cast<long>(r.incident_right.size());
  ShpbWaves w;
  w.time_step = bars.time_step();
  for (long k = 0; k + std::max(di, dt) < records; ++k) {
    w.time.push_back(static_cast<double>(k) * w.time_step);
    w.incident.push_back(k >= di ? r.incident_right[static_cast<std::size_t>(k - di)] : 0.0);
    w.reflected.push_back(r.incident_left[static_cast<std::size_t>(k + di)]);
    w.transmitted.push_back(r.transmitted_right[static_cast<std::size_t>(k + dt)]);
  }
  return w;
}

namespace {

// The discs of a relaxed specimen reach a little beyond its mould (0.4 um on 50 mm for the
// sample); a face's end point still holds them. Wider than this fraction is warned about.
constexpr double kWidthTolerance = 0.01;

// Above this coupling number the one-step lag of the face force shows in the waves (the
// coupling tests hold 1 % at 0.13).
constexpr double kCouplingLimit = 0.3;

// The largest |R| that counts as force equilibrium (issue 16: "within 10 %").
constexpr double kEquilibriumLimit = 0.10;

// The run's doubts about its own figures: a 3-wave peak that is not the failure of the intact
// specimen, and faces out of equilibrium before the first failure as real bars' gauges read
// them (docs/lab_tests.md "Pulse shaper and real bars' gauges").
void warn_shpb_figures(LabTestResult& res, const LabTestHooks& hooks, const ShpbFigures& f) {
  if (f.first_failure_stress < f.peak_stress) {
    std::ostringstream msg;
    msg << "the 3-wave peak (" << f.peak_stress * 1e-6 << " MPa at " << f.time_at_peak * 1e6
        << " us) comes after a first failure at " << f.first_failure_stress * 1e-6 << " MPa ("
        << f.time_at_first_failure * 1e6
        << " us): it is a hump of the cracked specimen; the first failure peak is the strength "
           "of the intact specimen";
    warn(res, hooks, msg.str());
  }
  if (f.equilibrium_worst_bar_first_failure > kEquilibriumLimit) {
    std::ostringstream msg;
    msg << "the face forces differ by up to " << 100 * f.equilibrium_worst_bar_first_failure
        << " % before the first failure even as real bars' gauges read them (more than "
        << 100 * kEquilibriumLimit << " %): the 3-wave stress is not a specimen stress there";
    warn(res, hooks, msg.str());
  }
}

}  // namespace

void run_shpb_test(World& world, const Box& e, bool disc_specimen, const LabTestInput& input,
                   const LabTestHooks& hooks, LabTestResult& res) {
  const LabTestControls& c = input.controls;
  const ShpbOptions& o = c.shpb;
  ShpbResult& out = res.shpb;
  out.options = o;
  ShpbBars bars = attach_shpb_bars(world, e, o);
  const int incident_face = bars.incident_face(), transmitted_face = bars.transmitted_face();
  out.cells = bars.incident().cells();
  out.cell_size = bars.incident().cell_size();
  out.bar_time_step = bars.time_step();
  out.arrival_time = o.bar.length / o.bar.wave_speed();
  res.time_step = world.time_step();

  const double specimen_width = e.xmax - e.xmin;
  res.width = specimen_width;
  res.height = e.ymax - e.ymin;
  if (specimen_width > o.bar.width * (1 + kWidthTolerance)) {
    std::ostringstream msg;
    msg << "the specimen (" << specimen_width * 1e3 << " mm) is wider than the bars ("
        << o.bar.width * 1e3 << " mm): the faces load only its middle";
    warn(res, hooks, msg.str());
  }
  out.geometry = ShpbGeometry{
      o.bar.young_modulus, o.bar.wave_speed(),          o.bar.area(),
      res.height,          specimen_width * kThickness, o.gauge_length / o.bar.wave_speed(),
      0.5 * o.bar.width,   o.bar_poisson_ratio,         o.incident_gauge,
      o.transmitted_gauge};

  // The record runs until the incident pulse has passed the specimen, plus after_pulse, plus
  // the time the waves take from the faces to the farther gauge.
  const long lag = std::max(bars.incident_gauge_lag(), bars.transmitted_gauge_lag());
  const long needed =
      static_cast<long>(
          std::ceil((out.arrival_time + o.pulse_duration + o.after_pulse) / bars.time_step())) +
      lag;
  if (needed > c.max_steps) {
    std::ostringstream msg;
    msg << "the SHPB record needs " << needed << " steps of " << bars.time_step()
        << " s (the pulse's arrival " << out.arrival_time << " s + its duration "
        << o.pulse_duration << " s + after_pulse " << o.after_pulse
        << " s + the gauge-to-face transit), more than test.max_steps = " << c.max_steps;
    throw RunError(msg.str());
  }
  out.gauges.reserve(static_cast<std::size_t>(needed + 1));

  // The central region of the lateral strain, as in the quasi-static tests.
  const double ymid = 0.5 * (e.ymin + e.ymax), half = 0.5 * c.gauge_fraction * res.height;
  const Box gauge_box{e.xmin, ymid - half, e.xmax, ymid + half};
  const StrainGauge gauge(world, gauge_box);
  res.gauge_discs = gauge.disc_count();
  LabHistory& h = res.history;
  h.reserve(static_cast<std::size_t>(needed / c.history_interval + 2));
  const double y0_incident = world.walls().ay[incident_face];
  const double y0_transmitted = world.walls().ay[transmitted_face];
  const long step0 = world.step_count();
  const double time0 = world.time();
  double face_work = 0;  // J/m
  const auto record = [&] {
    const double force =
        0.5 * (world.walls().fy[transmitted_face] - world.walls().fy[incident_face]);  // N/m
    const double travel = (y0_transmitted - y0_incident) -
                          (world.walls().ay[transmitted_face] - world.walls().ay[incident_face]);
    h.step.push_back(world.step_count() - step0);
    h.time.push_back(world.time() - time0);
    h.axial_strain.push_back(travel / res.height);
    h.lateral_strain.push_back(-gauge.gradient(world)(0, 0));
    h.axial_stress.push_back(force / out.geometry.specimen_area);
    h.confining_stress.push_back(contact_stress(world, gauge_box)(0, 0));
    h.platen_force.push_back(force);
    h.push_energies(world, face_work);
    out.coupling_number = std::max(out.coupling_number, bars.coupling_number(world));
    if (hooks.progress)
      hooks.progress(h, *std::max_element(h.axial_stress.begin(), h.axial_stress.end()), needed);
  };

  using Clock = std::chrono::steady_clock;
  Clock::duration in_bars{};
  out.gauges.record(bars, world.walls());
  record();
  const bool snapshots = hooks.snapshot && c.snapshot_interval > 0;
  if (snapshots) hooks.snapshot(world, 0, 0.0);
  // Only the steps the loop records or snapshots keep the per-pair results, as in the
  // quasi-static loop: a record reads them (the confining stress, the energies), a snapshot
  // hook may.
  const PairResultsOnRequestScope on_request(world);
  for (long s = 1; s <= needed; ++s) {
    const bool records = s % c.history_interval == 0 || s == needed;
    const bool snapshot = snapshots && (s % c.snapshot_interval == 0 || s == needed);
    if (records || snapshot) world.request_pair_results();
    world.step();
    // Work of this step: the force of its pass over the faces' displacement in it.
    for (const int f : {incident_face, transmitted_face})
      face_work -= world.walls().fy[f] * world.walls().vy[f] * world.time_step();
    const Clock::time_point t0 = Clock::now();
    bars.couple(world);
    out.gauges.record(bars, world.walls());
    in_bars += Clock::now() - t0;
    if (records) record();
    if (snapshot) hooks.snapshot(world, world.step_count() - step0, world.time() - time0);
  }
  out.bar_wall_time = std::chrono::duration<double>(in_bars).count();
  if (out.coupling_number > kCouplingLimit) {
    std::ostringstream msg;
    msg << "the bar-face coupling number dt K / (rho c0 A) reached " << out.coupling_number
        << " (stable below 1, accurate well below " << kCouplingLimit
        << "): the faces' contacts are stiff for the bars at this step";
    warn(res, hooks, msg.str());
  }
  out.face_work = face_work;
  if (world.critical_time_step() > 0 && world.time_step() > world.critical_time_step()) {
    std::ostringstream msg;
    msg << "the fixed step " << world.time_step() << " s exceeded the critical step "
        << world.critical_time_step() << " s of the contacts at the end of the run";
    warn(res, hooks, msg.str());
  }

  out.waves = face_waves(out.gauges, bars);
  out.waves.first_crack_time = std::numeric_limits<double>::infinity();
  for (const Crack& k : world.cracks().cracks)
    if (k.time >= time0) {  // the log is in time order; earlier ones are the genesis's
      out.waves.first_crack_time = k.time - time0;
      break;
    }
  try {
    out.analysis = analyse_shpb(out.waves, out.geometry);
  } catch (const std::invalid_argument& err) {
    throw RunError(std::string("SHPB analysis: ") + err.what());
  }
  const ShpbFigures& f = out.analysis.figures;
  warn_shpb_figures(res, hooks, f);
  res.peak_stress = f.peak_stress;
  res.peak_force = f.peak_stress * out.geometry.specimen_area;  // mean of the two faces, N/m
  // A disc between the bars splits as in a Brazilian test (the dynamic Brazilian test).
  if (disc_specimen) out.dynamic_tensile_strength = brazilian_strength(res.peak_force, res.width);
  res.stop_reason = StopReason::PulsePassed;
  res.steps = world.step_count() - step0;
  tally_cracks(res, world.cracks(), time0);
}

}  // namespace cdem::lab
