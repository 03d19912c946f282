#pragma once
// The DEM world: bodies, their discs, walls, the neighbour list and the contact laws, advanced
// one cycle at a time. Data are public structure-of-arrays (read them freely; change positions
// or radii only through the functions below so the neighbour list stays valid).
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
#include "dem/linear_contact.hpp"
#include "dem/neighbor_list.hpp"
#include "dem/servo.hpp"
#include "dem/threaded_cycle.hpp"
#include "dem/wall.hpp"

namespace cdem::dem {

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
  // dem/threaded_cycle.hpp). Every sum runs in the order of the one-thread cycle whatever the
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
  int add_wall(double ax, double ay, double bx, double by) { return walls.add(ax, ay, bx, by); }
  void add_container_walls(const Container& mould, int polygon_sides = 256);

  // One cycle: (neighbour rebuild if needed), force pass, wall servos, energy bookkeeping,
  // integration, wall motion. Throws RunError on instability (non-finite state, overlap beyond
  // max_overlap_ratio x radius, runaway kinetic energy), std::invalid_argument on bad settings.
  void step();
  void cycle(long steps) {
    for (long s = 0; s < steps; ++s) step();
  }

  // Multiplies every disc radius by `factor` (radius expansion / radius servo of free-disc
  // packings); the mass and inertia of free discs follow (r^2, r^4). Clump pebble offsets and
  // clump inertias are left alone.
  void scale_radii(double factor);
  // Sets a body's velocity (m/s, rad/s) and carries it to its discs at once, so the next force
  // pass already sees it (prescribed motions, initial conditions).
  void set_body_velocity(int body, double vx, double vy, double omega);
  // Forces a neighbour-list rebuild (and time step update) at the next step.
  void invalidate_neighbors() { rebuild_pending_ = true; }
  // Rebuilds the neighbour list now if it is out of date (as step() would), so its candidate
  // pairs can be inspected or bonded before the next step.
  void refresh_neighbors();

  // Restarts the energy bookkeeping at the next energy check (step count a multiple of
  // settings.energy_check_interval): the reference absorbs what the accumulated work and
  // damping terms (which are kept) do not explain. scale_radii, set_body_velocity and adding
  // bodies call it.
  void reset_energy_reference() { energy.reference_pending = true; }

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

  WorldSettings settings;
  Bodies bodies;
  Discs discs;
  Walls walls;
  NeighborList neighbors;
  ContactForces pair_forces, wall_forces;
  CrackLog cracks;  // every bond failure, in the order they happened
  WallServos servos;
  EnergyLedger energy;

 private:
  void rebuild();
  void update_time_step();
  void account_wall_work();
  void check_energy();
  [[noreturn]] void fail(const std::string& what, long disc) const;

  double dt_ = 0, dt_critical_ = 0, time_ = 0;
  double friction_dissipated_ = 0, bond_energy_released_ = 0;  // J/m
  long steps_ = 0;
  bool rebuild_pending_ = true;
  // m, bound on the largest disc displacement since the last neighbour build, summed from the
  // integration's speeds; infinite until the first build and after a radius change. Lets the
  // rebuild check skip its pass over every disc while the bound alone rules a rebuild out.
  double moved_bound_ = std::numeric_limits<double>::infinity();
  ForcePassResult last_pass_;
  ThreadedCycle threaded_;                         // plan and scratch of the multi-thread cycle
  std::vector<double> stiffness_, rot_stiffness_;  // per body, scratch of update_time_step
};

}  // namespace cdem::dem
