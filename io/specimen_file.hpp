#pragma once
// Reading and writing the HDF5 specimen file (schema: docs/specimen_file.md).
#include <filesystem>

#include "core/specimen.hpp"

namespace cdem {

// Writes atomically: the file appears complete or not at all.
void write_specimen(const Specimen& specimen, const std::filesystem::path& path);
// Throws InputError naming the file and the missing or malformed dataset.
Specimen read_specimen(const std::filesystem::path& path);

}  // namespace cdem
