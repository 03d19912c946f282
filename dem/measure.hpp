#pragma once
// Measurements on a world (read-only): stresses from contacts and from walls, overlap and
// contact statistics, force balance, energies, porosity. Stresses are 2D (force per length per
// 1 m of thickness = Pa) and reported compression positive.
#include <Eigen/Core>

#include "dem/world.hpp"

namespace cdem::dem {

// An axis-aligned measurement box (m).
struct Box {
  double xmin, ymin, xmax, ymax;
  double area() const { return (xmax - xmin) * (ymax - ymin); }
  // (x, y) lies in the box widened by `margin` (m) on every side.
  bool contains(double x, double y, double margin = 0) const {
    return x >= xmin - margin && x <= xmax + margin && y >= ymin - margin && y <= ymax + margin;
  }
};

// Average stress from the contacts (Love-Weber): the tension-positive tensor is
// -(1/A) sum_c l_c (x) f_c with l the branch vector from the first to the second body and f the
// force on the second; this returns its negative (compression positive). All touching contacts
// (disc-disc and disc-wall, branch to the contact point) over `area`.
Eigen::Matrix2d contact_stress(const World& world, double area);
// The same over the contacts whose contact point lies in `region`, divided by its area.
Eigen::Matrix2d contact_stress(const World& world, const Box& region);
// Boundary stress of the material enclosed by the walls: (1/A) sum over wall contacts of
// (x_c - origin) (x) f_on_wall, compression positive (Cauchy's boundary average).
Eigen::Matrix2d wall_stress(const World& world, double area, const Eigen::Vector2d& origin);
// Mean isotropic stress (trace / 2) of a 2D tensor.
inline double mean_stress(const Eigen::Matrix2d& s) {
  return 0.5 * s.trace();
}
// Normal stress on one wall: force pushing the wall away from the discs / wall length (Pa).
double wall_normal_stress(const World& world, int wall);

struct OverlapStatistics {
  long contacts = 0;        // touching disc-disc contacts
  double mean_overlap = 0;  // m
  double mean_ratio = 0;    // mean of overlap / min(R1, R2)
  double max_ratio = 0;
};
OverlapStatistics overlap_statistics(const World& world);

// Mean number of touching disc-disc contacts per active disc, 2 Nc / N.
double coordination_number(const World& world);
// Active discs with fewer than `min_contacts` touching contacts (walls included).
long floating_disc_count(const World& world, int min_contacts = 3);
// Mean |net force| over free (not prescribed) bodies / mean |contact force| over touching
// contacts; 0 when nothing touches.
double unbalanced_force_ratio(const World& world);
// Physical kinetic energy (real masses even under density scaling), J per m of thickness.
double kinetic_energy(const World& world);
// Energy stored in the contact springs and bonds, J per m (contact_energy(world).strain()).
double strain_energy(const World& world);
// 1 - sum(pi r^2) / A over active discs (overlaps not subtracted).
double porosity(const World& world, double area);

}  // namespace cdem::dem
