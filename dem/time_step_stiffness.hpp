#pragma once
// The stiffness sums the critical time step is set from (World::update_time_step): per body, the
// translational stiffness (N/m) and rotational stiffness (N m/rad) of its candidate contacts,
// each sum taken in contact order, shared out on the world's team with the bits of one thread.
//
// How it is shared out: member t takes the contacts whose first disc belongs to its range of
// bodies (the contacts are sorted by first disc, and the discs are numbered body by body, as the
// world adds them, so a range of bodies holds a range of contacts). A contact's second disc has the
// larger index, so a member's terms reach its own bodies and later ones, never earlier ones, and
// every body's terms in contact order are those of member 0, then member 1, and so on. A body that
// terms of an earlier member reach ("crossed") therefore takes member 0's terms as they come and
// the later members' after them: members 1 and up set theirs aside and they are added once all
// members are done, in member order. Every other body gets its terms from one member only, which
// adds them as it goes. On a packing the crossed bodies are about a row of discs per cut.
#include <atomic>
#include <cstdint>
#include <exception>
#include <vector>

#include "dem/bodies.hpp"
#include "dem/contact_store.hpp"
#include "dem/discs.hpp"
#include "dem/worker_team.hpp"

namespace cdem::dem {

// What one disc-disc contact adds onto its two discs' bodies.
struct ContactStiffnessTerm {
  double translational;  // N/m, onto both bodies
  double rotational_first,
      rotational_second;  // N m/rad, onto the first disc's body and the second's
};

class TimeStepStiffness {
 public:
  std::vector<double> translational, rotational;  // per body: N/m, N m/rad

  // Zeroes the sums and adds term(k) (a ContactStiffnessTerm) of every disc-disc contact k.
  // Allocates only when the bodies, the terms set aside or the team grow.
  template <class Term>
  void sum_pairs(const Bodies& bodies, const Discs& discs, const ContactStore& contacts,
                 Term&& term, WorkerTeam* team);

  // Capacities in bytes (dem/memory_footprint.hpp): of the per-body arrays (the sums, and the
  // marks when shared out), and of the rest (the cuts and the terms set aside).
  std::size_t body_bytes() const;
  std::size_t other_bytes() const;

 private:
  struct SetAside {
    std::int32_t body;
    double translational, rotational;
  };
  void cut(const Bodies& bodies, const Discs& discs, const ContactStore& contacts, int members);

  std::vector<std::int32_t> body_cut_;    // member t holds bodies [body_cut_[t], body_cut_[t + 1])
  std::vector<std::size_t> contact_cut_;  // and contacts [contact_cut_[t], contact_cut_[t + 1])
  std::vector<std::uint8_t> crossed_;     // per body: 1 if an earlier member's terms reach it
  std::vector<std::vector<SetAside>> set_aside_;  // per member, its terms onto crossed bodies
  std::vector<std::exception_ptr> failed_;        // per member, what its job threw
};

template <class Term>
void TimeStepStiffness::sum_pairs(const Bodies& bodies, const Discs& discs,
                                  const ContactStore& contacts, Term&& term, WorkerTeam* team) {
  const std::size_t count = contacts.keys.size();
  translational.assign(bodies.size(), 0.0);
  rotational.assign(bodies.size(), 0.0);
  const int members = share_out_members(team, count);
  cut(bodies, discs, contacts, members);
  failed_.assign(static_cast<std::size_t>(members), nullptr);
  share_out(team, count, [&](int t, int) {
    const auto first_body = body_cut_[static_cast<std::size_t>(t)];
    const auto end_body = body_cut_[static_cast<std::size_t>(t) + 1];
    const std::size_t begin = contact_cut_[static_cast<std::size_t>(t)];
    const std::size_t end = contact_cut_[static_cast<std::size_t>(t) + 1];
    if (members > 1) {
      // Bodies beyond this member's that its terms reach. Members may mark one body at once, all
      // with the same value.
      for (std::size_t k = begin; k < end; ++k) {
        const std::int32_t b = discs.body[contacts.second[k]];
        if (b >= end_body)
          std::atomic_ref<std::uint8_t>(crossed_[static_cast<std::size_t>(b)])
              .store(1, std::memory_order_relaxed);
      }
      team->barrier();
    }
    auto& aside = set_aside_[static_cast<std::size_t>(t)];
    const auto add = [&](std::int32_t b, double kt, double kr) {
      const auto i = static_cast<std::size_t>(b);
      if (t == 0 || (b >= first_body && b < end_body && !crossed_[i])) {
        translational[i] += kt;
        rotational[i] += kr;
      } else {
        aside.push_back({b, kt, kr});
      }
    };
    try {
      aside.clear();
      for (std::size_t k = begin; k < end; ++k) {
        const ContactStiffnessTerm s = term(k);
        // The order of one thread: both translational terms, then both rotational ones; each
        // body's sums see its own terms in contact order either way.
        add(discs.body[contacts.first[k]], s.translational, s.rotational_first);
        add(discs.body[contacts.second[k]], s.translational, s.rotational_second);
      }
    } catch (...) {
      failed_[static_cast<std::size_t>(t)] = std::current_exception();
    }
  });
  for (const auto& e : failed_)
    if (e) std::rethrow_exception(e);
  for (std::size_t t = 1; t < set_aside_.size() && t < static_cast<std::size_t>(members); ++t)
    for (const SetAside& s : set_aside_[t]) {
      translational[static_cast<std::size_t>(s.body)] += s.translational;
      rotational[static_cast<std::size_t>(s.body)] += s.rotational;
    }
}

}  // namespace cdem::dem
