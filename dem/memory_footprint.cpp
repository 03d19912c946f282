#include "dem/memory_footprint.hpp"

#include "dem/world.hpp"

namespace cdem::dem {

namespace {

std::size_t state_bytes(const ContactStates& s) {
  return capacity_bytes(s.shear_force, s.bond, s.bond_normal, s.bond_shear, s.bond_moment,
                        s.bond_gap, s.joint);
}

std::size_t force_bytes(const ContactForces& f) {
  return capacity_bytes(f.normal, f.overlap, f.fx, f.fy, f.moment, f.cx, f.cy, f.branch, f.failure,
                        f.bond_energy_released, f.failed_elements, f.failed_shear, f.broken);
}

}  // namespace

MemoryFootprint memory_footprint(const World& world) {
  MemoryFootprint m;
  const Bodies& b = world.bodies_;
  m.bodies =
      capacity_bytes(b.x, b.y, b.theta, b.vx, b.vy, b.omega, b.fx, b.fy, b.moment, b.fx_applied,
                     b.fy_applied, b.mass, b.inertia, b.inv_mass_dyn, b.inv_inertia_dyn,
                     b.first_disc, b.disc_count, b.is_clump, b.prescribed) +
      world.stiffness_.body_bytes();
  const Discs& d = world.discs_;
  m.discs = capacity_bytes(d.state, d.body, d.active, d.material, d.load);
  const ContactStore& c = world.contacts_;
  m.pairs = capacity_bytes(c.keys, c.first, c.second, c.contact_class) + state_bytes(c.state) +
            force_bytes(world.pair_forces_);
  m.wall_pairs = capacity_bytes(c.wall_keys, c.wall_disc, c.wall_index) +
                 state_bytes(c.wall_state) + force_bytes(world.wall_forces_);
  const FlatJointStates& fj = c.flat_joints;
  const SmoothJointStates& sj = c.smooth_joints;
  m.joints = capacity_bytes(fj.gap0, fj.theta, fj.bonded, fj.first_element, fj.element_shear,
                            sj.sets, sj.set, sj.nx, sj.ny, sj.area, sj.gap, sj.fs, sj.bonded);
  m.merge_scratch =
      capacity_bytes(c.merged_keys_, c.member_offsets_, c.merge_runs_, c.merge_run_old_) +
      state_bytes(c.merged_state_);
  m.wall_pairs += capacity_bytes(c.merged_wall_keys_) + state_bytes(c.merged_wall_state_);
  const NeighborList& n = world.neighbors_;
  m.neighbor_list = capacity_bytes(n.ref_x_, n.ref_y_, n.ref_r_, n.wall_ax0_, n.wall_ay0_,
                                   n.cell_start_, n.cell_discs_, n.disc_cell_, n.pair_parts_,
                                   n.wall_keys_, n.scratch_, n.reach_, n.extent_);
  for (const auto& keys : n.pair_parts_) m.neighbor_list += capacity_bytes(keys);
  const ThreadedCycle& t = world.threaded_;
  m.thread_plan = capacity_bytes(
      t.first_start_, t.wall_start_, t.order_, t.work_, t.cuts_, t.owner_, t.chunks_, t.chunk_done_,
      t.links_, t.shared_, t.shared_discs_, t.special_pairs_, t.virial_, t.shared_terms_,
      t.shared_term_start_, t.shared_term_mid_, t.rate_, t.clumps_, t.target_cuts_, t.next_term_,
      t.body_damped_, t.body_applied_, t.body_prescribed_, t.wall_slip_, t.lanes_);
  // Its room, written or not (the resident size counts only the written pages).
  m.thread_plan += t.slip_terms_.capacity() * sizeof(double);
  for (const auto& lane : t.lanes_) m.thread_plan += capacity_bytes(lane.broken);
  const Walls& w = world.walls_;
  m.other = capacity_bytes(w.ax, w.ay, w.bx, w.by, w.arc, w.vx, w.vy, w.friction, w.fx, w.fy, w.sxx,
                           w.sxy, w.syx, w.syy, world.servos_.servos, world.cracks_.cracks,
                           world.energy_.last_dx, world.energy_.last_dy) +
            world.stiffness_.other_bytes() +
            capacity_bytes(world.member_dt_, world.mass_scale_behind_, world.step_radius_factor_,
                           world.step_radius_before_);
  return m;
}

}  // namespace cdem::dem
