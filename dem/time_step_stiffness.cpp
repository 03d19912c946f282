#include "dem/time_step_stiffness.hpp"

#include <algorithm>

#include "dem/memory_footprint.hpp"

namespace cdem::dem {

namespace {

// A contact of stiffness c whose discs turn their bodies at levers arm_first and arm_second (m):
// the translational term takes the larger of its normal and shear stiffness (N/m), each
// rotational one ks arm^2 plus the bond's bending stiffness (N m/rad).
template <class T>
ContactStiffnessTermOf<T> term_of(const ContactStiffnessOf<T>& c, T arm_first, T arm_second) {
  return {max_of(c.normal, c.shear), c.shear * arm_first * arm_first + c.rotation,
          c.shear * arm_second * arm_second + c.rotation};
}

}  // namespace

// The terms of the kLanes<L> contacts from k, none of which carries a flat or a smooth joint, to
// out[0 .. kLanes<L> - 1]: the operations of one() in the same order, each correctly rounded in
// every lane (dem/lanes.hpp), so each lane has its bits. Lane code: called only from the
// groups_in_lanes8 / 4 below, which inline it.
template <class L>
void ContactStiffnessTerms::lane_terms(std::size_t k, ContactStiffnessTerm* out) const {
  constexpr std::size_t n = kLanes<L>;
  L a[kRecordFields], b[kRecordFields];
  load_pair_records(discs_, contacts_, k, a, b);
  const L r1 = a[DiscState::kR], r2 = b[DiscState::kR];
  const std::uint8_t* cls = contacts_.contact_class.data() + k;
  const ParallelBondLanes<L> p = by_class_.parallel_bond<L>(cls);
  const ContactStiffnessOf<L> s =
      linear_pair_stiffness(lookup<L>(by_class_.emod, cls), lookup<L>(by_class_.kappa, cls), p,
                            lanes_equal<L>(contacts_.state.bond.data() + k,
                                           static_cast<std::uint8_t>(BondKind::Parallel)),
                            r1, r2);
  const ContactStiffnessTermOf<L> t =
      term_of(s, body_arm(a[DiscState::kOffsetX], a[DiscState::kOffsetY], r1),
              body_arm(b[DiscState::kOffsetX], b[DiscState::kOffsetY], r2));
  for (std::size_t l = 0; l < n; ++l)
    out[l] = {t.translational[l], t.rotational_first[l], t.rotational_second[l]};
}

template <class L>
std::size_t ContactStiffnessTerms::groups_in_lanes(std::size_t k, std::size_t n,
                                                   ContactStiffnessTerm* out) const {
  constexpr std::size_t width = kLanes<L>;
  std::size_t q = 0;
  for (; q + width <= n; q += width) {
    if (no_joint_in_lanes<L>(contacts_.state.bond.data() + k + q))
      lane_terms<L>(k + q, out + q);
    else
      for (std::size_t l = 0; l < width; ++l) out[q + l] = one(k + q + l);
  }
  return q;
}

CDEM_LANES8_TARGET std::size_t ContactStiffnessTerms::groups_in_lanes8(
    std::size_t k, std::size_t n, ContactStiffnessTerm* out) const {
  return groups_in_lanes<Lanes8>(k, n, out);
}
CDEM_LANES4_TARGET std::size_t ContactStiffnessTerms::groups_in_lanes4(
    std::size_t k, std::size_t n, ContactStiffnessTerm* out) const {
  return groups_in_lanes<Lanes4>(k, n, out);
}

ContactStiffnessTerms::ContactStiffnessTerms(
    const Discs& discs, const ContactStore& contacts,
    const std::array<LinearContact, kContactClassCount>& laws, const BondModels& bonds,
    LaneIsa lanes)
    : discs_(discs),
      contacts_(contacts),
      laws_(laws),
      bonds_(bonds),
      lanes_(usable_lanes(lanes)),
      by_class_(laws, bonds) {}

ContactStiffnessTerm ContactStiffnessTerms::one(std::size_t k) const {
  const std::int32_t i = contacts_.first[k], j = contacts_.second[k];
  const std::uint8_t cls = contacts_.contact_class[k];
  const auto kind = static_cast<BondKind>(contacts_.state.bond[k]);
  const ContactStiffness c =
      kind == BondKind::SmoothJoint
          ? smooth_joint_stiffness(contacts_.smooth_joints, contacts_.state.joint[k])
          : pair_stiffness(laws_[cls], bonds_[cls], kind, discs_.r[i], discs_.r[j]);
  return term_of(c, body_arm(discs_, i), body_arm(discs_, j));
}

void ContactStiffnessTerms::operator()(std::size_t k, std::size_t n,
                                       ContactStiffnessTerm* out) const {
  std::size_t q = 0;
  if (lanes_ == LaneIsa::Avx512)
    q = groups_in_lanes8(k, n, out);
  else if (lanes_ == LaneIsa::Avx2)
    q = groups_in_lanes4(k, n, out);
  for (; q < n; ++q) out[q] = one(k + q);
}

void TimeStepStiffness::cut(const Bodies& bodies, const Discs& discs, const ContactStore& contacts,
                            int members) {
  const std::size_t count = contacts.keys.size(), m = static_cast<std::size_t>(members);
  const auto bodies_end = static_cast<std::int32_t>(bodies.size());
  body_cut_.assign(m + 1, bodies_end);
  contact_cut_.assign(m + 1, count);
  body_cut_[0] = 0;
  contact_cut_[0] = 0;
  for (std::size_t t = 1; t < m; ++t) {
    // The body of the contact where an equal share would start, and all of its contacts.
    const std::size_t k = member_range(count, static_cast<int>(t), members).begin;
    const std::int32_t b =
        std::max(k < count ? discs.body[contacts.first[k]] : bodies_end, body_cut_[t - 1]);
    body_cut_[t] = b;
    contact_cut_[t] = b < bodies_end
                          ? static_cast<std::size_t>(std::lower_bound(contacts.first.begin(),
                                                                      contacts.first.end(),
                                                                      bodies.first_disc[b]) -
                                                     contacts.first.begin())
                          : count;
  }
  if (m > 1) crossed_.assign(bodies.size(), 0);
  if (set_aside_.size() < m) set_aside_.resize(m);
}

std::size_t TimeStepStiffness::body_bytes() const {
  return capacity_bytes(translational, rotational, crossed_);
}

std::size_t TimeStepStiffness::other_bytes() const {
  std::size_t bytes = capacity_bytes(body_cut_, contact_cut_, set_aside_, failed_);
  for (const auto& aside : set_aside_) bytes += capacity_bytes(aside);
  return bytes;
}

}  // namespace cdem::dem
