#pragma once
// Pictures of a lab test (cairo PNG): the stress-strain curves (axial and lateral strain
// against the axial stress; three-point bending: the load against deflection and CMOD) and the
// crack map (every bond failure as a dot coloured by mode and contact class, aggregate polygons
// outlined). Written atomically.
#include <filesystem>
#include <vector>

#include "core/specimen.hpp"
#include "lab/lab_test.hpp"

namespace cdem::dem {

void draw_stress_strain_png(const LabHistory& history, LabTestType type,
                            const std::filesystem::path& png, int width_px = 1000,
                            int height_px = 700);

void draw_crack_map_png(const Specimen& specimen, const std::vector<Crack>& cracks,
                        const std::filesystem::path& png, int pixels_long_side = 1200);

}  // namespace cdem::dem
