#pragma once
// Discs, structure of arrays laid out for the contact loop: everything a contact needs sits in
// contiguous per-disc arrays (position, radius, velocity of the owning body carried to the disc),
// so the pair kernel never looks at the bodies.
#include <cstdint>

#include "dem/staggered_array.hpp"

namespace cdem::dem {

// The material a disc belongs to; a pair's contact class follows from the two materials.
enum class DiscMaterial : std::uint8_t { Mortar = 0, Aggregate = 1 };

struct Discs {
  StaggeredArray<double> x, y;                // m, centre, world frame
  StaggeredArray<double> r;                   // m, radius
  StaggeredArray<double> vx, vy, omega;       // m/s, rad/s: velocity of the disc centre and spin
  StaggeredArray<double> offset_x, offset_y;  // m, centre in the body frame (0 for free discs)
  StaggeredArray<std::int32_t> body;          // owning body
  StaggeredArray<std::uint8_t> active;        // 0: never in contact detection (buried pebble)
  StaggeredArray<DiscMaterial> material;
  // Force and moment (about the disc centre) from the contacts of the last force pass.
  StaggeredArray<double> fx, fy, moment;  // N, N m

  std::size_t size() const { return x.size(); }
  // Room for n discs in every array, so a world built disc by disc holds no growth slack.
  void reserve(std::size_t n) {
    for (auto* v : {&x, &y, &r, &vx, &vy, &omega, &offset_x, &offset_y, &fx, &fy, &moment})
      v->reserve(n);
    body.reserve(n);
    active.reserve(n);
    material.reserve(n);
  }
};

}  // namespace cdem::dem
