#include "io/specimen_file.hpp"

#include <H5Cpp.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numbers>
#include <sstream>
#include <stdexcept>

#include "core/input_error.hpp"
#include "core/version.hpp"
#include "io/atomic_output.hpp"
#include "io/hdf5_write.hpp"

namespace cdem {

double Container::area() const {
  return shape == ContainerShape::Disc ? std::numbers::pi * 0.25 * width * width : width * height;
}

double Container::distance_to_notch(double x, double y) const {
  if (!notched()) return std::numeric_limits<double>::infinity();
  const double dx = std::max(std::abs(x - 0.5 * width) - 0.5 * notch_width, 0.0);
  const double dy = std::max(y - notch_depth, std::max(-y, 0.0));
  return std::hypot(dx, dy);
}

namespace {

constexpr const char* kFormat = "cdem-specimen";
constexpr int kFormatVersion = 1;

using hdf5::write_array;
using hdf5::write_scalar_attr;
using hdf5::write_string_attr;
template <class T>
const H5::PredType& h5type() {
  return hdf5::type_of<T>();
}

// Root attributes the file format itself writes; a provenance attribute of the same name would
// make HDF5 fail half-way through the file.
constexpr std::array<const char*, 5> kReservedAttributes = {
    "format", "format_version", "cdem_version", "mortar_density_kg_m3", "aggregate_density_kg_m3"};

// A specimen the reader would reject must not be written: refuse it before touching the disk.
void check_consistent(const Specimen& s) {
  const std::size_t n = s.x.size();
  auto same_length = [n](const char* name, std::size_t size) {
    if (size != n)
      throw std::invalid_argument("write_specimen: discs/" + std::string(name) + " has " +
                                  std::to_string(size) + " entries, discs/x has " +
                                  std::to_string(n));
  };
  same_length("y", s.y.size());
  same_length("r", s.r.size());
  same_length("clump", s.clump.size());
  same_length("contact_active", s.contact_active.size());
  const auto m = static_cast<std::int32_t>(s.clumps.size());
  for (std::size_t i = 0; i < n; ++i)
    if (s.clump[i] < -1 || s.clump[i] >= m)
      throw std::invalid_argument("write_specimen: disc " + std::to_string(i) + " names clump " +
                                  std::to_string(s.clump[i]) + " of " + std::to_string(m));
  for (const char* name : kReservedAttributes)
    if (s.attributes.count(name))
      throw std::invalid_argument("write_specimen: attribute name '" + std::string(name) +
                                  "' is reserved for the file format");
}

struct Reader {
  const std::filesystem::path& path;

  [[noreturn]] void fail(const std::string& what, const std::string& why) const {
    throw InputError(path.string(), what, why);
  }

  template <class T>
  std::vector<T> array(const H5::Group& g, const std::string& name, std::size_t expect_rows,
                       hsize_t cols = 1) const {
    const std::string where = g.getObjName() + "/" + name;
    if (!g.nameExists(name)) fail(where, "dataset missing; not a cdem specimen file?");
    H5::DataSet ds = g.openDataSet(name);
    H5::DataSpace sp = ds.getSpace();
    hsize_t dims[2] = {0, 0};
    const int rank = sp.getSimpleExtentNdims();
    if (rank != (cols == 1 ? 1 : 2)) fail(where, "wrong rank");
    sp.getSimpleExtentDims(dims);
    if (cols != 1 && dims[1] != cols) fail(where, "wrong number of columns");
    if (expect_rows != SIZE_MAX && dims[0] != expect_rows)
      fail(where,
           "has " + std::to_string(dims[0]) + " rows, expected " + std::to_string(expect_rows));
    std::vector<T> v(dims[0] * cols);
    if (!v.empty()) ds.read(v.data(), h5type<T>());
    return v;
  }
  H5::Group group(const H5::H5File& f, const std::string& name) const {
    if (!f.nameExists(name)) fail(name, "group missing; not a cdem specimen file?");
    return f.openGroup(name);
  }
  std::string string_attr(const H5::H5Object& o, const std::string& name) const {
    if (!o.attrExists(name)) fail(name, "attribute missing");
    H5::Attribute a = o.openAttribute(name);
    std::string s;
    a.read(a.getStrType(), s);
    return s;
  }
  template <class T>
  T scalar_attr(const H5::H5Object& o, const std::string& name) const {
    if (!o.attrExists(name)) fail(name, "attribute missing");
    T v{};
    o.openAttribute(name).read(h5type<T>(), &v);
    return v;
  }
};

std::string number(double v) {
  std::ostringstream o;
  o.precision(6);
  o << v;
  return o.str();
}

// Every value the DEM trusts, checked as it comes in: a NaN or a disc far outside the mould
// would otherwise size the neighbour grid from garbage. Positions must lie in the mould grown
// by the disc's own radius (or the clump's equivalent diameter): the generator keeps discs
// inside the mould, and a lab test trims nothing.
void check_values(const Reader& rd, const Specimen& s) {
  const auto positive = [&](const std::string& what, double v) {
    if (!std::isfinite(v) || v <= 0) rd.fail(what, "is " + number(v) + "; must be finite and > 0");
  };
  positive("mortar_density_kg_m3", s.mortar_density);
  positive("aggregate_density_kg_m3", s.aggregate_density);
  positive("container/width_m", s.container.width);
  positive("container/height_m", s.container.height);
  const Container& c = s.container;
  if (c.notch_depth != 0 || c.notch_width != 0) {
    if (c.shape != ContainerShape::Rectangle)
      rd.fail("container/notch_depth_m", "a notch needs a rectangular mould");
    if (!std::isfinite(c.notch_depth) || !(c.notch_depth > 0) || !(c.notch_depth < c.height))
      rd.fail("container/notch_depth_m",
              "is " + number(c.notch_depth) + " m; must be in (0, height)");
    if (!std::isfinite(c.notch_width) || !(c.notch_width > 0) || !(c.notch_width < c.width))
      rd.fail("container/notch_width_m",
              "is " + number(c.notch_width) + " m; must be in (0, width)");
  }
  const auto inside = [&c](const Eigen::Vector2d& p, double margin) {
    if (c.shape == ContainerShape::Disc) return (p - c.centre()).norm() <= 0.5 * c.width + margin;
    return p.x() >= -margin && p.x() <= c.width + margin && p.y() >= -margin &&
           p.y() <= c.height + margin;
  };
  const auto entry = [&](const std::string& what, std::size_t i, const std::string& why) {
    rd.fail(what, "entry " + std::to_string(i) + " " + why);
  };
  for (std::size_t i = 0; i < s.disc_count(); ++i) {
    if (!std::isfinite(s.x[i])) entry("discs/x", i, "is " + number(s.x[i]) + "; must be finite");
    if (!std::isfinite(s.y[i])) entry("discs/y", i, "is " + number(s.y[i]) + "; must be finite");
    if (!std::isfinite(s.r[i]) || s.r[i] <= 0)
      entry("discs/r", i, "is " + number(s.r[i]) + " m; a radius must be finite and > 0");
    if (!inside({s.x[i], s.y[i]}, s.r[i]))
      entry("discs/x, discs/y", i,
            "(disc at x " + number(s.x[i]) + " m, y " + number(s.y[i]) + " m, r " + number(s.r[i]) +
                " m) lies outside the mould (" + number(c.width) + " x " + number(c.height) +
                " m)");
    if (c.distance_to_notch(s.x[i], s.y[i]) == 0)
      entry("discs/x, discs/y", i, "(a disc centre) lies in the notch");
    if (s.contact_active[i] > 1)
      entry("discs/contact_active", i,
            "is " + std::to_string(s.contact_active[i]) + "; must be 0 or 1");
  }
  for (std::size_t k = 0; k < s.clumps.size(); ++k) {
    const Clump& cl = s.clumps[k];
    if (!std::isfinite(cl.mass) || cl.mass <= 0)
      entry("clumps/mass", k, "is " + number(cl.mass) + " kg; must be finite and > 0");
    if (!std::isfinite(cl.inertia) || cl.inertia <= 0)
      entry("clumps/inertia", k, "is " + number(cl.inertia) + " kg m^2; must be finite and > 0");
    if (!std::isfinite(cl.equivalent_diameter) || cl.equivalent_diameter <= 0)
      entry("clumps/equivalent_diameter", k,
            "is " + number(cl.equivalent_diameter) + " m; must be finite and > 0");
    if (!cl.centroid.allFinite() || !inside(cl.centroid, cl.equivalent_diameter))
      entry("clumps/centroid", k, "is not a finite point inside the mould");
    if (cl.vertices.size() < 3) entry("clumps/vertex_offset", k, "gives fewer than 3 vertices");
    for (const auto& v : cl.vertices)
      if (!v.allFinite()) entry("clumps/vertices", k, "(a vertex of this clump) is not finite");
  }
}

}  // namespace

void write_specimen(const Specimen& s, const std::filesystem::path& path) {
  check_consistent(s);
  AtomicOutput out(path);
  H5::Exception::dontPrint();
  // H5::Exception is not a std::exception: translate it, or no caller would catch it. The
  // temporary file is removed by `out` on the way out.
  try {
    H5::H5File f = hdf5::create_file_in_memory(out.temp_path().string());
    write_string_attr(f, "format", kFormat);
    write_scalar_attr<std::int32_t>(f, "format_version", kFormatVersion);
    write_string_attr(f, "cdem_version", kVersion);
    write_scalar_attr<double>(f, "mortar_density_kg_m3", s.mortar_density);
    write_scalar_attr<double>(f, "aggregate_density_kg_m3", s.aggregate_density);
    for (const auto& [k, v] : s.attributes) write_string_attr(f, k, v);

    H5::Group c = hdf5::create_group(f, "container");
    write_string_attr(c, "shape", s.container.shape == ContainerShape::Disc ? "disc" : "rectangle");
    write_scalar_attr<double>(c, "width_m", s.container.width);
    write_scalar_attr<double>(c, "height_m", s.container.height);
    if (s.container.notched()) {  // absent = no notch (and in files older than the beam)
      write_scalar_attr<double>(c, "notch_depth_m", s.container.notch_depth);
      write_scalar_attr<double>(c, "notch_width_m", s.container.notch_width);
    }

    H5::Group d = hdf5::create_group(f, "discs");
    write_array(d, "x", s.x, "m");
    write_array(d, "y", s.y, "m");
    write_array(d, "r", s.r, "m");
    std::vector<std::uint8_t> tag(s.disc_count());
    for (std::size_t i = 0; i < tag.size(); ++i) tag[i] = static_cast<std::uint8_t>(s.tag(i));
    write_array(d, "tag", tag, "", "0 = mortar, 1 = aggregate pebble");
    write_array(d, "clump", s.clump);
    write_array(d, "contact_active", s.contact_active);

    H5::Group g = hdf5::create_group(f, "clumps");
    std::vector<double> centroid, mass, inertia, deq, vertices;
    std::vector<std::int32_t> bin;
    std::vector<std::int64_t> offset{0};
    for (const Clump& k : s.clumps) {
      centroid.insert(centroid.end(), {k.centroid.x(), k.centroid.y()});
      mass.push_back(k.mass);
      inertia.push_back(k.inertia);
      deq.push_back(k.equivalent_diameter);
      bin.push_back(k.bin);
      for (const auto& v : k.vertices) vertices.insert(vertices.end(), {v.x(), v.y()});
      offset.push_back(offset.back() + static_cast<std::int64_t>(k.vertices.size()));
    }
    write_array(g, "centroid", centroid, "m", "", 2);
    write_array(g, "mass", mass, "kg (per m thickness)");
    write_array(g, "inertia", inertia, "kg m^2 (per m thickness), about the centroid");
    write_array(g, "equivalent_diameter", deq, "m");
    write_array(g, "bin", bin);
    write_array(g, "vertex_offset", offset);
    write_array(g, "vertices", vertices, "m", "", 2);
    hdf5::save_and_close(f, out);
  } catch (const H5::Exception& e) {
    throw RunError("cannot write specimen file " + path.string() + " (" + e.getDetailMsg() + ")");
  }
  out.commit();
}

Specimen read_specimen(const std::filesystem::path& path) {
  Reader rd{path};
  if (!std::filesystem::exists(path)) rd.fail("", "file not found");
  H5::Exception::dontPrint();
  try {
    if (!H5::H5File::isHdf5(path.string())) rd.fail("", "not an HDF5 file (corrupt or wrong file)");
    H5::H5File f(path.string(), H5F_ACC_RDONLY);
    if (!f.attrExists("format") || rd.string_attr(f, "format") != kFormat)
      rd.fail("format", "not a cdem specimen file");
    const auto version = rd.scalar_attr<std::int32_t>(f, "format_version");
    if (version != kFormatVersion)
      rd.fail("format_version", "is " + std::to_string(version) + ", this cdem reads " +
                                    std::to_string(kFormatVersion));
    Specimen s;
    s.mortar_density = rd.scalar_attr<double>(f, "mortar_density_kg_m3");
    s.aggregate_density = rd.scalar_attr<double>(f, "aggregate_density_kg_m3");
    for (int i = 0, n = f.getNumAttrs(); i < n; ++i) {
      H5::Attribute a = f.openAttribute(static_cast<unsigned>(i));
      if (a.getTypeClass() == H5T_STRING) {
        std::string v;
        a.read(a.getStrType(), v);
        s.attributes[a.getName()] = v;
      }
    }
    s.attributes.erase("format");
    s.attributes.erase("cdem_version");

    H5::Group c = rd.group(f, "container");
    const std::string shape = rd.string_attr(c, "shape");
    if (shape != "rectangle" && shape != "disc")
      rd.fail("container/shape", "unknown shape '" + shape + "'");
    s.container.shape = shape == "disc" ? ContainerShape::Disc : ContainerShape::Rectangle;
    s.container.width = rd.scalar_attr<double>(c, "width_m");
    s.container.height = rd.scalar_attr<double>(c, "height_m");
    if (c.attrExists("notch_depth_m")) {
      s.container.notch_depth = rd.scalar_attr<double>(c, "notch_depth_m");
      s.container.notch_width = rd.scalar_attr<double>(c, "notch_width_m");
    }

    H5::Group d = rd.group(f, "discs");
    s.x = rd.array<double>(d, "x", SIZE_MAX);
    const std::size_t n = s.x.size();
    s.y = rd.array<double>(d, "y", n);
    s.r = rd.array<double>(d, "r", n);
    s.clump = rd.array<std::int32_t>(d, "clump", n);
    s.contact_active = rd.array<std::uint8_t>(d, "contact_active", n);

    H5::Group g = rd.group(f, "clumps");
    const auto mass = rd.array<double>(g, "mass", SIZE_MAX);
    const std::size_t m = mass.size();
    const auto centroid = rd.array<double>(g, "centroid", m, 2);
    const auto inertia = rd.array<double>(g, "inertia", m);
    const auto deq = rd.array<double>(g, "equivalent_diameter", m);
    const auto bin = rd.array<std::int32_t>(g, "bin", m);
    const auto offset = rd.array<std::int64_t>(g, "vertex_offset", m + 1);
    const auto vertices = rd.array<double>(g, "vertices", SIZE_MAX, 2);
    s.clumps.resize(m);
    for (std::size_t k = 0; k < m; ++k) {
      Clump& cl = s.clumps[k];
      cl.centroid = {centroid[2 * k], centroid[2 * k + 1]};
      cl.mass = mass[k];
      cl.inertia = inertia[k];
      cl.equivalent_diameter = deq[k];
      cl.bin = bin[k];
      if (offset[k] < 0 || offset[k + 1] < offset[k] ||
          static_cast<std::size_t>(offset[k + 1]) * 2 > vertices.size())
        rd.fail("clumps/vertex_offset", "inconsistent with clumps/vertices");
      for (auto v = offset[k]; v < offset[k + 1]; ++v)
        cl.vertices.emplace_back(vertices[2 * v], vertices[2 * v + 1]);
    }
    for (std::size_t i = 0; i < n; ++i)
      if (s.clump[i] < -1 || s.clump[i] >= static_cast<std::int32_t>(m))
        rd.fail("discs/clump", "disc " + std::to_string(i) + " names clump " +
                                   std::to_string(s.clump[i]) + " of " + std::to_string(m));
    check_values(rd, s);
    return s;
  } catch (const H5::Exception& e) {
    rd.fail("", "cannot read HDF5 file (" + e.getDetailMsg() + ")");
  }
}

}  // namespace cdem
