#include "dem/time_step_stiffness.hpp"

#include <algorithm>

#include "dem/memory_footprint.hpp"

namespace cdem::dem {

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
