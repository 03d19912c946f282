#pragma once
// Rigid bodies, structure of arrays. A body is either a free disc (one disc, centred on the
// body) or a clump (several pebble discs at fixed offsets in the body frame). Forces and moments
// from the discs are summed about the body centroid before the body is integrated.
#include <cstdint>

#include "dem/staggered_array.hpp"

namespace cdem::dem {

struct Bodies {
  // Kinematics, world frame. For a free disc, these and the resultants below are a copy of its
  // disc's record and load sums, which the integration steps alone; World keeps the copy current
  // for its readers (dem/integrator.hpp catch_up_free_bodies).
  StaggeredArray<double> x, y;    // m, centroid
  StaggeredArray<double> theta;   // rad, orientation (only clumps need it to place pebbles)
  StaggeredArray<double> vx, vy;  // m/s, at the half step t - dt/2 (central difference)
  StaggeredArray<double> omega;   // rad/s, at the half step
  // Resultants of the last force pass (contacts + applied), before local damping.
  StaggeredArray<double> fx, fy;  // N (per 1 m thickness)
  StaggeredArray<double> moment;  // N m
  // Applied external load (e.g. gravity when asked for), added to every force pass.
  StaggeredArray<double> fx_applied, fy_applied;  // N
  // False while every applied load is the +0 a body starts with (no World::set_applied_force
  // yet): the integration then adds a constant +0 in place of reading the two arrays, the same
  // bits. At 10^6 discs the two read streams cost the free discs' integration measurably
  // (docs/performance.md "Session 45").
  bool any_applied = false;
  // Physical inertia (measurements, kinetic energy) and the inertia the integrator uses, which
  // differ only when density scaling is on.
  StaggeredArray<double> mass, inertia;                  // kg, kg m^2
  StaggeredArray<double> inv_mass_dyn, inv_inertia_dyn;  // 1/kg, 1/(kg m^2)
  // Discs owned by the body: [first_disc, first_disc + disc_count).
  StaggeredArray<std::int32_t> first_disc, disc_count;
  StaggeredArray<std::uint8_t> is_clump;  // 1: pebbles sit at offsets and follow theta
  // 1: the velocity is prescribed (forces do not change it; zero holds the body in place).
  StaggeredArray<std::uint8_t> prescribed;

  std::size_t size() const { return x.size(); }
  // Room for n bodies in every array, so a world built body by body holds no growth slack.
  void reserve(std::size_t n) {
    for (auto* v : {&x, &y, &theta, &vx, &vy, &omega, &fx, &fy, &moment, &fx_applied, &fy_applied,
                    &mass, &inertia, &inv_mass_dyn, &inv_inertia_dyn})
      v->reserve(n);
    for (auto* v : {&first_disc, &disc_count}) v->reserve(n);
    for (auto* v : {&is_clump, &prescribed}) v->reserve(n);
  }
};

}  // namespace cdem::dem
