#include "dem/crack_log.hpp"

#include <algorithm>
#include <bit>
#include <cmath>

namespace cdem::dem {

long CrackLog::count(BondFailure mode, ContactClass cls) const {
  long n = 0;
  for (const Crack& c : cracks) n += c.mode == mode && c.contact_class == cls;
  return n;
}

void CrackLog::record(const ContactForces& pair, const ContactStore& list, const Discs& discs,
                      const BondModels& bonds, double time) {
  for (const std::int32_t k : pair.broken) {
    const std::int32_t i = list.first[k], j = list.second[k];
    const double dx = discs.x[j] - discs.x[i], dy = discs.y[j] - discs.y[i];
    const double dist = std::sqrt(dx * dx + dy * dy);
    // Contact point at arm_i = R_i - overlap / 2 from the centre of i along the normal.
    const double arm = discs.r[i] - 0.5 * pair.overlap[k];
    const double s = dist > 0 ? arm / dist : 0.0;
    const std::uint8_t cls = list.contact_class[k];
    Crack c;
    c.time = time;
    c.x = discs.x[i] + s * dx;
    c.y = discs.y[i] + s * dy;
    c.mode = static_cast<BondFailure>(pair.failure[k]);
    c.contact_class = static_cast<ContactClass>(cls);
    // A smooth joint keeps its kind after the break; other bonds are the class's.
    const bool smooth = list.state.bond[k] == static_cast<std::uint8_t>(BondKind::SmoothJoint);
    c.bond = smooth ? BondKind::SmoothJoint : bonds[cls].kind;
    c.first = i;
    c.second = j;
    c.energy = pair.bond_energy_released[k];
    const double nx = dist > 0 ? dx / dist : 0.0, ny = dist > 0 ? dy / dist : 0.0;
    c.nx = nx;
    c.ny = ny;
    const double r_min = std::min(discs.r[i], discs.r[j]);
    const BondModel& model = bonds[cls];
    c.half_width = model.kind == BondKind::Parallel ? model.parallel.radius_multiplier * r_min
                   : model.kind == BondKind::FlatJoint
                       ? model.flat_joint.radius_multiplier * r_min / model.flat_joint.elements
                       : r_min;
    const std::uint32_t failed = pair.failed_elements[k];
    if (!failed) {
      cracks.push_back(c);
      continue;
    }
    c.energy /= std::popcount(failed);
    const Crack contact = c;
    for (int e = 0; e < kMaxFlatJointElements; ++e) {
      if (!(failed & (1u << e))) continue;
      // Element centroid: along t = (-ny, nx) from the contact point.
      const double along =
          flat_joint_element_centroid(bonds[cls].flat_joint, discs.r[i], discs.r[j], e);
      c = contact;
      c.x -= along * ny;
      c.y += along * nx;
      c.mode = pair.failed_shear[k] & (1u << e) ? BondFailure::Shear : BondFailure::Tension;
      c.element = static_cast<std::int8_t>(e);
      cracks.push_back(c);
    }
  }
}

CrackSegment crack_segment(const Crack& crack) {
  const double tx = -crack.ny * crack.half_width, ty = crack.nx * crack.half_width;
  return {crack.x - tx, crack.y - ty, crack.x + tx, crack.y + ty};
}

}  // namespace cdem::dem
