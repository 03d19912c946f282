#pragma once
// A linear-elastic 1D bar (rod) for the split Hopkinson pressure bar (SPEC 6, docs/lab_tests.md
// "SHPB"): the method of characteristics on a uniform grid at Courant number 1, a d'Alembert
// lattice. The bar carries a right-going wave f and a left-going wave g (both in Pa, compression
// positive); stress sigma = f + g, particle velocity v = (f - g) / (rho c0) (m/s, along +x, from
// end 0 towards end L). With cell size dx = c0 dt every wave moves exactly one node per step, so
// the lattice is exact for the 1D wave equation at its nodes and steps: no dispersion, no
// numerical damping, any pulse shape travels undistorted for ever. One step costs O(1): each
// wave is a ring buffer of the values that entered it at its end (the value at node i is the
// one that entered i steps ago). Unit thickness (SPEC 2): the cross-section is width x 1 m.
#include <cstddef>
#include <vector>

namespace cdem::dem {

struct BarProperties {
  double young_modulus = 0;  // Pa
  double density = 0;        // kg/m3
  double length = 0;         // m
  double width = 0;          // m, cross-section width (thickness 1 m)

  double wave_speed() const;  // m/s, c0 = sqrt(E / rho)
  double impedance() const;   // Pa s/m, rho c0 (stress per particle velocity)
  double area() const;        // m2, width x the unit thickness
};

enum class BarEnd { Left, Right };  // x = 0 and x = L

class ElasticBar {
 public:
  // `cells` >= 1 cells of dx = L / cells; the step is dx / c0. Throws std::invalid_argument for
  // non-positive or non-finite properties or cells < 1.
  ElasticBar(const BarProperties& properties, long cells);

  const BarProperties& properties() const { return p_; }
  long cells() const { return n_; }
  double cell_size() const { return dx_; }  // m
  double time_step() const { return dt_; }  // s, dx / c0 (Courant number 1)
  long steps() const { return level_; }     // time level: steps taken since the start
  double time() const { return static_cast<double>(level_) * dt_; }  // s

  // Moves both waves one cell. The two end values that enter the bar at this new level (the
  // right-going wave at x = 0, the left-going wave at x = L) are then set by one end condition
  // per end, before any state is read at that end: set_end_stress or set_end_velocity.
  void advance();
  // The wave arriving at an end at this level (Pa): g at x = 0, f at x = L.
  double arriving(BarEnd end) const;
  // Stress (Pa, compression positive) held at the end: an applied pressure, 0 at a free end,
  // the contact force of a specimen / area at a coupled end.
  void set_end_stress(BarEnd end, double stress);
  // Velocity (m/s along +x) held at the end: 0 at a fixed end.
  void set_end_velocity(BarEnd end, double velocity);

  // State at node i in [0, cells] (x = i dx) at this level.
  double right_going(long node) const;  // Pa, f
  double left_going(long node) const;   // Pa, g
  double stress(long node) const { return right_going(node) + left_going(node); }
  double strain(long node) const { return stress(node) / p_.young_modulus; }  // compression +
  double velocity(long node) const;                                           // m/s along +x
  double end_stress(BarEnd end) const { return stress(end_node(end)); }
  double end_velocity(BarEnd end) const { return velocity(end_node(end)); }
  long end_node(BarEnd end) const { return end == BarEnd::Left ? 0 : n_; }
  // The node nearest to x (m), for a strain gauge; x must lie in [0, L].
  long node_at(double x) const;

  // Energy of the waves in the bar (J per m of thickness): each wave value stands for one cell,
  // the right-going ones of nodes 0 .. cells - 1 and the left-going ones of nodes 1 .. cells,
  // with energy density (f^2 + g^2) / E (strain + kinetic: sigma^2 / 2E + rho v^2 / 2). The sum
  // changes only by what the end conditions put in or take out (exactly kept at free and fixed
  // ends). O(cells): for checks, not for the step.
  double wave_energy() const;

 private:
  double& slot(std::vector<double>& ring, long entered) {
    return ring[static_cast<std::size_t>(entered % (n_ + 1))];
  }
  double at(const std::vector<double>& ring, long entered) const {
    return entered < 0 ? 0.0 : ring[static_cast<std::size_t>(entered % (n_ + 1))];
  }

  BarProperties p_;
  long n_ = 0;  // cells
  double dx_ = 0, dt_ = 0, impedance_ = 0;
  long level_ = 0;
  // right_[k mod (n+1)]: the right-going value that entered at x = 0 at level k; left_ the
  // left-going one that entered at x = L. Levels before 0: the bar at rest.
  std::vector<double> right_, left_;
};

// Joins the right end of `a` to the left end of `b` (a welded interface: equal forces and equal
// velocities), after both have advanced to the same level. Impedance-matched bars (equal
// rho c0 A) transmit everything; otherwise the plane-wave reflection and transmission
// coefficients follow. Both bars must share the time step.
void join_bars(ElasticBar& a, ElasticBar& b);

}  // namespace cdem::dem
