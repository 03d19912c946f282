#pragma once
// The specimen: what mesogen/ produces and dem/ consumes (docs/specimen_file.md has the HDF5
// schema). All quantities SI, 2D with unit thickness (masses in kg per 1 m of thickness).
#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include <Eigen/Core>

namespace cdem {

enum class ContainerShape : int { Rectangle = 0, Disc = 1 };

// The mould. A rectangle spans [0, width] x [0, height]; a disc of diameter D is centred at
// (D/2, D/2). y is the vertical (loading) axis. A notched beam is a rectangle with a notch: a
// void [width/2 - notch_width/2, width/2 + notch_width/2] x [0, notch_depth] cut at mid-span
// from the bottom edge, which holds no disc and no aggregate (docs/generator.md "Beam").
struct Container {
  ContainerShape shape = ContainerShape::Rectangle;
  double width = 0;        // m (rectangle) or diameter (disc)
  double height = 0;       // m (rectangle) or diameter (disc)
  double notch_depth = 0;  // m, a0; 0 = no notch
  double notch_width = 0;  // m, of the notch (meaningful when notch_depth > 0)

  double area() const;  // m^2, of the mould without the notch taken out
  Eigen::Vector2d centre() const { return {0.5 * width, 0.5 * height}; }
  bool notched() const { return notch_depth > 0; }
  // Distance (m) from (x, y) to the notch void, 0 inside it; infinite without a notch.
  double distance_to_notch(double x, double y) const;
};

// One aggregate: a rigid convex polygon whose pebbles are the discs with its clump id.
struct Clump {
  std::vector<Eigen::Vector2d> vertices;  // m, counter-clockwise, world frame
  Eigen::Vector2d centroid{0, 0};         // m
  double mass = 0;                        // kg (per 1 m thickness)
  double inertia = 0;                     // kg m^2 about the centroid (per 1 m thickness)
  double equivalent_diameter = 0;         // m, 2 sqrt(area / pi)
  int bin = 0;                            // index of the gradation bin it was drawn from
};

enum class DiscTag : std::uint8_t { Mortar = 0, Aggregate = 1 };

struct Specimen {
  Container container;
  // Discs, structure of arrays.
  std::vector<double> x, y, r;      // m
  std::vector<std::int32_t> clump;  // -1 for mortar, else index into clumps
  std::vector<std::uint8_t>
      contact_active;  // 0 for pebbles too deep inside a clump to touch anything
  std::vector<Clump> clumps;
  double mortar_density = 2000;     // kg/m3
  double aggregate_density = 2650;  // kg/m3
  // Provenance: generation inputs, seed, cdem version, and measured packing figures.
  std::map<std::string, std::string> attributes;

  std::size_t disc_count() const { return r.size(); }
  DiscTag tag(std::size_t i) const { return clump[i] < 0 ? DiscTag::Mortar : DiscTag::Aggregate; }
};

}  // namespace cdem
