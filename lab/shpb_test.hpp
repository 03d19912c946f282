#pragma once
// The split Hopkinson pressure bar test (SPEC 6, docs/lab_tests.md "SHPB"): the specimen sits
// between an incident bar (below it, along +y) and a transmitted bar (above it), each a 1D
// elastic bar (dem/elastic_bar.hpp, exact at Courant 1). A pressure pulse enters the incident
// bar's far end; each bar's specimen end is a rigid face (a wall, dem/wall.hpp) that moves with
// the bar-end velocity, and the bar feels the contact force of the discs on that face as its end
// stress (force per m of thickness / bar width). Gauges on both bars record the strain and its
// two travelling parts; the analysis (lab/shpb_analysis.hpp) shifts them to the faces.
//
// One time step for both: the bars' cell is c0 x the DEM step, with the DEM step set (fixed)
// at the largest value <= the automatic DEM step that divides the bar length into whole cells,
// so each DEM step is exactly one bar step and the bars stay exact. Coupling after each DEM
// step: the bars take the face forces of that step's force pass and return the face velocities
// that move the walls over the next step (a lag of one step, 1e-4 of the pulse for the sample;
// stable while dt x face stiffness / (rho c0 A) << 1, checked in the tests).
#include <cstddef>
#include <vector>

#include "dem/elastic_bar.hpp"
#include "dem/measure.hpp"
#include "io/input_table.hpp"
#include "lab/shpb_analysis.hpp"

namespace cdem::dem {
class World;
struct Walls;
}  // namespace cdem::dem

namespace cdem::lab {

using namespace cdem::dem;  // the engine the lab layer drives

struct LabTestControls;
struct LabTestInput;
struct LabTestHooks;
struct LabTestResult;

// The incident pulse's shape: a half-sine; a rectangle (a striker bar's pulse); a ramp (the
// trapezoid a pulse shaper makes of it: a linear rise, a plateau and a linear fall).
enum class ShpbPulse { HalfSine, Rectangle, Ramp };

// The name of a pulse shape, as the input and the outputs spell it.
const char* pulse_name(ShpbPulse pulse);

struct ShpbOptions {
  // Both bars (the published set-up: steel, 3.0 m, 50 mm wide).
  BarProperties bar{206e9, 7800, 3.0, 0.05};
  double incident_gauge = 1.5;     // m, gauge distance from the specimen face on the incident bar
  double transmitted_gauge = 1.5;  // m, the same on the transmitted bar
  // m, the gauges' length: a foil gauge reads the strain averaged over it (5 mm: a common
  // length on SHPB bars). Used for the force equilibrium as gauges read it; the other figures
  // use the waves at a point.
  double gauge_length = 5e-3;
  ShpbPulse pulse = ShpbPulse::HalfSine;
  double pulse_peak = 0;         // Pa, compression, at the incident bar's far end
  double pulse_duration = 1e-3;  // s
  double pulse_rise = 0.5e-3;    // s, a ramp's rise (and fall) time, <= duration / 2
  // The bars' Poisson ratio, for the face forces as gauges on real round bars of diameter
  // bar.width would read them (lab/shpb_dispersion.hpp); steel 0.29.
  double bar_poisson_ratio = 0.29;
  // s, recorded beyond the incident pulse's passage at the specimen (its arrival L / c0 plus
  // its duration), so the transmitted pulse and the unloading are in the record; at most
  // 2 L / c0 - duration, when the bars' echoes from their far ends reach the faces.
  double after_pulse = 0.1667e-3;

  // Pa, the pulse's stress at time t (s) since it began: sigma_0 sin(pi t / T), sigma_0 on
  // [0, T], or the ramp sigma_0 min(1, t / t_r, (T - t) / t_r); 0 outside.
  double pulse_stress(double t) const;
};

// Reads the [test.shpb] table (docs/lab_tests.md): throws InputError naming the file, the key
// and its allowed range (non-positive E, density, length, width; a gauge outside its bar; a
// pulse longer than 2 L / c0, whose reflection from the loading end would return to the
// specimen before it has passed; a non-positive duration; after_pulse beyond the echoes).
ShpbOptions read_shpb_options(const InputTable& shpb);

// The [test] keys of type "shpb": the [test.shpb] table into controls.shpb, local damping 0
// unless given (a wave test needs no numerical damping), and a clear error for the keys of the
// quasi-static tests that would change it (presets, density scaling, platen velocity, the
// peak stop rule).
void read_shpb_controls(const InputTable& test, LabTestControls& controls);

// The two bars and their coupling to the faces (walls) of a world.
class ShpbBars {
 public:
  // `cells` of each bar (their step is L / (cells c0)); the faces are walls `incident_face`
  // (below the specimen) and `transmitted_face` (above).
  ShpbBars(const ShpbOptions& options, long cells, int incident_face, int transmitted_face);
  // The cells that give the largest bar step <= max_step (s).
  static long cells_for(const BarProperties& bar, double max_step);

  // After a World step: advances both bars one step, loads the incident bar's far end with the
  // pulse, takes the forces of the discs on the faces from the walls' last force pass as the end
  // stresses, and sets the faces' velocities (along y) to the bar-end velocities.
  void couple(World& world);

  double time_step() const { return incident_.time_step(); }
  const ElasticBar& incident() const { return incident_; }
  const ElasticBar& transmitted() const { return transmitted_; }
  long incident_gauge_node() const { return incident_gauge_; }
  long transmitted_gauge_node() const { return transmitted_gauge_; }
  int incident_face() const { return incident_face_; }
  int transmitted_face() const { return transmitted_face_; }
  // Coupling number r = dt K / (rho c0 A) of each face, K = touching contacts x the wall
  // contacts' normal stiffness: the face force answers the bar a step late, which is stable for
  // r < 1 and accurate for r << 1 (the larger of the two faces').
  double coupling_number(const World& world) const;
  // Whole steps a wave takes from a gauge to its bar's face.
  long incident_gauge_lag() const { return incident_.cells() - incident_gauge_; }
  long transmitted_gauge_lag() const { return transmitted_gauge_; }

 private:
  ShpbOptions o_;
  ElasticBar incident_, transmitted_;
  int incident_face_, transmitted_face_;
  long incident_gauge_, transmitted_gauge_;  // nodes
};

// Per bar step (index = step, 0 = the start), strains compression positive.
struct ShpbGaugeRecords {
  std::vector<double> incident_right, incident_left;        // incident gauge: the two waves
  std::vector<double> transmitted_right, transmitted_left;  // transmitted gauge
  // N/m, DEM: the discs on the faces in the force pass the bars took at this step (that of the
  // DEM step that ended here, at the positions one step earlier: the coupling's lag).
  std::vector<double> front_face_force, back_face_force;

  void reserve(std::size_t n);
  void record(const ShpbBars& bars, const Walls& walls);
};

// Puts the two faces on a world (segments as wide as the bars, centred on the specimen's extent
// `extent`, tangent to it below and above), makes the bars with the largest step <= the world's
// automatic step that divides them into whole cells, and fixes the world's step to it.
ShpbBars attach_shpb_bars(World& world, const Box& extent, const ShpbOptions& options);

// The three waves at the faces from the gauge records: eps_i(t) = incident_right(t - a_i / c0),
// eps_r(t) = incident_left(t + a_i / c0), eps_t(t) = transmitted_right(t + a_t / c0), shifts in
// whole steps; the waves end where the gauges' records do.
ShpbWaves face_waves(const ShpbGaugeRecords& records, const ShpbBars& bars);

struct ShpbResult {
  ShpbOptions options;
  long cells = 0;            // per bar
  double cell_size = 0;      // m
  double bar_time_step = 0;  // s, = the DEM step
  double arrival_time = 0;   // s, L / c0: the pulse's front at the specimen
  ShpbGeometry geometry;
  ShpbGaugeRecords gauges;
  ShpbWaves waves;
  ShpbAnalysis analysis;
  double coupling_number = 0;  // largest of the run (ShpbBars::coupling_number)
  double face_work = 0;  // J/m, work the two faces did on the specimen (DEM forces x velocities)
  double dynamic_tensile_strength = 0;  // Pa, disc specimens: 2 F / (pi D t) at the peak
  double bar_wall_time = 0;             // s, spent in the bars and their records
};

// The loading of an SHPB test on a world after genesis; `extent` is the specimen's disc extent
// at the start, `disc_specimen` whether it is a disc (then also a dynamic Brazilian strength).
// Fills res (history at test.history_interval, cracks, shpb, stop reason "pulse_passed"). Throws
// RunError when max_steps cannot hold the record the pulse needs.
void run_shpb_test(World& world, const Box& extent, bool disc_specimen, const LabTestInput& input,
                   const LabTestHooks& hooks, LabTestResult& res);

}  // namespace cdem::lab
