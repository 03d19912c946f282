#include "dem/elastic_bar.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

#include "dem/linear_contact.hpp"

namespace cdem::dem {

double BarProperties::wave_speed() const {
  return std::sqrt(young_modulus / density);
}

double BarProperties::impedance() const {
  return density * wave_speed();
}

double BarProperties::area() const {
  return width * kThickness;
}

ElasticBar::ElasticBar(const BarProperties& properties, long cells) : p_(properties), n_(cells) {
  for (const double v : {p_.young_modulus, p_.density, p_.length, p_.width})
    if (!(v > 0) || !std::isfinite(v))
      throw std::invalid_argument("elastic bar: E, density, length and width must be finite > 0");
  if (cells < 1) throw std::invalid_argument("elastic bar: needs at least one cell");
  dx_ = p_.length / static_cast<double>(n_);
  dt_ = dx_ / p_.wave_speed();
  impedance_ = p_.impedance();
  right_.assign(static_cast<std::size_t>(n_ + 1), 0.0);
  left_.assign(static_cast<std::size_t>(n_ + 1), 0.0);
}

void ElasticBar::advance() {
  ++level_;
  // The slots of this level held the values that entered n + 1 levels ago, which have left the
  // bar; until an end condition sets them they stand for a bar that lets nothing in.
  slot(right_, level_) = 0;
  slot(left_, level_) = 0;
}

double ElasticBar::arriving(BarEnd end) const {
  return end == BarEnd::Left ? at(left_, level_ - n_) : at(right_, level_ - n_);
}

// At x = 0: sigma = f + g, v = (f - g) / Z with g arriving, f entering; at x = L the roles swap
// and v = (f - g) / Z gives g = f - Z v.
void ElasticBar::set_end_stress(BarEnd end, double stress) {
  const double in = arriving(end);
  slot(end == BarEnd::Left ? right_ : left_, level_) = stress - in;
}

void ElasticBar::set_end_velocity(BarEnd end, double velocity) {
  const double in = arriving(end);
  if (end == BarEnd::Left)
    slot(right_, level_) = in + impedance_ * velocity;
  else
    slot(left_, level_) = in - impedance_ * velocity;
}

double ElasticBar::right_going(long node) const {
  return at(right_, level_ - node);
}

double ElasticBar::left_going(long node) const {
  return at(left_, level_ - (n_ - node));
}

double ElasticBar::velocity(long node) const {
  return (right_going(node) - left_going(node)) / impedance_;
}

long ElasticBar::node_at(double x) const {
  if (!(x >= 0 && x <= p_.length))
    throw std::invalid_argument("elastic bar: position " + std::to_string(x) +
                                " m outside the bar [0, " + std::to_string(p_.length) + "] m");
  return std::lround(x / dx_);
}

double ElasticBar::wave_energy() const {
  double sum = 0;
  for (long i = 0; i < n_; ++i) {
    const double f = right_going(i), g = left_going(i + 1);
    sum += f * f + g * g;
  }
  return sum * p_.area() * dx_ / p_.young_modulus;
}

void join_bars(ElasticBar& a, ElasticBar& b) {
  if (a.time_step() != b.time_step() || a.steps() != b.steps())
    throw std::invalid_argument("join_bars: the bars must share the time step and the level");
  const double fa = a.arriving(BarEnd::Right), gb = b.arriving(BarEnd::Left);
  const double aa = a.properties().area(), ab = b.properties().area();
  // Equal forces A_a (2 f_a - Z_a v) = A_b (2 g_b + Z_b v) give the common velocity.
  const double v =
      2 * (aa * fa - ab * gb) / (aa * a.properties().impedance() + ab * b.properties().impedance());
  a.set_end_velocity(BarEnd::Right, v);
  b.set_end_velocity(BarEnd::Left, v);
}

}  // namespace cdem::dem
