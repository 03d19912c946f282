#pragma once
// Small helpers shared by cdem's HDF5 files (specimen, lab-test results): native types,
// string and scalar attributes, and datasets with their units.
#include <H5Cpp.h>

#include <cerrno>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "core/input_error.hpp"
#include "io/atomic_output.hpp"

namespace cdem::hdf5 {

template <class T>
const H5::PredType& type_of();
template <>
inline const H5::PredType& type_of<double>() {
  return H5::PredType::NATIVE_DOUBLE;
}
template <>
inline const H5::PredType& type_of<std::int32_t>() {
  return H5::PredType::NATIVE_INT32;
}
template <>
inline const H5::PredType& type_of<std::int64_t>() {
  return H5::PredType::NATIVE_INT64;
}
template <>
inline const H5::PredType& type_of<std::uint8_t>() {
  return H5::PredType::NATIVE_UINT8;
}
template <>
inline const H5::PredType& type_of<std::uint64_t>() {
  return H5::PredType::NATIVE_UINT64;
}

inline void write_string_attr(H5::H5Object& o, const std::string& name, const std::string& value) {
  H5::StrType st(H5::PredType::C_S1, H5T_VARIABLE);
  o.createAttribute(name, st, H5::DataSpace(H5S_SCALAR)).write(st, value);
}

// Object-creation property lists without modification times (HDF5 stores them by default):
// the same specimen and seed must give the same bytes. A file-creation list covers the root
// group.
template <class PropList>
PropList untimed() {
  PropList p;
  H5Pset_obj_track_times(p.getId(), false);
  return p;
}

// cdem's HDF5 files are built in memory (HDF5's core driver without a backing store) and
// written to disk in one piece by save_and_close: a write that fails (disk full, file-size limit)
// is then an error cdem reports, not one inside HDF5's own flush and close, where the C++
// destructors only print it (the file would be renamed into place truncated, with exit 0) and
// HDF5 1.10 crashes closing the file again. `name` only identifies the file in memory.
inline H5::H5File create_file_in_memory(const std::string& name) {
  H5::FileAccPropList fapl;
  fapl.setCore(std::size_t{1} << 20, false);  // grows by 1 MiB, never touches the disk
  fapl.setFcloseDegree(H5F_CLOSE_STRONG);     // closing the file closes what is left open in it
  return H5::H5File(name, H5F_ACC_TRUNC, untimed<H5::FileCreatPropList>(), fapl);
}

// Writes the image of `file` (from create_file_in_memory) to the temporary file of `out` and
// closes the file. Throws RunError naming the target when the disk refuses it.
inline void save_and_close(H5::H5File& file, const AtomicOutput& out) {
  file.flush(H5F_SCOPE_GLOBAL);
  const ssize_t size = H5Fget_file_image(file.getId(), nullptr, 0);
  if (size < 0) throw H5::FileIException("save_and_close", "H5Fget_file_image failed");
  std::vector<char> image(static_cast<std::size_t>(size));
  if (H5Fget_file_image(file.getId(), image.data(), image.size()) != size)
    throw H5::FileIException("save_and_close", "H5Fget_file_image failed");
  file.close();
  std::ofstream disk(out.temp_path(), std::ios::binary);
  disk.write(image.data(), size);
  disk.close();
  if (!disk) throw RunError("cannot write " + out.target().string() + ": " + std::strerror(errno));
}

// A new group `name` in `parent`, untimed.
inline H5::Group create_group(const H5::H5Location& parent, const std::string& name) {
  const H5::PropList gcpl(H5P_GROUP_CREATE);  // a class id: a new list of that class
  H5Pset_obj_track_times(gcpl.getId(), false);
  const hid_t id = H5Gcreate2(parent.getId(), name.c_str(), H5P_DEFAULT, gcpl.getId(), H5P_DEFAULT);
  if (id < 0) throw H5::GroupIException("create_group", "cannot create group " + name);
  H5::Group g(id);  // takes a reference of its own
  H5Idec_ref(id);
  return g;
}

template <class T>
void write_scalar_attr(H5::H5Object& o, const std::string& name, T value) {
  o.createAttribute(name, type_of<T>(), H5::DataSpace(H5S_SCALAR)).write(type_of<T>(), &value);
}

// A dataset of `v`: 1-D, or 2-D row-major with `columns` > 1; `units` and `meaning` become
// string attributes when given.
template <class T>
void write_array(H5::Group& g, const std::string& name, const std::vector<T>& v,
                 const std::string& units = "", const std::string& meaning = "",
                 hsize_t columns = 1) {
  const hsize_t dims[2] = {columns == 1 ? v.size() : v.size() / columns, columns};
  H5::DataSet ds = g.createDataSet(name, type_of<T>(), H5::DataSpace(columns == 1 ? 1 : 2, dims),
                                   untimed<H5::DSetCreatPropList>());
  if (!v.empty()) ds.write(v.data(), type_of<T>());
  if (!units.empty()) write_string_attr(ds, "units", units);
  if (!meaning.empty()) write_string_attr(ds, "meaning", meaning);
  ds.close();  // throws when the data cannot be flushed; the destructor would only print
}

}  // namespace cdem::hdf5
