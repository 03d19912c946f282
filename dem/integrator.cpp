#include "dem/integrator.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <type_traits>

namespace cdem::dem {

namespace {

// Body k's force and moment about its centroid: its discs' sums plus the applied loads, into
// bodies.fx/fy/moment (read after the step too: unbalanced force, prescribed work).
void gather_body_force(Bodies& b, const Discs& d, std::size_t k) {
  const std::int32_t first = b.first_disc[k];
  if (!b.is_clump[k]) {
    b.fx[k] = d.fx[first] + b.fx_applied[k];
    b.fy[k] = d.fy[first] + b.fy_applied[k];
    b.moment[k] = d.moment[first];
    return;
  }
  double fx = b.fx_applied[k], fy = b.fy_applied[k], m = 0;
  for (std::int32_t i = first; i < first + b.disc_count[k]; ++i) {
    fx += d.fx[i];
    fy += d.fy[i];
    m += d.moment[i] + (d.x[i] - b.x[k]) * d.fy[i] - (d.y[i] - b.y[k]) * d.fx[i];
  }
  b.fx[k] = fx;
  b.fy[k] = fy;
  b.moment[k] = m;
}

// Body k's kinematics from its disc's record when k is a free disc (catch_up_free_bodies).
void catch_up_free_disc(Bodies& b, const Discs& d, std::size_t k) {
  const DiscState& disc = d.state[static_cast<std::size_t>(b.first_disc[k])];
  b.x[k] = disc.x;
  b.y[k] = disc.y;
  b.vx[k] = disc.vx;
  b.vy[k] = disc.vy;
  b.omega[k] = disc.omega;
}

// Energy terms of one body over one step, before the common factor dt / 2: damping and
// applied work as force x (v_old + v_new). T = double for one body, Lanes8 or Lanes4 for several.
template <class T>
struct StepEnergyOf {
  T damped{}, applied{};
};

// Local damping of one degree of freedom; with kDamped = false (alpha = 0) the force itself,
// which is what local_damping returns for alpha = 0 (F minus a signed zero), so the velocities
// have the same bits either way.
template <bool kDamped, class T>
T damped_force(T force, T velocity, T alpha) {
  if constexpr (kDamped)
    return local_damping(force, velocity, alpha);
  else
    return force;
}

// One degree of freedom of a free body: updates the half-step velocity and adds its share of
// the energy removed by damping, (F - F_damped) . v_mean dt, and of the applied work,
// F_applied . v_mean dt. The sums per body are added to the step totals once per body, which
// keeps the serial dependency chains of the accumulators short. The power of the contact
// forces, which carries the strain energy to the half step, is not summed here: it is needed
// only when the energies are read, and strain_to_half_step (dem/energy.hpp) forms it then from
// the forces and velocities the step leaves behind.
// kBook = false: the velocity alone.
template <bool kBook, bool kDamped, class T>
void advance(T& v, T force, T applied, T inv_inertia, T dt, T alpha, StepEnergyOf<T>& e) {
  const T f_damped = damped_force<kDamped>(force, v, alpha);
  const T v_old = v;
  v += dt * inv_inertia * f_damped;
  if constexpr (kBook) {
    const T v_sum = v_old + v;
    if constexpr (kDamped) e.damped += (force - f_damped) * v_sum;
    e.applied += applied * v_sum;
  }
}

// n consecutive free discs (not clumps, not prescribed) integrated at once: their step's
// energy terms, each summed into the totals in body order by the caller, and the running
// bounds of every group of the range, lane by lane.
template <std::size_t n>
struct FreeDiscLanes {
  // J before the factor dt / 2: lane l's damping term at 2 l, its applied work at 2 l + 1
  // (store_interleaved). As two arrays, GCC summed each lane's two terms as one vector whose
  // 16-byte load straddled two of the lane function's vector stores, and the load waited for
  // them to retire: 41 % of the two-thread integration's samples sat behind it
  // (docs/performance.md "Session 41"). Written by each group.
  alignas(64) double energy[2 * n];
  // Over the range's groups so far, per lane: the sum of x + y + theta after the step (m; only
  // its finiteness is read, so the order of its additions is free) and the largest squared
  // speed (m^2/s^2; a maximum has one value in any order). Summed into the range's totals in
  // body order, one addition and one maximum per body, they were two serial chains that held
  // the integration of a step without energy terms (docs/performance.md "Session 56").
  alignas(64) double position[n] = {};
  alignas(64) double speed2[n] = {};
};

// True when bodies k .. k + n - 1 are all free discs, on consecutive discs (as World numbers
// them: a body's discs follow the previous body's), whose forces are then read as one vector.
template <std::size_t n>
bool free_discs(const Bodies& b, std::size_t k) {
  using Flags = std::conditional_t<n == 8, std::uint64_t, std::uint32_t>;
  Flags prescribed, clump;
  static_assert(sizeof(prescribed) == n * sizeof(b.prescribed[0]));
  std::memcpy(&prescribed, b.prescribed.data() + k, sizeof(prescribed));
  std::memcpy(&clump, b.is_clump.data() + k, sizeof(clump));
  return (prescribed | clump) == 0 &&
         b.first_disc[k + n - 1] - b.first_disc[k] == static_cast<std::int32_t>(n - 1);
}

// Disc i's radius changed as `radii` says, one disc at a time (the lanes below do the same
// operations).
void change_radius(const RadiusChange& radii, Discs& d, std::size_t i) {
  d.r[i] *= radii.factor;
  if (radii.before) radii.before[i] = d.r[i];
  if (radii.per_disc) d.r[i] *= radii.per_disc[i];
}

// The free-disc branch of integrate_bodies on lanes, the same operations in the same order, on
// the discs' records: a free disc's position, velocity and forces are not copied to its body
// (catch_up_free_bodies, dem/integrator.hpp), which saves 128 bytes of traffic per free disc and
// step (read and write of x, y, vx, vy, omega; write of fx, fy, moment). kApplied = false
// (Bodies::any_applied false: every applied load is +0) adds a constant +0 for the applied loads
// instead of reading them, which gives the same bits. Lane code: called only from the
// integrate_free_discs below, which inline it.
template <bool kBook, bool kDamped, bool kApplied, class L>
void integrate_free_discs_of(Bodies& b, Discs& d, double dt, double alpha,
                             const RadiusChange& radii, std::size_t k,
                             const BodyEnergyArrays* per_body, FreeDiscLanes<kLanes<L>>& out) {
  using S = DiscState;
  const L dtl = splat<L>(dt), al = splat<L>(alpha);
  double* const records = reinterpret_cast<double*>(d.state.data());
  const std::int32_t* const index = b.first_disc.data() + k;
  L fields[kRecordFields];
  load_records(records, index, fields);
  L vx = fields[S::kVx], vy = fields[S::kVy], w = fields[S::kOmega];
  const L inv_mass = load<L>(b.inv_mass_dyn.data() + k);
  // The bodies' forces gathered from their discs here (gather_body_force's free-disc branch),
  // not in a pass of their own before the integration: one pass over the bodies, not two.
  const std::size_t first = static_cast<std::size_t>(b.first_disc[k]);
  const L fx_applied = kApplied ? load<L>(b.fx_applied.data() + k) : splat<L>(0.0),
          fy_applied = kApplied ? load<L>(b.fy_applied.data() + k) : splat<L>(0.0);
  L sums[DiscLoad::kFields];
  load_quads(reinterpret_cast<const double*>(d.load.data() + first), sums);
  const L fx = sums[DiscLoad::kFx] + fx_applied, fy = sums[DiscLoad::kFy] + fy_applied;
  const L moment = sums[DiscLoad::kMoment];
  StepEnergyOf<L> e;
  advance<kBook, kDamped>(vx, fx, fx_applied, inv_mass, dtl, al, e);
  advance<kBook, kDamped>(vy, fy, fy_applied, inv_mass, dtl, al, e);
  advance<kBook, kDamped>(w, moment, L{}, load<L>(b.inv_inertia_dyn.data() + k), dtl, al, e);
  const L x = fields[S::kX] + dtl * vx, y = fields[S::kY] + dtl * vy;
  const L theta = load<L>(b.theta.data() + k) + dtl * w;
  store(b.theta.data() + k, theta);
  if constexpr (kBook) {
    store_interleaved(out.energy, e.damped, e.applied);
    if (per_body) {
      store(per_body->damped + k, e.damped);
      store(per_body->applied + k, e.applied);
      store(per_body->prescribed + k, L{});
    }
  }
  store(out.position, load<L>(out.position) + (x + y + theta));
  // As std::max(bound, speed2): a NaN speed leaves the bound as it was.
  store(out.speed2, max_of(load<L>(out.speed2), vx * vx + vy * vy));
  // Back onto the discs' records: position, velocity and the radius changed (in the line the
  // store writes anyway); the offset keeps its value.
  fields[S::kX] = x;
  fields[S::kY] = y;
  fields[S::kR] = fields[S::kR] * splat<L>(radii.factor);
  if (radii.before) store(radii.before + first, fields[S::kR]);
  if (radii.per_disc) fields[S::kR] = fields[S::kR] * load<L>(radii.per_disc + first);
  fields[S::kVx] = vx;
  fields[S::kVy] = vy;
  fields[S::kOmega] = w;
  constexpr unsigned kMoved =
      1u << S::kX | 1u << S::kY | 1u << S::kR | 1u << S::kVx | 1u << S::kVy | 1u << S::kOmega;
  store_records(records, index, fields, kMoved);
}

template <bool kBook, bool kDamped, bool kApplied>
CDEM_LANES8_TARGET void integrate_free_discs(Bodies& b, Discs& d, double dt, double alpha,
                                             const RadiusChange& radii, std::size_t k,
                                             const BodyEnergyArrays* per_body,
                                             FreeDiscLanes<8>& out) {
  integrate_free_discs_of<kBook, kDamped, kApplied, Lanes8>(b, d, dt, alpha, radii, k, per_body,
                                                            out);
}
template <bool kBook, bool kDamped, bool kApplied>
CDEM_LANES4_TARGET void integrate_free_discs(Bodies& b, Discs& d, double dt, double alpha,
                                             const RadiusChange& radii, std::size_t k,
                                             const BodyEnergyArrays* per_body,
                                             FreeDiscLanes<4>& out) {
  integrate_free_discs_of<kBook, kDamped, kApplied, Lanes4>(b, d, dt, alpha, radii, k, per_body,
                                                            out);
}

// kBook = false is the same loop without the energy terms, kDamped = false without local
// damping (alpha = 0: its force and energy terms are zero); each combination is instantiated
// separately so the loop carries no branch per degree of freedom. With `per_body`, each body's
// energy terms are also stored there (the multi-thread cycle sums them in body order). n > 1:
// runs of n free discs in lanes (8: AVX-512, 4: AVX2).
template <bool kBook, bool kDamped, std::size_t n>
RangeMotion integrate_bodies(Bodies& b, Discs& d, double dt, double alpha,
                             const RadiusChange& radii, std::size_t begin, std::size_t end,
                             const BodyEnergyArrays* per_body, InterleavedSum* side) {
  RangeMotion m;
  // The side sum's terms per group of n bodies, rounded up, so that the groups add nearly all
  // of them.
  const std::size_t side_per_group =
      side && end > begin ? (side->count * n + (end - begin) - 1) / (end - begin) : 0;
  // Sum of every position: non-finite exactly when some position is (positions are far from
  // overflow), so the loop carries one addition per body instead of a test and a branch; the
  // body is looked for only when the sum says there is one. Its value is not read, so the lanes
  // keep their own sums (FreeDiscLanes).
  double position_sum = 0;
  // Largest squared speed of a free disc and largest pebble speed bound of a clump (m/s).
  double disc_speed2 = 0, pebble_speed = 0;
  FreeDiscLanes<n> out;  // the groups' terms and their running bounds
  for (std::size_t k = begin; k < end; ++k) {
    if constexpr (n > 1) {
      if (k + n <= end && free_discs<n>(b, k)) {
        if (b.any_applied)
          integrate_free_discs<kBook, kDamped, true>(b, d, dt, alpha, radii, k, per_body, out);
        else
          integrate_free_discs<kBook, kDamped, false>(b, d, dt, alpha, radii, k, per_body, out);
        if constexpr (kBook)
          for (std::size_t l = 0; l < n; ++l) {
            m.damped += out.energy[2 * l];
            m.applied += out.energy[2 * l + 1];
          }
        if (side) side->advance(side_per_group);
        k += n - 1;
        continue;
      }
    }
    // A free disc the lanes integrated last holds its motion on its record alone.
    if (!b.is_clump[k]) catch_up_free_disc(b, d, k);
    gather_body_force(b, d, k);
    if (!b.prescribed[k]) {
      StepEnergyOf<double> e;
      advance<kBook, kDamped>(b.vx[k], b.fx[k], b.fx_applied[k], b.inv_mass_dyn[k], dt, alpha, e);
      advance<kBook, kDamped>(b.vy[k], b.fy[k], b.fy_applied[k], b.inv_mass_dyn[k], dt, alpha, e);
      advance<kBook, kDamped>(b.omega[k], b.moment[k], 0.0, b.inv_inertia_dyn[k], dt, alpha, e);
      if constexpr (kBook) {
        m.damped += e.damped;
        m.applied += e.applied;
        if (per_body) {
          per_body->damped[k] = e.damped;
          per_body->applied[k] = e.applied;
          per_body->prescribed[k] = 0;
        }
      }
    } else if constexpr (kBook) {
      // The contacts push on the body with F - F_applied; it does the opposite work on them.
      const double work = (b.fx[k] - b.fx_applied[k]) * b.vx[k] +
                          (b.fy[k] - b.fy_applied[k]) * b.vy[k] + b.moment[k] * b.omega[k];
      m.prescribed -= work;
      if (per_body) {
        per_body->damped[k] = per_body->applied[k] = 0;
        per_body->prescribed[k] = work;
      }
    }
    b.x[k] += dt * b.vx[k];
    b.y[k] += dt * b.vy[k];
    b.theta[k] += dt * b.omega[k];
    // Positions integrate the velocities, so a non-finite velocity shows in them already.
    position_sum += b.x[k] + b.y[k] + b.theta[k];
    const std::int32_t first = b.first_disc[k];
    if (!b.is_clump[k]) {
      disc_speed2 = std::max(disc_speed2, b.vx[k] * b.vx[k] + b.vy[k] * b.vy[k]);
      d.x[first] = b.x[k];
      d.y[first] = b.y[k];
      d.vx[first] = b.vx[k];
      d.vy[first] = b.vy[k];
      d.omega[first] = b.omega[k];
      change_radius(radii, d, static_cast<std::size_t>(first));
      continue;
    }
    const double c = std::cos(b.theta[k]), s = std::sin(b.theta[k]);
    // A pebble moves by at most |v| dt + |omega| dt |offset| in a step (the chord of its arc is
    // shorter than the arc); |ox| + |oy| >= |offset|.
    const double speed = std::sqrt(b.vx[k] * b.vx[k] + b.vy[k] * b.vy[k]);
    for (std::int32_t i = first; i < first + b.disc_count[k]; ++i) {
      const double ox = c * d.offset_x[i] - s * d.offset_y[i];
      const double oy = s * d.offset_x[i] + c * d.offset_y[i];
      pebble_speed =
          std::max(pebble_speed, speed + std::abs(b.omega[k]) * (std::abs(ox) + std::abs(oy)));
      d.x[i] = b.x[k] + ox;
      d.y[i] = b.y[k] + oy;
      // Rigid-body velocity of the pebble centre: v + omega x offset.
      d.vx[i] = b.vx[k] - b.omega[k] * oy;
      d.vy[i] = b.vy[k] + b.omega[k] * ox;
      d.omega[i] = b.omega[k];
      change_radius(radii, d, static_cast<std::size_t>(i));
    }
  }
  if constexpr (n > 1)
    for (std::size_t l = 0; l < n; ++l) {
      position_sum += out.position[l];
      disc_speed2 = std::max(disc_speed2, out.speed2[l]);
    }
  if (side) side->advance(side->count);
  m.position_sum = position_sum;
  m.disc_speed2 = disc_speed2;
  m.pebble_speed = pebble_speed;
  return m;
}

}  // namespace

RangeMotion integrate_range(Bodies& b, Discs& d, double dt, double alpha, bool book,
                            std::size_t begin, std::size_t end, const BodyEnergyArrays* per_body,
                            LaneIsa lanes, const RadiusChange& radii, InterleavedSum* side) {
  // Each combination of energy terms, damping and lane count is its own loop, with no branch on
  // them per body.
  const auto with_lanes = [&]<bool kBook, bool kDamped>() {
    switch (usable_lanes(lanes)) {
      case LaneIsa::Avx512:
        return integrate_bodies<kBook, kDamped, 8>(b, d, dt, alpha, radii, begin, end, per_body,
                                                   side);
      case LaneIsa::Avx2:
        return integrate_bodies<kBook, kDamped, 4>(b, d, dt, alpha, radii, begin, end, per_body,
                                                   side);
      case LaneIsa::None:
        break;
    }
    return integrate_bodies<kBook, kDamped, 1>(b, d, dt, alpha, radii, begin, end, per_body, side);
  };
  if (alpha != 0)
    return book ? with_lanes.template operator()<true, true>()
                : with_lanes.template operator()<false, true>();
  return book ? with_lanes.template operator()<true, false>()
              : with_lanes.template operator()<false, false>();
}

void book_step_energy(const RangeMotion& m, double dt, EnergyLedger& ledger) {
  ledger.damping += 0.5 * dt * m.damped;
  ledger.applied_work += 0.5 * dt * m.applied;
  ledger.prescribed_work += dt * m.prescribed;
}

void catch_up_free_bodies(Bodies& b, const Discs& d) {
  catch_up_free_bodies(b, d, 0, b.size());
}

void catch_up_free_bodies(Bodies& b, const Discs& d, std::size_t begin, std::size_t end) {
  for (std::size_t k = begin; k < end; ++k) {
    if (b.is_clump[k]) continue;
    // What the disc-by-disc integration stores: the same copies and sums, so the same bits.
    catch_up_free_disc(b, d, k);
    gather_body_force(b, d, k);
  }
}

StepMotion step_motion(const Bodies& b, const Discs& d, const RangeMotion& m, double dt) {
  StepMotion motion;
  motion.max_displacement = dt * std::max(std::sqrt(m.disc_speed2), m.pebble_speed);
  if (!std::isfinite(m.position_sum))
    for (std::size_t k = 0; k < b.size(); ++k)
      if (const BodyMotion now = body_motion(b, d, k, true);
          !std::isfinite(now.x + now.y + b.theta[k])) {
        motion.bad_body = static_cast<long>(k);
        break;
      }
  return motion;
}

StepMotion integrate(Bodies& b, Discs& d, double dt, double alpha, EnergyLedger* ledger,
                     LaneIsa lanes, const RadiusChange& radii) {
  const RangeMotion m =
      integrate_range(b, d, dt, alpha, ledger != nullptr, 0, b.size(), nullptr, lanes, radii);
  if (ledger) book_step_energy(m, dt, *ledger);
  return step_motion(b, d, m, dt);
}

}  // namespace cdem::dem
