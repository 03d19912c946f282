// Compaction of aggregates in a shrinking mould with Box2D (SPEC 3.3). docs/placement.md has
// the algorithm, the exactness argument and measured figures.
//
// Units. Box2D is tuned for bodies of 0.1-10 "meters" and has absolute tolerances (linear slop
// 0.005, polygon skin 0.01), so the aggregates are scaled: one Box2D unit = L metres with the
// largest aggregate kUnitsPerLargest units across. Everything named *_u below is in these
// units; everything else is SI.
#include "mesogen/compaction.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <set>
#include <stdexcept>

#include <box2d/box2d.h>

#include "core/input_error.hpp"
#include "mesogen/aggregate_shape.hpp"

namespace cdem::mesogen {
namespace {

using Polygon = std::vector<Eigen::Vector2d>;

// Scale: the largest aggregate spans this many Box2D units (so a 20 mm stone is 4 units and a
// 2.5 mm one 0.5 unit, both inside Box2D's comfortable range).
constexpr double kUnitsPerLargest = 4;
// Safety margin added to the inflation (units): covers the float rounding of the fixture
// vertices (~1e-6 units) and Box2D's welding of vertices closer than half a linear slop with a
// wide margin.
constexpr double kInflationMargin_u = 1e-3;
// Box2D keeps touching shapes at about one linear slop of overlap of their skins (each polygon
// and each wall carries a skin of b2_polygonRadius around its core).
constexpr double kSkins_u = 2 * b2_polygonRadius;
// The walls advance only while the deepest skin overlap is below this (units): half the two
// skins, so the cores stay well apart while the mould shrinks.
constexpr double kPenetrationAllowed_u = 0.5 * kSkins_u;
// At the end the packing relaxes until the deepest overlap is down to this (units). Then any
// two cores are at least kCushion_u apart, and that cushion is counted as part of the gap.
constexpr double kPenetrationFinal_u = 1.5 * b2_linearSlop;
constexpr double kCushion_u = kSkins_u - kPenetrationFinal_u;
constexpr float kTimeStep = 1.0f / 60;  // Box2D seconds; the physical time scale is arbitrary
constexpr int kVelocityIterations = 8;
constexpr int kPositionIterations = 3;
// Wall advance per step of the farthest wall (units): 0.002 units = 0.1 % of a large stone.
constexpr double kWallAdvance_u = 2e-3;
// Granular gas: every kKickInterval steps each aggregate keeps half its velocity and gets a
// random kick of up to kKickSpeed_u (units/s), i.e. up to ~0.008 units per step.
constexpr long kKickInterval = 10;
constexpr double kKickSpeed_u = 0.5;
constexpr float kFriction = 0.1f;  // low: frictionless-like packings reach high contents
// Inflated area fraction of the gas before compaction: low enough for random insertion.
constexpr double kGasFraction = 0.35;
// The disc mould is a regular polygon inscribed in the circle, with enough sides that its
// sagitta (the room lost at mid-side, units) stays below one linear slop.
constexpr double kDiscSagitta_u = b2_linearSlop;
// Jam: fewer than kStallMinAdvances wall advances in kStallWindow steps.
constexpr long kStallWindow = 3000;
constexpr long kStallMinAdvances = 30;
constexpr long kRelaxMinSteps = 60, kRelaxMaxSteps = 1500;
// Violators repaired by re-placement at most this share of the aggregates (at least 3).
constexpr double kRepairShare = 0.03;
constexpr long kRepairTrials = 20000;

Eigen::Vector2d outward_normal(const Eigen::Vector2d& from, const Eigen::Vector2d& to) {
  const Eigen::Vector2d e = (to - from).normalized();
  return {e.y(), -e.x()};  // right of the direction of travel = outside for CCW
}

// A convex polygon (units, CCW) grown so that it contains its Minkowski sum with a disc of
// radius r: each edge moved out by r, corners mitred, or bevelled by the tangent at the
// bisector where the mitre would stick out more than 2 r (interior angle below 60 degrees).
Polygon inflate(const Polygon& p, double r) {
  Polygon out;
  const std::size_t n = p.size();
  for (std::size_t i = 0; i < n; ++i) {
    const Eigen::Vector2d& prev = p[(i + n - 1) % n];
    const Eigen::Vector2d& v = p[i];
    const Eigen::Vector2d& next = p[(i + 1) % n];
    const Eigen::Vector2d n_in = outward_normal(prev, v), n_out = outward_normal(v, next);
    const double c = n_in.dot(n_out);
    if (c >= -0.5) {
      out.push_back(v + r * (n_in + n_out) / (1 + c));
      continue;
    }
    const Eigen::Vector2d m = (n_in + n_out).normalized();
    const Eigen::Vector2d d_in = (v - prev).normalized(), d_out = (next - v).normalized();
    out.push_back(v + r * n_in + r * (1 - n_in.dot(m)) / d_in.dot(m) * d_in);
    out.push_back(v + r * n_out + r * (1 - n_out.dot(m)) / d_out.dot(m) * d_out);
  }
  return out;
}

// Box2D welds vertices closer than half a linear slop and aborts on a polygon left with fewer
// than three. Neighbours closer than one linear slop are therefore merged first, into the
// intersection of the lines of the edges before and after them: the polygon stays convex and
// still contains the original one. Only where that point would stick out (a needle tip made of
// two close vertices) is the second vertex dropped, which gives up less than a linear slop,
// well inside the cushion (and the exact check has the last word anyway).
Polygon merge_close_vertices(Polygon p) {
  const double tol = b2_linearSlop;
  for (bool merged = true; merged && p.size() > 3;) {
    merged = false;
    const std::size_t n = p.size();
    for (std::size_t i = 0; i < n; ++i) {
      const std::size_t j = (i + 1) % n;
      if ((p[j] - p[i]).norm() >= tol) continue;
      const Eigen::Vector2d& before = p[(i + n - 1) % n];
      const Eigen::Vector2d& after = p[(j + 1) % n];
      const Eigen::Vector2d d1 = p[i] - before, d2 = after - p[j];
      const double cross = d1.x() * d2.y() - d1.y() * d2.x();
      Eigen::Vector2d x = p[i];
      if (cross > 0) {  // lines meet ahead of p[i]
        const Eigen::Vector2d w = p[j] - before;
        const Eigen::Vector2d meet = before + (w.x() * d2.y() - w.y() * d2.x()) / cross * d1;
        if ((meet - p[i]).norm() <= 4 * tol) x = meet;
      }
      p[i] = x;
      p.erase(p.begin() + static_cast<std::ptrdiff_t>(j));
      merged = true;
      break;
    }
  }
  return p;
}

// Would b2PolygonShape::Set keep at least three vertices (it welds those closer than half a
// linear slop and aborts otherwise) and a positive area?
bool box2d_accepts(const std::vector<b2Vec2>& piece) {
  const float weld = 0.5f * b2_linearSlop;
  std::vector<b2Vec2> kept;
  for (const b2Vec2& v : piece)
    if (std::none_of(kept.begin(), kept.end(),
                     [&](const b2Vec2& k) { return b2DistanceSquared(v, k) < weld * weld; }))
      kept.push_back(v);
  if (kept.size() < 3) return false;
  float twice_area = 0;
  for (std::size_t i = 0; i < kept.size(); ++i)
    twice_area += b2Cross(kept[i], kept[(i + 1) % kept.size()]);
  return twice_area > 1e3f * b2_epsilon;
}

// Box2D polygons have at most b2_maxPolygonVertices vertices: a larger convex polygon is cut
// into a fan of convex pieces around its first vertex, fixtures of one body.
std::vector<std::vector<b2Vec2>> fan_pieces(const Polygon& p) {
  std::vector<std::vector<b2Vec2>> pieces;
  const auto n = static_cast<int>(p.size());
  const int per_piece = b2_maxPolygonVertices - 1;  // besides the shared first vertex
  for (int k = 1; k < n - 1; k += per_piece - 1) {
    std::vector<b2Vec2> piece{b2Vec2(float(p[0].x()), float(p[0].y()))};
    for (int j = k; j < std::min(n, k + per_piece); ++j)
      piece.emplace_back(float(p[j].x()), float(p[j].y()));
    pieces.push_back(std::move(piece));
  }
  return pieces;
}

// The walls: kinematic boxes whose inner faces bound the Box2D mould. Wall i has its outward
// normal at angle theta_i and its inner face at distance s * distance_i from the centre, s
// being the scale of the mould (1 = the real one, less the clearance, plus the inflation).
class Walls {
 public:
  Walls(b2World& world, bool disc, int sides, double half_x_u, double half_y_u, double s0) {
    const double thickness_u = 1;
    if (disc) {
      const double half_angle = std::numbers::pi / sides;
      for (int i = 0; i < sides; ++i)
        add(world, 2 * half_angle * i, half_x_u * std::cos(half_angle),
            1.1 * s0 * half_x_u * std::sin(half_angle) + thickness_u, thickness_u);
    } else {
      const double long_x = s0 * half_x_u + 2 * thickness_u;
      const double long_y = s0 * half_y_u + 2 * thickness_u;
      add(world, 0, half_x_u, long_y, thickness_u);
      add(world, 0.5 * std::numbers::pi, half_y_u, long_x, thickness_u);
      add(world, std::numbers::pi, half_x_u, long_y, thickness_u);
      add(world, 1.5 * std::numbers::pi, half_y_u, long_x, thickness_u);
    }
  }

  // Puts the walls exactly at scale s and gives them the velocity that brings them to
  // s_next in one step (the kinematic velocity is what pushes the aggregates).
  void move(double s, double s_next) {
    for (const Wall& w : walls_) {
      const b2Vec2 dir(float(std::cos(w.theta)), float(std::sin(w.theta)));
      w.body->SetTransform(float(s * w.distance) * dir, float(w.theta));
      w.body->SetLinearVelocity(float((s_next - s) * w.distance / kTimeStep) * dir);
    }
  }

 private:
  struct Wall {
    b2Body* body;
    double theta, distance;
  };
  void add(b2World& world, double theta, double distance, double half_length, double thickness) {
    b2BodyDef def;
    def.type = b2_kinematicBody;
    b2Body* body = world.CreateBody(&def);
    b2PolygonShape box;
    box.SetAsBox(float(0.5 * thickness), float(half_length), b2Vec2(float(0.5 * thickness), 0), 0);
    b2FixtureDef fd;
    fd.shape = &box;
    fd.friction = kFriction;
    body->CreateFixture(&fd);
    walls_.push_back({body, theta, distance});
  }
  std::vector<Wall> walls_;
};

// Deepest overlap of the skins over all touching contacts (units, >= 0).
double max_penetration(b2World& world) {
  double deepest = 0;
  for (b2Contact* c = world.GetContactList(); c; c = c->GetNext()) {
    if (!c->IsTouching()) continue;
    b2WorldManifold wm;
    c->GetWorldManifold(&wm);
    for (int k = 0; k < c->GetManifold()->pointCount; ++k)
      deepest = std::max(deepest, -double(wm.separations[k]));
  }
  return deepest;
}

std::string mm(double metres) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.1f mm", metres * 1e3);
  return buf;
}

std::string fraction(double f) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.3f", f);
  return buf;
}

}  // namespace

RepairResult check_and_repair(const Container& mould, const std::vector<AggregateDraw>& draws,
                              std::vector<PlacedAggregate> placed,
                              const CompactionControls& controls, std::size_t max_replaced,
                              Rng& rng) {
  RepairResult out;
  std::set<std::size_t> bad;
  for (std::size_t k = 0; k < placed.size(); ++k)
    if (!inside_with_clearance(placed[k].vertices, mould, controls.boundary_clearance))
      bad.insert(k);
  for (const auto& [i, j] : pairs_closer_than(placed, controls.min_gap))
    if (!bad.count(i) && !bad.count(j)) bad.insert(placed[i].draw > placed[j].draw ? i : j);
  out.violators = bad.size();

  std::vector<PlacedAggregate> kept;
  std::vector<std::size_t> redo;
  for (std::size_t k = 0; k < placed.size(); ++k) {
    if (bad.count(k)) {
      redo.push_back(placed[k].draw);
    } else {
      out.valid_area += std::abs(polygon_area(placed[k].vertices));
      kept.push_back(std::move(placed[k]));
    }
  }
  if (redo.size() > max_replaced) {
    out.message = std::to_string(redo.size()) +
                  " aggregates fail the exact clearance/gap checks, more than the " +
                  std::to_string(max_replaced) + " that may be placed again";
    return out;
  }
  std::sort(redo.begin(), redo.end());  // largest first
  PlacementControls pc;
  pc.min_gap = controls.min_gap;
  pc.boundary_clearance = controls.boundary_clearance;
  pc.max_trials_per_aggregate = kRepairTrials;
  PlacementResult r = place_among(mould, draws, redo, std::move(kept), pc, rng);
  for (std::size_t k = placed.size() - redo.size(); k < r.placed.size(); ++k)
    out.valid_area += std::abs(polygon_area(r.placed[k].vertices));
  if (!r.unplaced.empty()) {
    out.message = std::to_string(r.unplaced.size()) + " of the " + std::to_string(redo.size()) +
                  " aggregates that failed the exact checks found no room again";
    return out;
  }
  std::sort(r.placed.begin(), r.placed.end(),
            [](const auto& a, const auto& b) { return a.draw < b.draw; });
  out.placed = std::move(r.placed);
  out.success = true;
  return out;
}

CompactionResult compact(const Container& mould, const std::vector<AggregateDraw>& draws,
                         const PlacementResult& start, const CompactionControls& controls,
                         Rng& rng) {
  if (!(controls.min_gap >= 0) || !(controls.boundary_clearance >= 0))
    throw InputError("", "compaction", "min_gap and boundary_clearance must be >= 0");
  if (!(mould.width > 0) || !(mould.height > 0))
    throw InputError("", "specimen", "the mould needs a positive width and height");
  const bool disc = mould.shape == ContainerShape::Disc;
  const double inner_x = 0.5 * mould.width - controls.boundary_clearance;
  const double inner_y = 0.5 * (disc ? mould.width : mould.height) - controls.boundary_clearance;
  if (!(inner_x > 0) || !(inner_y > 0))
    throw InputError("", "placement.boundary_clearance", "leaves no room inside the mould");

  // Every draw exactly once, in `start.placed` or `start.unplaced`.
  std::vector<int> seen(draws.size(), 0);
  for (const auto& p : start.placed)
    if (p.draw < draws.size()) ++seen[p.draw];
  for (std::size_t i : start.unplaced)
    if (i < draws.size()) ++seen[i];
  if (std::any_of(seen.begin(), seen.end(), [](int k) { return k != 1; }) ||
      start.placed.size() + start.unplaced.size() != draws.size())
    throw std::invalid_argument("compact: `start` must hold every draw exactly once");

  double aggregate_area = 0, largest = 0;
  for (const auto& d : draws) {
    aggregate_area += std::abs(polygon_area(d.shape));
    for (const auto& v : d.shape) largest = std::max(largest, 2 * v.norm());
  }
  CompactionResult result;
  const double target = aggregate_area / mould.area();

  const auto max_replaced = std::max<std::size_t>(
      3, static_cast<std::size_t>(kRepairShare * static_cast<double>(draws.size())));
  if (start.unplaced.empty()) {
    RepairResult done = check_and_repair(mould, draws, start.placed, controls, max_replaced, rng);
    if (done.success) {
      result.success = true;
      result.placed = std::move(done.placed);
      result.replaced = done.violators;
      result.area_fraction_reached = target;
      result.message = "all aggregates placed by random trials; no compaction needed";
      return result;
    }
  }

  // Box2D frame: origin at the mould centre, L metres per unit.
  const double L = largest / kUnitsPerLargest;
  const Eigen::Vector2d centre = mould.centre();
  // Two relaxed cores are at least the cushion apart, so each polygon is inflated by half the
  // gap less half the cushion (never deflated), plus the margin: 2 inflation + cushion >= gap.
  const double inflation_u =
      std::max(0.0, 0.5 * (controls.min_gap / L - kCushion_u)) + kInflationMargin_u;
  // Inner faces of the walls at scale 1: a core that keeps the cushion from the wall keeps the
  // inflation plus the cushion, so the faces sit that far outside the clearance line, less
  // the margin.
  const double wall_offset_u = inflation_u + kCushion_u - kInflationMargin_u;
  const double half_x_u = inner_x / L + wall_offset_u;
  const double half_y_u = inner_y / L + wall_offset_u;
  // sagitta = R (1 - cos(pi / n)) ~ R pi^2 / (2 n^2)
  const int sides = std::max(
      32,
      static_cast<int>(std::ceil(std::numbers::pi * std::sqrt(half_x_u / (2 * kDiscSagitta_u)))));
  const double apothem_factor = disc ? std::cos(std::numbers::pi / sides) : 1.0;
  auto mould_area_at = [&](double s) {  // m^2, the mould whose walls are at scale s
    const double grow_x = 2 * (s - 1) * half_x_u * L, grow_y = 2 * (s - 1) * half_y_u * L;
    if (disc) return 0.25 * std::numbers::pi * std::pow(mould.width + grow_x, 2);
    return (mould.width + grow_x) * (mould.height + grow_y);
  };

  // The gas: the placed aggregates with their centroids spread by s0 about the centre (which
  // keeps the mix uniform when the walls bring them back), the unplaced ones inserted by random
  // trials in between, in the enlarged mould, with the inflation and the skins as gap.
  const double skin_m = b2_polygonRadius * L;
  double inflated_area = 0;
  for (const auto& d : draws) {
    double perimeter = 0;
    for (std::size_t k = 0; k < d.shape.size(); ++k)
      perimeter += (d.shape[(k + 1) % d.shape.size()] - d.shape[k]).norm();
    const double r = inflation_u * L + skin_m;
    inflated_area += std::abs(polygon_area(d.shape)) + perimeter * r + std::numbers::pi * r * r;
  }
  double s0 = std::max(1.05, std::sqrt(inflated_area / (kGasFraction * mould_area_at(1))));
  std::vector<PlacedAggregate> gas;
  Container enlarged;
  for (int attempt = 0;; ++attempt) {
    enlarged.shape = mould.shape;
    enlarged.width = 2 * s0 * half_x_u * apothem_factor * L;
    enlarged.height = disc ? enlarged.width : 2 * s0 * half_y_u * L;
    std::vector<PlacedAggregate> spread = start.placed;
    for (auto& p : spread) {
      const Eigen::Vector2d shift = enlarged.centre() + s0 * (p.centroid - centre) - p.centroid;
      for (auto& v : p.vertices) v += shift;
      p.centroid += shift;
    }
    PlacementControls insertion;
    insertion.min_gap = 2 * (inflation_u * L + 2 * skin_m);
    insertion.boundary_clearance = inflation_u * L + 2 * skin_m;
    insertion.max_trials_per_aggregate = 2000;
    PlacementResult r =
        place_among(enlarged, draws, start.unplaced, std::move(spread), insertion, rng);
    if (r.unplaced.empty()) {
      gas = std::move(r.placed);
      break;
    }
    if (attempt == 10) {  // a pathological draw (e.g. one stone nearly the mould's size)
      double placed_area = 0;
      for (const auto& p : start.placed) placed_area += std::abs(polygon_area(p.vertices));
      result.area_fraction_reached = placed_area / mould.area();
      result.message = "compaction could not even scatter the aggregates in a mould " +
                       fraction(s0) + " times as wide; random placement reached area fraction " +
                       fraction(result.area_fraction_reached) + " of " + fraction(target);
      return result;
    }
    s0 *= 1.1;
  }

  b2World world(b2Vec2(0, 0));  // no gravity: the pile must stay uniform
  world.SetAllowSleeping(false);
  Walls walls(world, disc, sides, half_x_u, half_y_u, s0);
  std::vector<b2Body*> bodies;
  std::vector<double> body_radius_u;
  const Eigen::Vector2d gas_centre = enlarged.centre();
  for (const auto& p : gas) {
    Polygon local;
    double radius_u = 0;
    for (const auto& v : p.vertices) {
      local.emplace_back((v - p.centroid) / L);
      radius_u = std::max(radius_u, local.back().norm());
    }
    if (polygon_area(local) < 0) std::reverse(local.begin(), local.end());
    b2BodyDef def;
    def.type = b2_dynamicBody;
    const Eigen::Vector2d at = (p.centroid - gas_centre) / L;
    def.position.Set(float(at.x()), float(at.y()));
    b2Body* body = world.CreateBody(&def);
    for (const auto& piece : fan_pieces(merge_close_vertices(inflate(local, inflation_u)))) {
      if (!box2d_accepts(piece)) continue;  // a sliver of the fan; the exact check remains
      b2PolygonShape shape;
      shape.Set(piece.data(), static_cast<int>(piece.size()));
      b2FixtureDef fd;
      fd.shape = &shape;
      fd.density = 1;  // uniform: masses proportional to areas
      fd.friction = kFriction;
      body->CreateFixture(&fd);
    }
    if (!body->GetFixtureList()) {
      result.message = "compaction impossible: aggregate " + std::to_string(p.draw) +
                       " is too small for Box2D next to the largest one (" +
                       mm(p.equivalent_diameter) + " against " + mm(largest) + ")";
      return result;
    }
    bodies.push_back(body);
    body_radius_u.push_back(radius_u);
  }

  auto kick = [&](double strength) {
    for (std::size_t k = 0; k < bodies.size(); ++k) {
      const double phi = 2 * std::numbers::pi * rng.uniform();
      const double speed = strength * kKickSpeed_u * rng.uniform();
      const double spin = strength * kKickSpeed_u / body_radius_u[k] * rng.uniform(-1, 1);
      b2Body* b = bodies[k];
      b->SetLinearVelocity(0.5f * b->GetLinearVelocity() +
                           b2Vec2(float(speed * std::cos(phi)), float(speed * std::sin(phi))));
      b->SetAngularVelocity(0.5f * b->GetAngularVelocity() + float(spin));
    }
  };

  // Compression: walls advance while the overlaps allow, the gas is shaken throughout.
  const double ds = kWallAdvance_u / std::max(half_x_u, half_y_u);
  double s = s0;
  long advances_in_window = 0;
  bool jammed = false;
  while (s > 1 && result.steps < controls.max_steps) {
    const bool advance = max_penetration(world) <= kPenetrationAllowed_u;
    const double s_next = advance ? std::max(1.0, s - ds) : s;
    walls.move(s, s_next);
    if (result.steps % kKickInterval == 0) kick(1);
    world.Step(kTimeStep, kVelocityIterations, kPositionIterations);
    ++result.steps;
    s = s_next;
    advances_in_window += advance;
    if (result.steps % kStallWindow == 0) {
      if (advances_in_window < kStallMinAdvances) {
        jammed = true;
        break;
      }
      advances_in_window = 0;
    }
  }

  if (s > 1) {
    result.area_fraction_reached = aggregate_area / mould_area_at(s);
    const double w = mould.width + 2 * (s - 1) * half_x_u * L;
    const double h = disc ? w : mould.height + 2 * (s - 1) * half_y_u * L;
    result.message =
        std::string("compaction ") +
        (jammed ? "jammed"
                : "ran out of steps (" + std::to_string(result.steps) + " Box2D steps)") +
        ": the aggregates (area fraction " + fraction(target) +
        " of the mould) could not be brought into a mould smaller than " + mm(w) +
        (disc ? " across" : " x " + mm(h)) + "; area fraction reached " +
        fraction(result.area_fraction_reached);
    return result;
  }

  // Relax at the final size: no kicks, velocities bled off, until the overlaps are small.
  walls.move(1, 1);
  for (long k = 0; k < kRelaxMaxSteps && result.steps < controls.max_steps; ++k) {
    for (b2Body* b : bodies) {
      b->SetLinearVelocity(0.8f * b->GetLinearVelocity());
      b->SetAngularVelocity(0.8f * b->GetAngularVelocity());
    }
    world.Step(kTimeStep, kVelocityIterations, kPositionIterations);
    ++result.steps;
    if (k >= kRelaxMinSteps && max_penetration(world) <= kPenetrationFinal_u) break;
  }

  // Freeze: the final polygons, in metres and double, from the shapes and the body poses.
  std::vector<PlacedAggregate> final_state = gas;
  for (std::size_t k = 0; k < bodies.size(); ++k) {
    const b2Vec2 pos = bodies[k]->GetPosition();
    const double angle = bodies[k]->GetAngle();
    const double cs = std::cos(angle), sn = std::sin(angle);
    PlacedAggregate& p = final_state[k];
    const Eigen::Vector2d c = centre + L * Eigen::Vector2d(pos.x, pos.y);
    for (std::size_t j = 0; j < p.vertices.size(); ++j) {
      const Eigen::Vector2d w = gas[k].vertices[j] - gas[k].centroid;
      p.vertices[j] = c + Eigen::Vector2d(cs * w.x() - sn * w.y(), sn * w.x() + cs * w.y());
    }
    p.centroid = c;
    p.orientation = std::remainder(p.orientation + angle, 2 * std::numbers::pi);
  }

  // The exact checks decide; a few violators are placed again by random trials in the gaps.
  RepairResult checked =
      check_and_repair(mould, draws, std::move(final_state), controls, max_replaced, rng);
  if (!checked.success) {
    result.area_fraction_reached = checked.valid_area / mould.area();
    result.message = "compaction reached the mould but " + checked.message +
                     "; area fraction validly placed " + fraction(result.area_fraction_reached) +
                     " of " + fraction(target);
    return result;
  }
  result.success = true;
  result.placed = std::move(checked.placed);
  result.replaced = checked.violators;
  result.area_fraction_reached = target;
  result.message = "compacted " + std::to_string(draws.size()) + " aggregates to area fraction " +
                   fraction(target) + " in " + std::to_string(result.steps) + " Box2D steps" +
                   (result.replaced ? "; " + std::to_string(result.replaced) +
                                          " placed again after the exact check"
                                    : std::string());
  return result;
}

}  // namespace cdem::mesogen
