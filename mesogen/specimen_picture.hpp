#pragma once
// A PNG picture of a specimen (for `cdem generate --picture` and for reports): mortar discs light
// grey, aggregate pebbles coloured by their clump's gradation bin, pebbles dropped from contact
// detection paler, aggregate outlines dark, the container outline, and a legend. y points up.
#include <array>
#include <filesystem>
#include <string>
#include <vector>

#include "core/specimen.hpp"

namespace cdem::mesogen {

// Writes atomically (the PNG appears complete or not at all). The image's longer side is
// `pixels_long_side` pixels (200..16000), the other side follows from the container's aspect
// ratio and the legend column on the right. `bin_edges` (m, increasing): the gradation's sieve
// edges, bin k between edges k and k + 1, for the legend (bin_label). Throws
// std::invalid_argument for a bad size or a disc naming a missing clump, RunError when the file
// cannot be written.
void draw_specimen_png(const cdem::Specimen& specimen, const std::filesystem::path& png,
                       int pixels_long_side = 1600, const std::vector<double>& bin_edges = {});

// The legend's name of gradation bin `bin`: its sieve sizes in mm ("aggregate 5-7.5 mm"), or
// "aggregate bin k" when `bin_edges` (m) does not hold the bin (a specimen read from a file).
std::string bin_label(int bin, const std::vector<double>& bin_edges);

// The colour (red, green, blue in 0..1) of aggregate pebbles of a gradation bin: the
// Okabe-Ito qualitative palette (distinguishable with colour-vision deficiencies, and from the
// mortar grey), repeating after 7 bins.
std::array<double, 3> bin_colour(int bin);
// The same colour mixed with white, for pebbles that take no part in contact detection.
std::array<double, 3> inactive_colour(int bin);
// Mortar disc colour.
inline constexpr std::array<double, 3> kMortarColour = {0.82, 0.82, 0.82};

}  // namespace cdem::mesogen
