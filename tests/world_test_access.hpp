#pragma once
// Test-only write access to a World's arrays (the friend World declares): for states its
// methods never make, such as a contact stiffness raised without a time-step update (the
// instability diagnosis must still name it) or a clump body moved without its pebbles. Not for
// set-ups the methods can express.
#include "dem/world.hpp"

namespace cdem::dem {

struct WorldTestAccess {
  // The settings, changed in place: no neighbour-list rebuild, no time-step update.
  static WorldSettings& stale_settings(World& w) { return w.settings_; }
  // The bodies, changed in place: the discs do not follow.
  static Bodies& bodies(World& w) { return w.bodies_; }
};

}  // namespace cdem::dem
