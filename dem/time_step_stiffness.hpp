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
#include <algorithm>
#include <array>
#include <atomic>
#include <cstdint>
#include <exception>
#include <vector>

#include "dem/bodies.hpp"
#include "dem/contact_model.hpp"
#include "dem/contact_store.hpp"
#include "dem/discs.hpp"
#include "dem/lanes.hpp"
#include "dem/worker_team.hpp"

namespace cdem::dem {

// What one disc-disc contact adds onto its two discs' bodies (T = double; lanes for several).
template <class T>
struct ContactStiffnessTermOf {
  T translational;  // N/m, onto both bodies
  T rotational_first,
      rotational_second;  // N m/rad, onto the first disc's body and the second's
};
using ContactStiffnessTerm = ContactStiffnessTermOf<double>;

// The lever (m) at which a contact's shear stiffness turns disc d's body: the disc's distance from
// the body's centre plus its radius (its radius for a free disc). T = double, or lanes.
template <class T>
T body_arm(T offset_x, T offset_y, T r) {
  return sqrt_of(offset_x * offset_x + offset_y * offset_y) + r;
}
inline double body_arm(const Discs& discs, std::int32_t d) {
  return body_arm(discs.offset_x[d], discs.offset_y[d], discs.r[d]);
}

// The terms of the disc-disc contacts for the time step: max(kn, ks) and ks arm^2 + the bond's
// bending stiffness (dem/contact_model.hpp pair_stiffness) with each class's laws and bonds.
// Contacts without a flat joint or a smooth joint go in lanes (up to `lanes`; the bits of one at
// a time: tests/test_dem_time_step_stiffness.cpp).
class ContactStiffnessTerms {
 public:
  ContactStiffnessTerms(const Discs& discs, const ContactStore& contacts,
                        const std::array<LinearContact, kContactClassCount>& laws,
                        const BondModels& bonds, LaneIsa lanes);
  // out[q] = the term of contact k + q, q < n.
  void operator()(std::size_t k, std::size_t n, ContactStiffnessTerm* out) const;
  // The term of contact k alone.
  ContactStiffnessTerm one(std::size_t k) const;

 private:
  // The whole groups of eight (AVX-512) or four (AVX2) contacts of [k, k + n), each in lanes if
  // none of its contacts carries a flat or smooth joint, else one at a time; returns how many
  // contacts from k they wrote (the rest is left to one at a time).
  CDEM_LANES8_TARGET std::size_t groups_in_lanes8(std::size_t k, std::size_t n,
                                                  ContactStiffnessTerm* out) const;
  CDEM_LANES4_TARGET std::size_t groups_in_lanes4(std::size_t k, std::size_t n,
                                                  ContactStiffnessTerm* out) const;
  template <class L>
  std::size_t groups_in_lanes(std::size_t k, std::size_t n, ContactStiffnessTerm* out) const;
  template <class L>
  void lane_terms(std::size_t k, ContactStiffnessTerm* out) const;

  const Discs& discs_;
  const ContactStore& contacts_;
  const std::array<LinearContact, kContactClassCount>& laws_;
  const BondModels& bonds_;
  LaneIsa lanes_;
  ClassLaneConstants by_class_;
};

class TimeStepStiffness {
 public:
  std::vector<double> translational, rotational;  // per body: N/m, N m/rad

  // Zeroes the sums and adds the term of every disc-disc contact k, which terms(k, n, out)
  // writes to out[q] for the n contacts from k (ContactStiffnessTerms). Allocates only when the
  // bodies, the terms set aside or the team grow.
  template <class Terms>
  void sum_pairs(const Bodies& bodies, const Discs& discs, const ContactStore& contacts,
                 Terms&& terms, WorkerTeam* team);

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

template <class Terms>
void TimeStepStiffness::sum_pairs(const Bodies& bodies, const Discs& discs,
                                  const ContactStore& contacts, Terms&& terms, WorkerTeam* team) {
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
      // The terms a block at a time (in lanes), then added in contact order.
      constexpr std::size_t kBlock = 64;
      ContactStiffnessTerm block[kBlock];
      for (std::size_t start = begin; start < end; start += kBlock) {
        const std::size_t n = std::min(kBlock, end - start);
        terms(start, n, block);
        for (std::size_t q = 0; q < n; ++q) {
          const std::size_t k = start + q;
          // The order of one thread: both translational terms, then both rotational ones; each
          // body's sums see its own terms in contact order either way.
          add(discs.body[contacts.first[k]], block[q].translational, block[q].rotational_first);
          add(discs.body[contacts.second[k]], block[q].translational, block[q].rotational_second);
        }
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
