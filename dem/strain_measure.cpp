#include "dem/strain_measure.hpp"

#include <stdexcept>

namespace cdem::dem {

StrainGauge::StrainGauge(const World& world, const Box& region) {
  const Discs& d = world.discs();
  double cx = 0, cy = 0;
  for (std::size_t i = 0; i < d.size(); ++i) {
    if (!region.contains(d.x[i], d.y[i])) continue;
    discs_.push_back(static_cast<std::int32_t>(i));
    cx += d.x[i];
    cy += d.y[i];
  }
  if (discs_.size() < 3)
    throw std::invalid_argument("strain gauge: fewer than 3 discs in the measurement region");
  cx /= static_cast<double>(discs_.size());
  cy /= static_cast<double>(discs_.size());
  Eigen::Matrix3d normal = Eigen::Matrix3d::Zero();
  for (const std::int32_t i : discs_) {
    const Eigen::Vector3d row(1.0, d.x[i] - cx, d.y[i] - cy);
    x0_.push_back(row(1));
    y0_.push_back(row(2));
    normal += row * row.transpose();
  }
  Eigen::FullPivLU<Eigen::Matrix3d> lu(normal);
  if (!lu.isInvertible())
    throw std::invalid_argument("strain gauge: discs of the region are collinear");
  inverse_normal_ = lu.inverse();
}

Eigen::Matrix2d StrainGauge::gradient(const World& world) const {
  const Discs& d = world.discs();
  Eigen::Vector3d bx = Eigen::Vector3d::Zero(), by = Eigen::Vector3d::Zero();
  // Displacements relative to the reference: u = x - X. The region's centroid cancels in the
  // gradient (it only shifts u0), so current positions can be used relative to anything fixed.
  for (std::size_t k = 0; k < discs_.size(); ++k) {
    const std::int32_t i = discs_[k];
    const Eigen::Vector3d row(1.0, x0_[k], y0_[k]);
    const double ux = d.x[i] - x0_[k], uy = d.y[i] - y0_[k];
    bx += ux * row;
    by += uy * row;
  }
  const Eigen::Vector3d ax = inverse_normal_ * bx, ay = inverse_normal_ * by;
  Eigen::Matrix2d g;
  g << ax(1), ax(2), ay(1), ay(2);
  return g;
}

}  // namespace cdem::dem
