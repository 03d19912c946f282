#pragma once
// Lab tests on a bonded specimen (SPEC 6): uniaxial compression between rigid platens, the
// Brazilian disc between flat platens, curved jaws or loading arcs, direct tension by grip bands of
// discs, and one biaxial test (platens plus servo side walls at a confining stress;
// lab/biaxial_test.hpp runs the series of confinements), the split Hopkinson pressure bar
// (lab/shpb_test.hpp), and the notched-beam three-point bending test (two supports under the beam,
// a loading platen on top at mid-span; lab/three_point_bending.hpp). The test file
// (docs/lab_tests.md) names the specimen, the material table and the test controls; a run does the
// material genesis (SPEC 3.6), loads the specimen until the stop rule confirms its peak
// (lab/stop_rule.hpp), and returns the histories, the cracks and the lab figures.
#include <array>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "core/specimen.hpp"
#include "dem/confinement.hpp"
#include "dem/crack_log.hpp"
#include "dem/fragments.hpp"
#include "dem/world.hpp"
#include "io/input_table.hpp"
#include "lab/joint_record.hpp"
#include "lab/joint_set_input.hpp"
#include "lab/lab_analysis.hpp"
#include "lab/material_genesis.hpp"
#include "lab/material_table.hpp"
#include "lab/shpb_test.hpp"
#include "lab/stop_rule.hpp"
#include "lab/three_point_bending.hpp"

namespace cdem::lab {

using namespace cdem::dem;  // the engine the lab layer drives

enum class LabTestType { Uniaxial, Brazilian, DirectTension, Biaxial, Shpb, ThreePointBending };
// "uniaxial", "brazilian", "direct_tension", "biaxial", "shpb", "three_point_bending"
const char* lab_test_name(LabTestType type);

// How a Brazilian disc is loaded (test.platens).
enum class BrazilianPlatens { Flat, CurvedJaws, LoadingArc };

struct LabTestControls {
  LabTestType type = LabTestType::Uniaxial;
  std::vector<JointSet> joints;  // [[test.joints]]: smooth-joint sets (docs/smooth_joint.md)
  double platen_velocity =
      0.02;                    // m/s, of each platen (or grip band), toward / away from the other
  StopRuleOptions stop{};      // the peak and post-peak stop rule (lab/stop_rule.hpp)
  double local_damping = 0.7;  // alpha
  double time_step_safety = 0.8;
  bool density_scaling = false;
  double scaled_time_step = 1.0;  // s, the step under density scaling
  // > 0: density scaling with the step set to this multiple of the automatic step the true
  // masses give at the start of loading (genesis runs with the true masses). A speed knob that
  // holds for any specimen, unlike scaled_time_step; 0 = off.
  double density_step_factor = 0;
  long history_interval = 100;    // steps between history records
  long snapshot_interval = 0;     // steps between snapshots of the discs; 0 = none
  long max_steps = 5'000'000;     // bound on the run; reaching it is a RunError
  double grip_fraction = 0.05;    // direct tension: grip bands, fraction of the height per end
  double gauge_fraction = 0.5;    // central region of the lateral-strain fit, fraction of H
  double platen_overhang = 0.25;  // platens reach this fraction of the width beyond each side
  // Brazilian: flat platens; curved jaws (ISRM): arcs of radius jaw_radius_ratio x the disc's
  // radius covering +- jaw_cover of the disc's boundary about each pole; or loading arcs: the
  // boundary discs within +- loading_arc / 2 of each pole driven at the platen velocity
  // (lab/loading_arc.hpp).
  BrazilianPlatens platens = BrazilianPlatens::Flat;
  double jaw_radius_ratio = 1.5;
  double jaw_cover = 0.5235987755982988;    // rad, 30 degrees
  double loading_arc = 0.2617993877991494;  // rad, 2 alpha = 15 degrees
  int threads = 1;
  bool lanes = true;  // WorldSettings::lanes: true the CPU's widest set, false none (same bits)
  GenesisOptions genesis{};
  // Biaxial: the confinements of the series (Pa, >= 0; 0 = unconfined, no side walls), and the
  // one of the run in hand (set by run_biaxial_series); dem/confinement.hpp has the servo
  // settings.
  std::vector<double> confining_stresses;
  double confining_stress = 0;
  ConfinementOptions confinement{};
  ShpbOptions shpb{};  // the bars and the pulse of type "shpb" ([test.shpb])
  // Three-point bending (docs/lab_tests.md "Three-point bending"): the span S between the two
  // supports, the length of the support and loading plates, the deflection at which the run
  // ends, and E and f_t of the material for the characteristic length (0 = not given).
  double span = 0;              // m
  double bearing_width = 0;     // m; 0 = kDefaultBearingFraction x the beam's depth
  double max_deflection = 0;    // m; 0 = kDefaultMaxDeflectionFraction x the beam's depth
  double young_modulus = 0;     // Pa
  double tensile_strength = 0;  // Pa
  double pin_friction = 0.5;    // friction coefficient of the pinned (left) support
  // Loading: the platen at platen_velocity, or driven so the CMOD grows at cmod_rate
  // (lab/three_point_bending.hpp, CmodServo), never faster than kCmodServoSpeedCap x cmod_rate
  // and never retracting from a beam loaded below stop_load_fraction x its largest load.
  bool cmod_control = false;
  double cmod_rate = 0;  // m/s
  // The sieve of the fragment analysis after the run (m, increasing; dem/fragments.hpp).
  std::vector<double> fragment_sieve = kDefaultFragmentSieve;
};

// The CMOD servo's cap on the platen speed, in units of the CMOD rate.
constexpr double kCmodServoSpeedCap = 4;

// Three-point bending defaults, as fractions of the beam's depth H.
constexpr double kDefaultBearingFraction = 0.1;          // plates 10 mm long on a 100 mm beam
constexpr double kDefaultMaxDeflectionFraction = 0.005;  // 0.5 mm on a 100 mm beam
constexpr double kDefaultStopLoadFraction = 0.05;        // RILEM-style end of the tail
// The platen velocity of a bending test without platen_velocity: this fraction of the preset's
// (or the default) velocity (docs/lab_tests.md "Three-point bending", loading rate).
constexpr double kBendingVelocityFactor = 0.05;

struct LabTestInput {
  std::string file;            // the test file, as given
  std::string text;            // its text, stored with the results
  std::string materials_text;  // the material file's text when given by name
  // Resolved relative to the test file; with an inline [specimen] table, "<test file> [specimen]"
  // (a name for messages and records).
  std::filesystem::path specimen_path;
  // Inline [specimen] table: the text of the generator file it stands for (its plain keys under
  // [specimen], its sub-tables at the root, no seed: the run's seed is the generator's). Empty
  // when `specimen` names a file. apps/ generates the specimen from it (dem/ has no generator).
  std::string specimen_generator;
  MaterialTable materials;
  LabTestControls controls;
  std::uint64_t seed = 0;
};

// Reads and validates a test file. Throws InputError naming the file and key: missing
// specimen file, unknown test type, bad materials (docs/materials.md), negative velocity or
// other values out of range, unknown keys.
LabTestInput read_lab_test(const std::filesystem::path& file);
LabTestInput read_lab_test(const InputTable& input, const std::filesystem::path& base_dir);
// The controls of a test file's [test] table alone (read_lab_test's reading, defaults and
// checks), for a reader that needs the loading without the specimen and materials.
LabTestControls read_lab_test_controls(const InputTable& test);

// Throws InputError when the specimen's shape does not suit the test (Brazilian needs a disc,
// uniaxial, direct tension and biaxial a rectangle without a notch, three-point bending a
// rectangle whose supports and plates fit under and on it).
void check_specimen_for_test(const Specimen& specimen, const LabTestInput& input);

// Three-point bending: the length of the support and loading plates (m), test.bearing_width or
// its default for the beam.
double bearing_width(const LabTestControls& controls, const Container& beam);

// The stop rule of the loading phase: the test's options, and for three-point bending its
// strain (deflection / H) bound from max_deflection and its damage span (half the ligament).
StopRuleOptions loading_stop_options(const LabTestControls& controls, const Container& specimen);

// Histories, one entry per record (every history_interval steps, plus the last step). Stresses
// and strains are positive in the sense the test loads the specimen: compression for uniaxial
// and Brazilian, tension for direct tension. Lateral strain = -du_x/dx of the central region
// (positive = contraction), so a specimen bulging under compression has a negative one.
// Biaxial: the axial stress is sigma_1 = platen force / (side-wall gap x t), the confining stress
// the side walls' stress sigma_3 (0 unconfined), strains count from the end of consolidation.
struct LabHistory {
  std::vector<long> step;
  std::vector<double> time;              // s
  std::vector<double> axial_strain;      // platen (grip) travel / H0
  std::vector<double> lateral_strain;    // -G_xx of the central region's best-fit gradient
  std::vector<double> axial_stress;      // Pa, mean platen (grip) force / (W t)
  std::vector<double> confining_stress;  // Pa, central-region contact sigma_xx; biaxial: walls
  std::vector<double> platen_force;      // N (per m), mean of the two platens (grips)
  std::vector<double> kinetic_energy;    // J/m, physical masses
  std::vector<double> strain_energy;     // J/m, linear springs, bonds and joints (contact_energy)
  std::vector<double> friction_energy;   // J/m, dissipated by slip since the test began
  std::vector<double> breakage_energy;   // J/m, released by bond failures
  std::vector<double> boundary_work;     // J/m, done by the platens (grips) on the specimen
  std::vector<long> bonds_broken;
  // Three-point bending only (empty otherwise): the platen's load P is platen_force, the nominal
  // flexural stress 3 P S / (2 t H^2) is axial_stress and deflection / H is axial_strain.
  std::vector<double> deflection;        // m, load point relative to the supports
  std::vector<double> cmod;              // m, crack-mouth opening (lab/three_point_bending.hpp)
  std::vector<double> support_reaction;  // N (per m), sum of the two supports' reactions

  void reserve(std::size_t n);
  std::size_t size() const { return time.size(); }
  // Appends the energies of a record (kinetic, strain, friction, breakage from the world; the
  // boundary work so far, J/m) and the bonds broken.
  void push_energies(const World& world, double boundary_work_so_far);
};

// The figures of a three-point bending test (RILEM TC-50 FMC), per metre of thickness where a
// load or a work: docs/lab_tests.md "Three-point bending".
struct BendingResult {
  double span = 0, depth = 0, notch_depth = 0, length = 0;  // m: S, H, a0, L
  double bearing_width = 0;                                 // m, support and loading plates
  double peak_load = 0;                                     // N/m, P_max
  double deflection_at_peak = 0, cmod_at_peak = 0;          // m
  double reaction_at_peak = 0;                              // N/m, sum of the supports
  double flexural_strength = 0;                             // Pa, 3 P_max S / (2 t H^2)
  double net_flexural_strength = 0;                         // Pa, 3 P_max S / (2 t (H - a0)^2)
  double work_of_fracture = 0;           // J/m, W0: area under P-delta to the stop
  double final_deflection = 0;           // m, delta0: the deflection at the stop
  double final_load = 0;                 // N/m, P at the stop
  double mass_between_supports = 0;      // kg/m, beam mass x S / L
  double self_weight_work = 0;           // J/m, m g delta0
  double fracture_energy = 0;            // N/m, RILEM G_F = (W0 + m g delta0) / (t (H - a0))
  double fracture_energy_no_weight = 0;  // N/m, W0 / (t (H - a0)): the DEM beam has no weight
  // The energy balance at the stop (ledger terms from the start of loading, J/m): the strain
  // energy still stored in the beam (its change since the start) and the work dissipated, the
  // platen's booked work less the stored and kinetic energy gained. A beam cut at
  // max_deflection while it still carries load holds part of W0 as recoverable strain energy.
  double stored_energy = 0;               // J/m, U(stop) - U(start)
  double dissipated_work = 0;             // J/m, W - dU - dK (damping, friction, bond breakage)
  double dissipated_fracture_energy = 0;  // N/m, dissipated_work / (t (H - a0))
  double characteristic_length = 0;       // m, E G_F / f_t^2 (0 when E or f_t not given)
};

struct LabTestResult {
  LabTestType type = LabTestType::Uniaxial;
  GenesisReport genesis;
  InstalledJoints joints;    // smooth joints installed, per [[test.joints]] set (lines cut to the
                             // specimen's extent at the start of loading)
  JointStates joint_states;  // every smooth joint at the end of the run
  LabHistory history;
  std::vector<Crack> cracks;
  // crack_count[mode - 1][class]: mode Tension / Shear, class M / ITZ / A.
  std::array<std::array<long, 3>, 2> crack_count{};
  double width = 0, height = 0;  // m, specimen extent between platens at the start (D for a disc)
  double peak_stress = 0;        // Pa, the largest axial stress of the history
  double peak_force = 0;         // N per m, the largest platen (grip) force
  UcsResult ucs;                 // uniaxial; biaxial: of the deviator sigma_1 - sigma_3
  // Biaxial: peak_stress is sigma_1 at the peak deviator, peak_force the platen force there.
  double confining_stress = 0;          // Pa, sigma_3 asked for
  double confining_stress_at_peak = 0;  // Pa, side-wall stress measured at the peak deviator
  double peak_deviator = 0;             // Pa, largest sigma_1 - sigma_3 of the history
  ConsolidationReport consolidation;    // isotropic phase (none when unconfined)
  double tensile_strength = 0;          // Pa, Brazilian (2 P / pi D t) and direct tension (F / W t)
  BendingResult bending;                // three-point bending
  long steps = 0;
  double time_step = 0;         // s, at the start of loading (after bond installation)
  double wall_time = 0;         // s
  std::size_t gauge_discs = 0;  // discs in the lateral-strain region
  // Why the run ended: a completed run always ends at a confirmed post-peak drop (an unconfirmed
  // end is a RunError that names the reason); an SHPB run when its pulse has passed.
  StopReason stop_reason = StopReason::None;
  ShpbResult shpb;      // type "shpb": the bars, their records and the three-wave analysis
  Fragments fragments;  // the bond network's fragments at the end of the run
  // The test's walls when the loading starts (platens, curved jaws, bending supports and plate,
  // biaxial side walls; none for grips or SHPB), for the crack map.
  Walls walls;
  // Where the model or the run may not be what the user meant (printed on stderr as they arise,
  // and listed in the summary): docs/lab_tests.md "Warnings".
  std::vector<std::string> warnings;
};

// Observers of a run: `progress` at every history record, `snapshot` every snapshot_interval
// steps (and at the first and last step), `should_stop` at every history record (true ends the
// run there with StopReason::StoppedByUser and a warning that no peak was confirmed), all
// optional.
struct LabTestHooks {
  std::function<void(const LabHistory&, double peak, long max_steps)> progress;
  std::function<void(const World&, long step, double time)> snapshot;  // loading step, s
  std::function<bool(const World&, const LabHistory&)> should_stop;
  // A warning as it arises (the progress line prints it above itself); unset: to stderr.
  std::function<void(const std::string&)> warning;
};

// Keeps `message` in res.warnings (the summary's) and reports it at once through hooks.warning.
void warn(LabTestResult& res, const LabTestHooks& hooks, const std::string& message);

// Fills res.cracks (times from the loading's start time0, s) and res.crack_count from a run's
// crack log.
void tally_cracks(LabTestResult& res, const CrackLog& log, double time0);

// Genesis + loading. Throws RunError (with the figures reached and the stop reason) when the run
// ends at max_strain or max_steps before the stop rule has confirmed a peak, or when the DEM run
// goes unstable.
LabTestResult run_lab_test(const Specimen& specimen, const LabTestInput& input,
                           const LabTestHooks& hooks = {});

}  // namespace cdem::lab
