#pragma once
// The analysis of a split Hopkinson pressure bar test (SPEC 6, docs/lab_tests.md "SHPB"): from
// the incident, reflected and transmitted strain waves at the specimen's faces, the specimen's
// strain rate, strain and stress histories by the three-wave method and its one- and two-wave
// variants, the dynamic peak strength and modulus, the force equilibrium of the two faces and
// the wave energies. Strains and stresses are compression positive: the incident and
// transmitted waves of a compression test are positive, the reflected wave of a specimen softer
// than the bars negative (tension).
#include <cstddef>
#include <vector>

namespace cdem::lab {

// The three waves at the faces, one value per bar step (the lattice's step, so the time shift
// from a gauge to a face is a whole number of steps and exact).
struct ShpbWaves {
  double time_step = 0;             // s
  std::vector<double> time;         // s, since the loading began
  std::vector<double> incident;     // eps_i at the incident bar's face
  std::vector<double> reflected;    // eps_r there
  std::vector<double> transmitted;  // eps_t at the transmitted bar's face
  // s, since the loading began: the specimen's first bond failure (infinity: none). Before it
  // the specimen is elastic, so a fall of the stress there is the waves' ringing, not a failure:
  // the first failure is looked for from this time on. 0 = from the start.
  double first_crack_time = 0;
  std::size_t size() const { return time.size(); }
};

// What the analysis needs of the set-up.
struct ShpbGeometry {
  double bar_young_modulus = 0;  // Pa
  double bar_wave_speed = 0;     // m/s, c0
  double bar_area = 0;           // m2, A = bar width x 1 m
  double specimen_length = 0;    // m, l_s: distance between the faces at the start
  double specimen_area = 0;      // m2, A_s = specimen width (disc: diameter) x 1 m
  // s, the time over which a gauge averages a passing wave: its length / c0 (a foil gauge reads
  // the strain averaged over its length). 0: point gauges, the waves as recorded.
  double gauge_window = 0;
  // The bars as real round bars of this radius (m) and Poisson ratio, for the face forces as
  // their gauges would read them (lab/shpb_dispersion.hpp): the waves dispersed over the
  // gauges' distances from the faces (m). Radius 0: not computed.
  double bar_radius = 0;
  double bar_poisson_ratio = 0;
  double incident_gauge = 0, transmitted_gauge = 0;
};

// The stress fall, as a fraction of the running maximum, that marks the first failure.
constexpr double kFirstFailureDrop = 0.10;
// Records below this fraction of the dynamic strength do not count for the first failure (the
// noise of the wave's foot).
constexpr double kFirstFailureFloor = 0.05;

// The histories, one value per entry of ShpbWaves.
struct ShpbHistories {
  std::vector<double> front_force;  // N/m, E A (eps_i + eps_r): incident-bar face
  std::vector<double> back_force;   // N/m, E A eps_t: transmitted-bar face
  // Three-wave: rate c0 / l_s (eps_i - eps_r - eps_t), stress (front + back) / (2 A_s).
  std::vector<double> strain_rate;  // 1/s
  std::vector<double> strain;       // 1, time integral of the strain rate
  std::vector<double> stress;       // Pa
  // One-wave (back face) and two-wave (front face) stresses, both with the equilibrium strain
  // rate -2 c0 eps_r / l_s and its integral.
  std::vector<double> stress_one_wave;        // Pa, back force / A_s
  std::vector<double> stress_two_wave;        // Pa, front force / A_s
  std::vector<double> strain_rate_reflected;  // 1/s, -2 c0 eps_r / l_s
  std::vector<double> strain_reflected;       // 1
  // N/m, the face forces as the gauges of real round bars read them (ShpbGeometry::bar_radius
  // > 0; empty otherwise): E A (eps_i + eps_r) and E A eps_t with each wave taken where its
  // gauge is (the incident wave before, the reflected and transmitted waves after their
  // dispersion over the gauge distance), averaged over the gauge length and shifted to the
  // face by distance / c0, as an experimenter computes them.
  std::vector<double> front_force_gauges, back_force_gauges;
};

struct ShpbFigures {
  double peak_stress = 0;   // Pa, largest three-wave stress (dynamic strength)
  double time_at_peak = 0;  // s
  double strain_at_peak = 0;
  double strain_rate_at_peak = 0;  // 1/s
  // 1/s, mean three-wave strain rate over the loading branch: strain at the peak / the time
  // from the first record of stress above 5 % of the peak to the peak.
  double mean_strain_rate = 0;
  double peak_stress_one_wave = 0;  // Pa
  double peak_stress_two_wave = 0;  // Pa
  // Dynamic modulus on the three-wave stress-strain curve: tangent = least-squares slope of the
  // loading branch between 40 % and 60 % of the peak (as the UCS modulus, lab/lab_analysis.hpp);
  // secant = 50 % of the peak / the strain there. 0 when the branch has too few points.
  double tangent_modulus = 0;  // Pa
  double secant_modulus = 0;   // Pa
  // Force equilibrium: R = 2 (F_front - F_back) / (F_front + F_back); at the peak, and the
  // largest and the mean |R| over the loading branch from 50 % of the peak to the peak (one
  // value per step: the largest catches single contact events, the mean the trend).
  double equilibrium_at_peak = 0;
  double equilibrium_worst = 0;
  double equilibrium_mean = 0;
  // The largest |R| of the face forces as gauges of ShpbGeometry::gauge_window read them (each
  // force averaged over that window, centred), over the same branch.
  double equilibrium_worst_gauge = 0;
  // The first failure: from the first crack on (ShpbWaves::first_crack_time), the largest stress
  // before the stress first falls kFirstFailureDrop below its running maximum (records above
  // kFirstFailureFloor x the peak); the peak when it never does. At high pulses the peak is a later
  // hump of the crushed specimen (docs/lab_tests.md).
  double first_failure_stress = 0;   // Pa
  double time_at_first_failure = 0;  // s
  // |R| per step (largest, mean) and as the gauges read it (largest) from 50 % of the first
  // failure stress to it: the loading branch of the intact specimen.
  double equilibrium_worst_first_failure = 0;
  double equilibrium_mean_first_failure = 0;
  double equilibrium_worst_gauge_first_failure = 0;
  // |R| (largest, mean) of the forces as real bars' gauges read them (front_force_gauges,
  // back_force_gauges), to the peak and to the first failure, each from 50 % of it; 0 when
  // they are not computed.
  double equilibrium_worst_bar = 0, equilibrium_mean_bar = 0;
  double equilibrium_worst_bar_first_failure = 0, equilibrium_mean_bar_first_failure = 0;
  // J per m of thickness: W = A E c0 sum eps^2 dt over the record; absorbed = W_i - W_r - W_t.
  double incident_energy = 0, reflected_energy = 0, transmitted_energy = 0, absorbed_energy = 0;
};

struct ShpbAnalysis {
  ShpbHistories histories;
  ShpbFigures figures;
};

// Throws std::invalid_argument for inconsistent lengths, non-positive geometry, or waves that
// never load the specimen (no positive three-wave stress).
ShpbAnalysis analyse_shpb(const ShpbWaves& waves, const ShpbGeometry& geometry);

}  // namespace cdem::lab
