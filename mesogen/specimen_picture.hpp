#pragma once
#include <filesystem>
#include "core/specimen.hpp"
namespace cdem::mesogen {
void draw_specimen_png(const cdem::Specimen& specimen, const std::filesystem::path& png,
                       int pixels_long_side = 1600);
}
