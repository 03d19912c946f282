#pragma once
// The DEM world: bodies, their discs, walls, the neighbour list and the contact laws, advanced
// one cycle at a time. Its state is read through const views of the structure-of-arrays
// (`bodies()`, `discs()`, ...) and changed only through the methods below, each of which carries
// its own side effects (neighbour list and time step, energy reference), so no caller has to
// remember them. Engine parts that edit the world's arrays in place (bond and joint
// installation, the wall servos, the energy reference) are its friends.
#include <array>
#include <limits>
#include <string>
#include <vector>

#include "core/specimen.hpp"
#include "dem/bodies.hpp"
#include "dem/contact_model.hpp"
#include "dem/contact_solver.hpp"
#include "dem/crack_log.hpp"
#include "dem/discs.hpp"
#include "dem/energy.hpp"
#include "dem/integrator.hpp"
#include "dem/linear_contact.hpp"
#include "dem/memory_footprint.hpp"
#include "dem/neighbor_list.hpp"
#include "dem/servo.hpp"
#include "dem/threaded_cycle.hpp"
#include "dem/time_step_stiffness.hpp"
#include "dem/wall.hpp"
#include "dem/worker_team.hpp"

namespace cdem::dem {

struct BondInstallation;  // dem/bond_installation.hpp
struct InstalledBonds;
struct JointSet;  // dem/smooth_joint_install.hpp
struct InstalledJoints;

struct WorldSettings {
  double local_damping = 0.7;     // alpha, 0 = off
  double time_step_safety = 0.8;  // fraction of min sqrt(m / sum k)
  double fixed_time_step = 0;     // s; > 0 overrides the automatic step
  // Density scaling (quasi-static runs): every body's inertia is set so that its own critical
  // step equals `scaled_time_step` / time_step_safety. Static equilibria do not depend on mass;
  // dynamics (wave speeds, kinetic energy with scaled masses) do, so it is off by default.
  bool density_scaling = false;
  double scaled_time_step = 1.0;   // s, the step used when density scaling is on
  double skin = 0;                 // m; 0 = 0.2 x the mean radius at the first build
  double max_overlap_ratio = 1.0;  // guard: overlap / min radius beyond which the run stops
  ContactLaws laws{};              // by ContactClass (M, ITZ, A, W)
  // Bond law by ContactClass (default none: linear everywhere). Bonds exist only where
  // install_bonds (dem/bond_installation.hpp) put them; a pair's bond breaks for good.
  BondModels bonds{};
  // Threads of a cycle (> 1: force pass and integration in one job of a thread team per step,
  // dem/threaded_cycle.hpp, and the neighbour search shared out on rebuilds,
  // dem/neighbor_list.hpp). Every sum runs in the order of the one-thread cycle whatever the
  // count, so results are bitwise the same for any value.
  int threads = 1;
  // Runaway kinetic energy guard, checked every `energy_check_interval` steps: the run stops
  // when kinetic (integration inertia) + contact strain + damped energy exceeds
  // `runaway_energy_factor` x the energy put in (initial + boundary and applied work), i.e.
  // when the scheme creates energy. A stable run stays within O(dt^2) of a factor 1.
  double runaway_energy_factor = 2.0;
  long energy_check_interval = 100;
  // Energy bookkeeping in the integration (damping, applied and prescribed work). Off saves a
  // few % of a cycle (its terms were 17 % of the integration's time, which is about 15 % of a
  // cycle; docs/performance.md) and switches the runaway check off too (it needs the work put
  // in); the wall work is booked either way.
  bool energy_tracking = true;
  // Evaluate the unbonded and parallel-bonded disc pairs, and integrate the free discs, several
  // at a time: eight with AVX-512, four with AVX2, the widest set up to this one that the CPU
  // has (dem/lanes.hpp). The results are bitwise the same either way
  // (tests/test_dem_pair_lanes.cpp, tests/test_bitwise_guard.cpp); LaneIsa::None takes every
  // pair and body alone, as a CPU without AVX2 does.
  LaneIsa lanes = LaneIsa::Avx512;
};

class World {
 public:
  explicit World(WorldSettings settings = {});

  // A free disc; mass = density pi r^2 t. Returns the body index (== disc index while only
  // free discs are added, which the packing relies on).
  int add_disc(double x, double y, double r, double density,
               DiscMaterial material = DiscMaterial::Mortar);
  // A rigid clump: pebbles at world positions, body centroid/mass/inertia given (from the
  // aggregate polygon, SPEC 3.5). Inactive pebbles ride along but are never in contact.
  int add_clump(double cx, double cy, double mass, double inertia, const std::vector<double>& px,
                const std::vector<double>& py, const std::vector<double>& pr,
                const std::vector<std::uint8_t>& active);
  // A segment wall from a to b (m); the discs are on its left (dem/wall.hpp).
  int add_wall(double ax, double ay, double bx, double by) { return walls_.add(ax, ay, bx, by); }
  // An arc wall (dem/wall.hpp): centre (ox, oy) and radius in m, spanning mid_angle +-
  // half_angle (rad); the discs are inside.
  int add_arc_wall(double ox, double oy, double radius, double mid_angle, double half_angle) {
    return walls_.add_arc(ox, oy, radius, mid_angle, half_angle);
  }
  // Appends wall `index` of `from` (geometry, velocity, friction), returns its index here.
  int append_wall(const Walls& from, int index) {
    return walls_.append(from, static_cast<std::size_t>(index));
  }
  void add_container_walls(const Container& mould, int polygon_sides = 256);
  // Room for `bodies` bodies and `discs` discs in all, so a world built one body at a time holds
  // its arrays at their size (vector growth would leave up to half of them unused: 50 bytes per
  // disc on C30, docs/performance.md "Scale").
  void reserve(std::size_t bodies, std::size_t discs) {
    bodies_.reserve(bodies);
    discs_.reserve(discs);
  }

  // One cycle: (neighbour rebuild if needed), force pass, wall servos, energy bookkeeping,
  // integration, wall motion. Throws RunError on instability (non-finite state, overlap beyond
  // max_overlap_ratio x radius, runaway kinetic energy), std::invalid_argument on bad settings.
  void step();
  void cycle(long steps) {
    for (long s = 0; s < steps; ++s) step();
  }

  // Multiplies every disc radius by `factor` (radius expansion / radius servo of free-disc
  // packings); the mass and inertia of free discs follow (r^2, r^4). Clump pebble offsets and
  // clump inertias are left alone. Under density scaling the radii are stored by the next step
  // (its pass sees them changed) or by the first read before it (discs(), and every method
  // that needs them): the bits of changing them at once.
  void scale_radii(double factor);
  // Multiplies disc i's radius by factor[i] (one entry per disc; the packing's cell-by-cell
  // decompression, mesogen/decompression_cells.hpp), with the masses and inertias of free discs
  // as above. The automatic step (no density scaling, no fixed step) changes disc by disc, so the
  // next step rebuilds (a full neighbour build), which sets it; the packing cycles under density
  // scaling, where it does not.
  void scale_radii(const std::vector<double>& factor);
  // Multiplies disc i's radius by factors[i] after every step from the next one on (a copy is
  // kept; nullptr: no more), with the bits of scale_radii(factors) called after each step,
  // masses included. The step's integration stores the radii in the records it writes anyway,
  // where that call reads and writes every record once more (the packing's decompression by
  // cells on a wide mould, whose factors hold for ten cycles: docs/performance.md "Session 66");
  // the masses wait for the next read of the bodies. Under density scaling only (std::logic_error
  // otherwise, and at a step once the disc count or the settings no longer fit the factors).
  void scale_radii_after_each_step(const std::vector<double>* factors);
  // Undoes the change that scale_radii_after_each_step made after the last step, the radii and
  // masses back to their bits before it (the step keeps the radii it changed): for a caller that
  // learns from the step's results that it wanted no change, or another. std::logic_error if the
  // last step made none. The neighbour list's displacement bound stays as the change left it.
  void undo_radius_change_of_last_step();
  // Translates body b and its discs by (dx[b], dy[b]) (m; one entry per body, velocities left
  // alone), so the next force pass sees the new positions; the neighbour list's rebuild check
  // counts the move. For a relaxation that must change the drift the last step() made with a
  // velocity it changes afterwards (FIRE, mesogen/fire_relaxation.hpp); the cycle never calls it.
  void translate_bodies(const std::vector<double>& dx, const std::vector<double>& dy);
  // Sets a body's velocity (m/s, rad/s) and carries it to its discs at once, so the next force
  // pass already sees it (prescribed motions, initial conditions).
  void set_body_velocity(int body, double vx, double vy, double omega);
  // Takes a disc out of every contact (it rides along with its body) or back in; the neighbour
  // list is rebuilt at the next step.
  void set_contact_active(int disc, bool active) {
    discs_.active[disc] = active;
    rebuild_pending_ = true;
  }
  // Holds a body's velocity at what set_body_velocity gives it (forces no longer change it) or
  // frees it again. No pair changes either way; only the automatic time step, which is the
  // minimum over free bodies, does. Freeing a body asks for a rebuild (and so a new step) at the
  // next step: its stiffness may lower the critical step, and a step kept from before could
  // exceed it. Prescribing one asks for nothing: the body leaves the minimum, so the step kept
  // until the next rebuild is at most the new critical step (safe), and direct tension's
  // results, whose grips are prescribed after genesis, keep their bits.
  void set_prescribed(int body, bool prescribed) {
    catch_up_bodies();
    if (bodies_.prescribed[body] && !prescribed) rebuild_pending_ = true;
    bodies_.prescribed[body] = prescribed;
  }
  // External load on a body, added to every force pass (N per m of thickness).
  void set_applied_force(int body, double fx, double fy) {
    catch_up_bodies();  // the last step's resultants, with the load it applied
    bodies_.fx_applied[body] = fx;
    bodies_.fy_applied[body] = fy;
    bodies_.any_applied = true;
  }
  // A wall's velocity (m/s); it moves by velocity x dt after every step. A servo on the wall
  // overrides it at the next step.
  void set_wall_velocity(int wall, double vx, double vy) {
    walls_.vx[wall] = vx;
    walls_.vy[wall] = vy;
  }
  // Friction coefficient of the contacts of one wall (-, >= 0).
  void set_wall_friction(int wall, double friction) { walls_.friction[wall] = friction; }
  // Stress servo on a wall (dem/servo.hpp: target stress in Pa, compression positive; velocity
  // cap in m/s; relaxation in (0, 1]). Returns the servo's index. Throws std::invalid_argument
  // for a bad wall or bad values.
  int add_wall_servo(int wall, double target_stress, double max_velocity, double relaxation = 0.5) {
    return servos_.add(*this, wall, target_stress, max_velocity, relaxation);
  }
  // New target of servo `servo`, Pa (compression positive).
  void set_servo_target(int servo, double target_stress) {
    servos_.servos[static_cast<std::size_t>(servo)].target_stress = target_stress;
  }
  // Takes every servo off wall `wall` (which keeps its last velocity); servo indices after it
  // shift down.
  void remove_wall_servos(int wall);

  // Replaces the settings (std::invalid_argument if check_settings refuses them). The neighbour
  // list and the time step are rebuilt at the next step (they follow the contact laws, the
  // skin, the safety factor, the fixed or scaled step); switching density scaling off gives
  // the bodies back their true inverse masses and inertias.
  void set_settings(const WorldSettings& settings);
  // Density scaling on (every body's inertia set at the next rebuild for `scaled_time_step`,
  // s) or off; through set_settings, so the step follows at the next step.
  void set_density_scaling(bool on, double scaled_time_step);
  // A fixed time step, s (0: automatic again); through set_settings.
  void set_fixed_time_step(double time_step);
  // Neighbour-list skin, m (> 0; the extra gap under which a pair stays a candidate), in place
  // of settings().skin; the list is rebuilt with it at the next step.
  void set_neighbor_skin(double skin) {
    neighbors_.skin = skin;
    rebuild_pending_ = true;
  }
  // Empties the crack log (the cracks of a relaxation that are not the test's).
  void clear_cracks() { cracks_.clear(); }

  // Forces a neighbour-list rebuild (and time step update) at the next step.
  void invalidate_neighbors() { rebuild_pending_ = true; }
  // Rebuilds the neighbour list now if it is out of date (as step() would), so its candidate
  // pairs can be inspected or bonded before the next step.
  void refresh_neighbors();

  // Restarts the energy bookkeeping at the next energy check (step count a multiple of
  // settings.energy_check_interval): the reference absorbs what the accumulated work and
  // damping terms (which are kept) do not explain. scale_radii, set_body_velocity and adding
  // bodies call it.
  void reset_energy_reference() { energy_.reference_pending = true; }

  double time_step() const { return dt_; }
  // min sqrt(m_dyn / sum k) (and the rotational analogue) over free bodies at the last
  // rebuild, s: the step the safety factor multiplies.
  double critical_time_step() const { return dt_critical_; }
  double time() const { return time_; }
  long step_count() const { return steps_; }
  const ForcePassResult& last_force_pass() const { return last_pass_; }
  // Sum over free bodies of |F| of the last force pass (undamped resultants), N.
  double sum_body_force() const;
  // Energy dissipated by friction slip since the world was built (disc-disc and disc-wall
  // contacts, summed in pair order every step), J per m of thickness.
  double friction_dissipated() const { return friction_dissipated_; }
  // Strain energy released by bond failures since the world was built (the bond's springs at
  // the break; for a contact bond its tensile normal spring), J per m of thickness.
  double bond_energy_released() const { return bond_energy_released_; }

  // Read-only views of the state (structure of arrays; units in their headers).
  const WorldSettings& settings() const { return settings_; }
  // The bodies (a free disc's motion and forces caught up from its record and load sums first:
  // the step keeps them there, dem/integrator.hpp catch_up_free_bodies; and the physical masses
  // of the radius changes under density scaling, mass_scale_behind_). The first read after a
  // step or such a radius change writes, so not from several threads at once; and a reference
  // kept across either shows a free disc's motion and resultant, or the masses, of before it
  // until bodies() is called again.
  const Bodies& bodies() const {
    if (bodies_behind_ || !mass_scale_behind_.empty() || step_mass_scale_behind_ > 0)
      catch_up_bodies();
    return bodies_;
  }
  // Body b's motion and resultant as bodies() gives them, without catching up every body (for a
  // reader of a few bodies every step).
  BodyMotion body_motion(int b) const {
    return dem::body_motion(bodies_, discs_, static_cast<std::size_t>(b), bodies_behind_);
  }
  // The discs (a radius change waiting under density scaling applied first: scale_radii). A
  // reference kept across such a change shows the radii of before it until discs() is called
  // again or a step has run; so does one a thread reads while another calls this.
  const Discs& discs() const {
    if (radius_factor_behind_ != 1.0) apply_radius_factor_behind();
    return discs_;
  }
  const Walls& walls() const { return walls_; }
  const NeighborList& neighbors() const { return neighbors_; }  // the broad phase
  const ContactStore& contacts() const { return contacts_; }    // contacts and their state
  // The per-pair results of the last step (normal, overlap, fx, fy of every disc pair). Throws
  // std::logic_error when that step did not keep them (pair results on request, below).
  const ContactForces& pair_forces() const {
    if (!pair_results_current_) throw_pair_results_not_kept();
    return pair_forces_;
  }
  const ContactForces& wall_forces() const { return wall_forces_; }
  // The world's thread team when it runs several threads, else null: for a measure between
  // steps (a read-only pass over the world, dem/contact_energy.cpp) that shares its work out
  // with the bits of one thread. Not from inside a step.
  WorkerTeam* measure_team() const { return team(); }
  const CrackLog& cracks() const { return cracks_; }  // every bond failure, in order
  const WallServos& servos() const { return servos_; }
  const EnergyLedger& energy() const { return energy_; }

  // Per-pair results: every step writes them (32 bytes per pair), unless they are on request:
  // then only a step after request_pair_results() does (and a pair whose bond breaks), for a
  // loop that reads them at its records only (lab/lab_test.cpp). The forces on the discs, the
  // state and every total are the same bits either way.
  void set_pair_results_on_request(bool on);
  void request_pair_results() { pair_results_requested_ = true; }
  // The virial (last_force_pass().virial) is summed in every step that keeps the per-pair
  // results, and in every step when this is on (a packing's stress servo, which reads it each
  // cycle and the per-pair results every few cycles).
  void set_virial_every_step(bool on) { virial_every_step_ = on; }

 private:
  // Engine parts that edit the arrays in place and carry their own side effects.
  friend InstalledBonds install_bonds(World& world, const BondInstallation& options);
  friend InstalledJoints install_smooth_joints(World& world, const std::vector<JointSet>& sets,
                                               double gap_ratio);
  friend void update_wall_servos(World& world);
  friend void restart_energy_reference(World& world);
  // Tests only (defined in tests/world_test_access.hpp): states the methods above never make,
  // such as a stiffness raised without a time-step update, to test the instability diagnosis.
  friend struct WorldTestAccess;
  // Lists this object's arrays, private ones included (dem/memory_footprint.hpp).
  friend MemoryFootprint memory_footprint(const World& world);

  void rebuild();
  void update_time_step();
  // The radius change per disc that this step stores (its factor field unused: 1).
  RadiusChange radius_change_after_step();
  // Copies the free discs' motion and forces of the last step into bodies_ (const: bodies()
  // does it on a read; the values are the step's, only their place changes).
  void catch_up_bodies() const;
  // Applies mass_scale_behind_ and then step_mass_scale_behind_ to the free bodies' masses and
  // inertias, and empties both.
  void apply_mass_scale_behind() const;
  // Multiplies every radius by radius_factor_behind_ (shared out on the team) and sets it to 1.
  void apply_radius_factor_behind() const;
  // Both of the above: before a change that needs the radii and masses as the calls left them.
  void apply_radius_changes_behind() const;
  // The team of a world that runs several threads, else null (dem/worker_team.hpp share_out).
  WorkerTeam* team() const {
    return settings_.threads > 1 ? &team_.get(settings_.threads) : nullptr;
  }
  void account_wall_work();
  bool energy_check_due() const;  // check_energy runs at the end of this step
  [[noreturn]] void throw_pair_results_not_kept() const;
  void check_energy();
  [[noreturn]] void fail(const std::string& what, long disc) const;

  WorldSettings settings_;
  // Mutable for catch_up_bodies, which a read of bodies() runs; bodies_behind_: the free discs'
  // x, y, vx, vy, omega, fx, fy, moment in bodies_ are those before the last step.
  mutable Bodies bodies_;
  mutable bool bodies_behind_ = false;
  bool clumps_ = false;  // a clump was added (the radius changes skip clumps' masses)
  // The squared factors of the uniform radius changes under density scaling whose physical
  // masses and inertias bodies_ does not hold yet, in call order. No step reads them (the
  // integration uses the scaled inverse masses), and a packing changes every radius every cycle
  // (4.6 % of the samples of a one-thread C30 packing were that radius change, about half of it
  // the masses: docs/performance.md "Session 51"); a read of the bodies applies them, a block of
  // bodies at a time, as does a change that needs them (settings, radius factors per disc, new
  // bodies), and at most kMassScaleBehindAtMost wait.
  mutable std::vector<double> mass_scale_behind_;
  static constexpr std::size_t kMassScaleBehindAtMost = 1024;
  // The factor of the last uniform radius change under density scaling that the radii do not
  // hold yet (1: none). The next step's pass multiplies the radii by it and its integration
  // stores them, in the records it writes anyway; a read of the discs before that applies it.
  // Mutable for discs(), which does.
  mutable double radius_factor_behind_ = 1.0;
  // scale_radii_after_each_step: the factors (empty: none), the radii each step changed, whether
  // a factor grows a radius (the rebuild check then needs its pass after each step), and whether
  // the last step changed them.
  std::vector<double> step_radius_factor_, step_radius_before_;
  bool step_radius_growth_ = false, last_step_changed_radii_ = false;
  // Steps whose change by step_radius_factor_ the masses and inertias in bodies_ do not hold yet
  // (under density scaling no step reads them), newer than those of mass_scale_behind_: a change
  // of the uniform radius factor applies them first.
  mutable long step_mass_scale_behind_ = 0;
  mutable Discs discs_;
  Walls walls_;
  NeighborList neighbors_;  // reports the candidate pairs
  ContactStore contacts_;   // owns them and their state, merged by key at each rebuild
  ContactForces pair_forces_, wall_forces_;
  CrackLog cracks_;  // every bond failure, in the order they happened
  WallServos servos_;
  EnergyLedger energy_;
  double dt_ = 0, dt_critical_ = 0, time_ = 0;
  double friction_dissipated_ = 0, bond_energy_released_ = 0;  // J/m
  long steps_ = 0;
  bool rebuild_pending_ = true;
  bool pair_results_on_request_ = false, pair_results_requested_ = false;
  bool virial_every_step_ = false;
  bool pair_results_current_ = true;  // pair_forces_ holds the last step's results
  // m, bound on the largest disc displacement since the last neighbour build, summed from the
  // integration's speeds; infinite until the first build and after a radius growth. Lets the
  // rebuild check skip its pass over every disc while the bound alone rules a rebuild out.
  double moved_bound_ = std::numeric_limits<double>::infinity();
  ForcePassResult last_pass_;
  ThreadedCycle threaded_;         // plan and scratch of the multi-thread cycle
  mutable WorkerTeamHandle team_;  // threads > 1: the threaded cycle, rebuilds, radius changes
  TimeStepStiffness stiffness_;    // per body, the sums update_time_step sets the step from
  std::vector<double> member_dt_;  // s, per team member: scratch of update_time_step
};

// Per-pair results on request (World::set_pair_results_on_request) for a loop that reads them
// at its records only, back to every step when the loop ends, also by an exception.
class PairResultsOnRequestScope {
 public:
  explicit PairResultsOnRequestScope(World& world) : world_(world) {
    world_.set_pair_results_on_request(true);
  }
  ~PairResultsOnRequestScope() { world_.set_pair_results_on_request(false); }
  PairResultsOnRequestScope(const PairResultsOnRequestScope&) = delete;
  PairResultsOnRequestScope& operator=(const PairResultsOnRequestScope&) = delete;

 private:
  World& world_;
};

}  // namespace cdem::dem
