#pragma once
// Test-only write access to a World's arrays (the friend World declares): for states its
// methods never make, such as a contact stiffness raised without a time-step update (the
// instability diagnosis must still name it) or a clump body moved without its pebbles. Not for
// set-ups the methods can express.
#include <vector>

#include "dem/world.hpp"

namespace cdem::dem {

struct WorldTestAccess {
  // The settings, changed in place: no neighbour-list rebuild, no time-step update.
  static WorldSettings& stale_settings(World& w) { return w.settings_; }
  // The bodies, changed in place: the discs do not follow.
  static Bodies& bodies(World& w) { return w.bodies_; }
  // Puts the cuts of a multi-thread world's cycle (it must have stepped once with its team)
  // where a test wants them: thread t evaluates the pairs of discs [disc_cuts[t],
  // disc_cuts[t + 1]) (moved up to a body start) and integrates bodies [body_cuts[t],
  // body_cuts[t + 1]). They stay until the cycle's next rebalance.
  static void set_thread_cuts(World& w, const std::vector<std::size_t>& disc_cuts,
                              const std::vector<std::size_t>& body_cuts) {
    ThreadedCycle& c = w.threaded_;
    c.cuts_ = disc_cuts;
    c.body_cuts_ = body_cuts;
    c.snap_cuts_to_bodies(w.bodies_, w.discs_);
    c.plan_shared(w.discs_, w.contacts_);
  }
};

}  // namespace cdem::dem
