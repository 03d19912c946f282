#pragma once
// Strain of a region of a specimen from the displacements of its discs: the best-fit uniform
// displacement gradient, u(X) = u0 + G (X - Xc), fitted by least squares over the discs whose
// reference centre lies in the region (SPEC 6, lateral strain of a UCS test). The normal
// matrix depends on the reference positions only, so it is factorised once; a measurement is
// one pass over the discs of the region and allocates nothing.
#include <cstdint>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Dense>

#include "dem/measure.hpp"
#include "dem/world.hpp"

namespace cdem::dem {

class StrainGauge {
 public:
  // Takes the current disc positions as the reference. Throws std::invalid_argument when the
  // region holds fewer than 3 discs or the discs are collinear (no gradient can be fitted).
  StrainGauge(const World& world, const Box& region);

  // Displacement gradient G = du/dX (dimensionless); G(0,0) is the horizontal extension,
  // G(1,1) the vertical one (tension positive, small-strain).
  Eigen::Matrix2d gradient(const World& world) const;
  std::size_t disc_count() const { return discs_.size(); }

 private:
  std::vector<std::int32_t> discs_;
  std::vector<double> x0_, y0_;  // m, reference centres relative to the region's centroid
  Eigen::Matrix3d inverse_normal_;
};

}  // namespace cdem::dem
