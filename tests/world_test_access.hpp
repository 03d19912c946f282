#pragma once
// Test-only write access to a World's arrays (the friend World declares): for states its
// methods never make, such as a contact stiffness raised without a time-step update (the
// instability diagnosis must still name it) or a clump body moved without its pebbles. Not for
// set-ups the methods can express.
#include <cstdint>
#include <vector>

#include "dem/world.hpp"

namespace cdem::dem {

struct WorldTestAccess {
  // The settings, changed in place: no neighbour-list rebuild, no time-step update.
  static WorldSettings& stale_settings(World& w) { return w.settings_; }
  // The bodies, changed in place: the discs do not follow. A clump's only: a step reads a free
  // disc's motion from its disc (dem/integrator.hpp catch_up_free_bodies).
  static Bodies& bodies(World& w) {
    w.catch_up_bodies();
    return w.bodies_;
  }
  // Whether the last step's second chunk had its virials summed during its owner's integration
  // (ThreadedCycle::Chunk::virial_chained).
  static bool virial_chained_during_integration(const World& w) {
    const ThreadedCycle& c = w.threaded_;
    return c.chunks_.size() > 1 && c.chunks_[1].virial_chained;
  }
  // Gives the bodies of a multi-thread world's cycle (it must have stepped once with its team)
  // the owners a test wants: thread owners[b] evaluates the pairs of body b's discs and
  // integrates it. They stay until the cycle's next rebalance or neighbour-list rebuild.
  static void set_thread_owners(World& w, const std::vector<std::int32_t>& owners) {
    ThreadedCycle& c = w.threaded_;
    c.owner_ = owners;
    c.plan_shared(w.bodies_, w.discs_, w.contacts_);
  }
};

}  // namespace cdem::dem
