// The extension `cdem._cdem` (pybind11): the generator and the lab tests called in process, with
// the very code `cdem generate` and `cdem run` run. The public API, its docstrings and the
// dict -> TOML conversion are in the pure-Python package (python/cdem/); this file takes TOML
// text or a file path and returns Specimen objects, JSON text and numpy arrays. Errors keep the
// CLI's messages: InputError -> cdem.InputError (a ValueError), RunError and the library errors
// the CLI reports with exit code 3 -> cdem.RunError (a RuntimeError).
#include <H5Cpp.h>
#include <pybind11/functional.h>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <filesystem>
#include <fstream>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include <toml++/toml.h>

#include "apps/lab_specimen.hpp"
#include "core/input_error.hpp"
#include "core/version.hpp"
#include "io/atomic_output.hpp"
#include "io/output_paths.hpp"
#include "io/specimen_file.hpp"
#include "lab/biaxial_test.hpp"
#include "lab/lab_test.hpp"
#include "lab/result_file.hpp"
#include "lab/run_summary.hpp"
#include "mesogen/generate.hpp"

namespace py = pybind11;

namespace cdem::python {

namespace {

// A specimen handed to Python: the model, the generator's summary (JSON text, empty when read
// from a file) and a name for messages and summaries (the file, or "cdem.generate(...)").
struct PySpecimen {
  Specimen specimen;
  std::string summary;
  std::string source;
};

// A read-only numpy array over `values`, kept alive by `owner` (no copy).
template <typename T>
py::array_t<T> view(const std::vector<T>& values, py::handle owner) {
  py::array_t<T> a({static_cast<py::ssize_t>(values.size())}, {static_cast<py::ssize_t>(sizeof(T))},
                   values.data(), owner);
  a.attr("setflags")(py::arg("write") = false);
  return a;
}

// A read-only numpy array holding a copy of `values` (state that outlives the engine's memory).
// `values`: a std::vector, or a field of the discs' records (dem/discs.hpp).
template <typename Array, typename T = typename Array::value_type>
py::array_t<T> copy(const Array& values) {
  py::array_t<T> a(static_cast<py::ssize_t>(values.size()));
  std::copy(values.begin(), values.end(), a.mutable_data());
  a.attr("setflags")(py::arg("write") = false);
  return a;
}

std::string read_text(const std::filesystem::path& file) {
  std::ifstream in(file);
  std::ostringstream text;
  text << in.rdbuf();
  if (!in) throw RunError("cannot read " + file.string());
  return text.str();
}

// Generator input: a file, or TOML text labelled for messages. Generated in memory; written
// (atomically) only when `output` is given.
PySpecimen generate(const std::optional<std::string>& text, const std::optional<std::string>& path,
                    const std::string& label, std::optional<std::uint64_t> seed,
                    const std::optional<std::string>& output, bool verbose) {
  if (path && !std::filesystem::is_regular_file(*path))
    throw InputError(*path, "", "generator file not found");
  const mesogen::GeneratorInput in = mesogen::read_generator_input(
      path ? InputTable::parse_file(*path) : InputTable::parse_string(*text, label));
  std::optional<OutputTransaction> transaction;
  if (output) {
    std::vector<NamedPath> inputs;
    if (path) inputs.push_back({"spec", *path});
    transaction.emplace(check_output_files(inputs, {{"output", *output}}));
  }
  mesogen::GenerateReport report{verbose, {}};
  PySpecimen out{mesogen::generate(in, seed.value_or(in.seed), report), report.summary.dump(),
                 output ? *output : "cdem.generate(" + (path ? *path : label) + ")"};
  if (output) {
    write_specimen(out.specimen, *output);
    transaction->commit();
  }
  return out;
}

// The test input. With a specimen object the test must not name one: an empty inline table
// stands in for it while the file is read (read_lab_test needs one), then the object replaces it.
// `joints` (TOML text of [[test.joints]] tables, from run_test's `joints` argument) is read after
// the test's own text, so its sets follow the test's and it is recorded with the input.
lab::LabTestInput read_test(const std::optional<std::string>& text,
                            const std::optional<std::string>& path, const std::string& label,
                            const std::string& base_dir, const PySpecimen* specimen,
                            const std::optional<std::string>& joints) {
  if (!specimen && !joints) {
    if (path) return lab::read_lab_test(std::filesystem::path(*path));
    return lab::read_lab_test(InputTable::parse_string(*text, label), base_dir);
  }
  std::string source = text ? *text : std::string();
  std::filesystem::path dir = base_dir;
  std::string name = label;
  if (path) {
    if (!std::filesystem::is_regular_file(*path))
      throw InputError(*path, "", "test file not found");
    source = read_text(*path);
    dir = std::filesystem::path(*path).parent_path();
    name = *path;
  }
  if (joints) source += "\n" + *joints;
  if (!specimen) return lab::read_lab_test(InputTable::parse_string(source, name), dir);
  InputTable::parse_string(source, name);  // syntax errors with the CLI's message
  toml::table root = toml::parse(source);
  if (root.contains("specimen"))
    throw InputError(name, "specimen",
                     "given twice: by the test and by the `specimen` argument; drop one");
  root.insert("specimen", toml::table{});
  std::ostringstream with_specimen;
  with_specimen << root << "\n";
  lab::LabTestInput input =
      lab::read_lab_test(InputTable::parse_string(with_specimen.str(), name), dir);
  input.specimen_generator.clear();
  input.specimen_path = specimen->source;
  return input;
}

// The files a run reads (outputs must not replace them): the test file, the specimen file and
// the material file when named.
std::vector<NamedPath> run_inputs(const lab::LabTestInput& input, bool test_is_file,
                                  bool specimen_is_file, const std::filesystem::path& base_dir) {
  std::vector<NamedPath> inputs;
  if (test_is_file) inputs.push_back({"test", input.file});
  if (specimen_is_file) inputs.push_back({"specimen", input.specimen_path});
  if (const auto materials = toml::parse(input.text)["materials"].value<std::string>()) {
    const std::filesystem::path m = *materials;
    inputs.push_back({"materials", m.is_absolute() ? m : base_dir / m});
  }
  return inputs;
}

py::dict history_arrays(const lab::LabHistory& h) {
  py::dict d;
  d["step"] = copy(h.step);
  d["time"] = copy(h.time);
  d["axial_strain"] = copy(h.axial_strain);
  d["lateral_strain"] = copy(h.lateral_strain);
  d["axial_stress"] = copy(h.axial_stress);
  d["confining_stress"] = copy(h.confining_stress);
  d["platen_force"] = copy(h.platen_force);
  d["kinetic_energy"] = copy(h.kinetic_energy);
  d["strain_energy"] = copy(h.strain_energy);
  d["friction_energy"] = copy(h.friction_energy);
  d["breakage_energy"] = copy(h.breakage_energy);
  d["boundary_work"] = copy(h.boundary_work);
  d["bonds_broken"] = copy(h.bonds_broken);
  return d;
}

// One field of every crack as a read-only numpy array.
template <typename T, typename Field>
py::array_t<T> crack_column(const std::vector<dem::Crack>& cracks, Field field) {
  py::array_t<T> a(static_cast<py::ssize_t>(cracks.size()));
  T* out = a.mutable_data();
  for (const dem::Crack& k : cracks) *out++ = static_cast<T>(field(k));
  a.attr("setflags")(py::arg("write") = false);
  return a;
}

// The crack log with the result file's names and codes (docs/result_file.md, /cracks).
py::dict crack_arrays(const std::vector<dem::Crack>& cracks) {
  using dem::Crack;
  py::dict d;
  d["time"] = crack_column<double>(cracks, [](const Crack& k) { return k.time; });
  d["x"] = crack_column<double>(cracks, [](const Crack& k) { return k.x; });
  d["y"] = crack_column<double>(cracks, [](const Crack& k) { return k.y; });
  d["mode"] = crack_column<std::uint8_t>(cracks, [](const Crack& k) { return k.mode; });
  d["class"] = crack_column<std::uint8_t>(cracks, [](const Crack& k) { return k.contact_class; });
  d["first"] = crack_column<std::int32_t>(cracks, [](const Crack& k) { return k.first; });
  d["second"] = crack_column<std::int32_t>(cracks, [](const Crack& k) { return k.second; });
  d["element"] = crack_column<std::int32_t>(cracks, [](const Crack& k) { return k.element; });
  d["energy"] = crack_column<double>(cracks, [](const Crack& k) { return k.energy; });
  d["nx"] = crack_column<double>(cracks, [](const Crack& k) { return k.nx; });
  d["ny"] = crack_column<double>(cracks, [](const Crack& k) { return k.ny; });
  d["half_width"] = crack_column<double>(cracks, [](const Crack& k) { return k.half_width; });
  return d;
}

// The smooth joints of a run with the result file's names and codes (docs/result_file.md,
// /joints): per joint its pair, set and state at the end; the lines of the sets.
py::dict joint_arrays(const lab::LabTestResult& r) {
  const lab::JointStates& s = r.joint_states;
  py::dict d;
  d["first"] = copy(s.first);
  d["second"] = copy(s.second);
  d["set"] = copy(s.set);
  d["touching"] = copy(r.joints.touching);
  d["nx"] = copy(s.nx);
  d["ny"] = copy(s.ny);
  d["area"] = copy(s.area);
  d["bonded"] = copy(s.bonded);
  d["mode"] = copy(s.mode);
  d["failure_time"] = copy(s.time);
  d["gap"] = copy(s.gap);
  d["normal_force"] = copy(s.normal_force);
  d["shear_force"] = copy(s.shear_force);
  std::vector<double> lines;
  std::vector<std::int32_t> line_set;
  lab::joint_line_table(r.joints, lines, line_set);
  py::array_t<double> xy = copy(lines);
  d["lines"] = xy.attr("reshape")(-1, 4);
  d["line_set"] = copy(line_set);
  return d;
}

// The state a callback sees: copies (the engine's arrays die with the run), read-only.
py::dict world_state(const dem::World& world, const lab::LabHistory& h, std::size_t confinement) {
  const dem::Discs& d = world.discs();
  // Per disc and per bonded pair: intact bonds (a flat joint's bonded elements).
  std::vector<std::int32_t> intact(d.size(), 0), bond_first, bond_second, bond_intact;
  const dem::ContactStore& list = world.contacts();
  for (std::size_t k = 0; k < list.keys.size(); ++k) {
    const int n = list.intact_bonds(k);
    if (n == 0) continue;
    intact[static_cast<std::size_t>(list.first[k])] += n;
    intact[static_cast<std::size_t>(list.second[k])] += n;
    bond_first.push_back(list.first[k]);
    bond_second.push_back(list.second[k]);
    bond_intact.push_back(n);
  }
  py::dict s;
  s["step"] = h.step.back();
  s["time"] = h.time.back();
  s["confinement"] = confinement;
  s["x"] = copy(d.x);
  s["y"] = copy(d.y);
  s["vx"] = copy(d.vx);
  s["vy"] = copy(d.vy);
  s["r"] = copy(d.r);
  s["fx"] = copy(d.fx);
  s["fy"] = copy(d.fy);
  s["intact_bonds"] = copy(intact);
  s["bond_first"] = copy(bond_first);
  s["bond_second"] = copy(bond_second);
  s["bond_intact"] = copy(bond_intact);
  s["history"] = history_arrays(h);
  return s;
}

py::dict run_test(const std::optional<std::string>& text, const std::optional<std::string>& path,
                  const std::string& label, const std::string& base_dir,
                  const PySpecimen* specimen_object, std::optional<std::uint64_t> seed,
                  const std::optional<py::function>& callback, long every,
                  const std::optional<std::string>& output,
                  const std::optional<std::string>& summary_path, bool verbose,
                  const std::optional<std::string>& joints) {
  lab::LabTestInput input = read_test(text, path, label, base_dir, specimen_object, joints);
  if (seed) input.seed = *seed;
  const bool biaxial = input.controls.type == lab::LabTestType::Biaxial;
  std::vector<NamedPath> outputs;
  if (output) outputs = lab::ResultFile::outputs("output", *output);
  if (summary_path) outputs.push_back({"summary", *summary_path});
  const std::filesystem::path dir =
      path ? std::filesystem::path(*path).parent_path() : std::filesystem::path(base_dir);
  const bool specimen_is_file = !specimen_object && input.specimen_generator.empty();
  OutputTransaction transaction(
      check_output_files(run_inputs(input, path.has_value(), specimen_is_file, dir), outputs));
  const Specimen specimen =
      specimen_object ? specimen_object->specimen : apps::lab_test_specimen(input, verbose);
  lab::check_specimen_for_test(specimen, input);

  std::optional<lab::ResultFile> result_file;
  if (output) result_file.emplace(*output, input);
  const auto make_hooks = [&](std::size_t confinement) {
    lab::LabTestHooks hooks;
    if (result_file)
      hooks.snapshot = [&result_file](const dem::World& w, long step, double time) {
        result_file->snapshot(w, step, time);
      };
    // At every history record: Ctrl-C (Python's handler only sets a flag while C++ runs), then
    // the callback once `every` loading steps have passed since its last call.
    auto next_call = std::make_shared<long>(every);
    hooks.should_stop = [&callback, every, next_call, confinement](const dem::World& w,
                                                                   const lab::LabHistory& h) {
      if (PyErr_CheckSignals() != 0) throw py::error_already_set();
      if (!callback || h.step.back() < *next_call) return false;
      *next_call = h.step.back() + every;
      return py::bool_((*callback)(world_state(w, h, confinement))).cast<bool>();
    };
    return hooks;
  };

  py::dict out;
  py::list histories, cracks, joint_lists;
  std::string summary;
  if (biaxial) {
    const lab::BiaxialSeries series = lab::run_biaxial_series(specimen, input, [&](std::size_t k) {
      if (result_file) result_file->begin_confinement(k, input.controls.confining_stresses[k]);
      return make_hooks(k);
    });
    if (result_file) result_file->commit(series);
    summary = to_json(lab::make_series_summary(series, input)).dump(2);
    for (const lab::LabTestResult& r : series.runs) {
      histories.append(history_arrays(r.history));
      cracks.append(crack_arrays(r.cracks));
      joint_lists.append(joint_arrays(r));
    }
  } else {
    const lab::LabTestResult result = lab::run_lab_test(specimen, input, make_hooks(0));
    if (result_file) result_file->commit(result);
    summary = to_json(lab::make_run_summary(result, input)).dump(2);
    histories.append(history_arrays(result.history));
    cracks.append(crack_arrays(result.cracks));
    joint_lists.append(joint_arrays(result));
  }
  if (summary_path) write_text_atomically(*summary_path, summary + "\n");
  transaction.commit();
  out["summary"] = summary;
  out["histories"] = histories;
  out["cracks"] = cracks;
  out["joints"] = joint_lists;
  return out;
}

}  // namespace

}  // namespace cdem::python

PYBIND11_MODULE(_cdem, m) {
  using cdem::python::PySpecimen;
  using cdem::python::view;
  m.doc() = "cdem's C++ core; use the package `cdem` (docs/python.md)";
  m.attr("__version__") = cdem::kVersion;
  H5::Exception::dontPrint();  // errors are reported once, from the exception

  static py::exception<cdem::InputError> input_error(m, "InputError", PyExc_ValueError);
  static py::exception<cdem::RunError> run_error(m, "RunError", PyExc_RuntimeError);
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const cdem::InputError& e) {
      input_error(e.what());
    } catch (const cdem::RunError& e) {
      run_error(e.what());
    } catch (const H5::Exception& e) {
      run_error(("HDF5 error in " + e.getFuncName() + ": " + e.getDetailMsg()).c_str());
    } catch (const std::filesystem::filesystem_error& e) {
      run_error(e.what());
    }
  });

  py::class_<PySpecimen> specimen(
      m, "Specimen",
      "A generated specimen (cdem.generate, cdem.load_specimen): discs as read-only numpy views "
      "(SI units), the mould, the aggregates and the generator's summary. len() is the disc "
      "count.");
  // A read-only numpy view of one per-disc array of the specimen, kept alive by the object.
  const auto disc_array = [&specimen](const char* name, auto member, const char* doc) {
    specimen.def_property_readonly(
        name, [member](py::object s) { return view(s.cast<PySpecimen&>().specimen.*member, s); },
        doc);
  };
  disc_array("x", &cdem::Specimen::x, "Disc centres, x (m), float64 (n,).");
  disc_array("y", &cdem::Specimen::y, "Disc centres, y (m; the loading axis), float64 (n,).");
  disc_array("r", &cdem::Specimen::r, "Disc radii (m), float64 (n,).");
  disc_array("clump", &cdem::Specimen::clump,
             "Per disc: -1 for mortar, else the index of its aggregate in `clumps`; int32.");
  disc_array("contact_active", &cdem::Specimen::contact_active,
             "Per disc: 0 for pebbles too deep inside an aggregate to touch anything; uint8.");
  specimen
      .def_property_readonly(
          "shape",
          [](const PySpecimen& s) -> std::string {
            return s.specimen.container.shape == cdem::ContainerShape::Disc ? "disc" : "rectangle";
          },
          "The mould: \"rectangle\" ([0, width] x [0, height]) or \"disc\".")
      .def_property_readonly(
          "width", [](const PySpecimen& s) { return s.specimen.container.width; },
          "Mould width (m; the diameter of a disc).")
      .def_property_readonly(
          "height", [](const PySpecimen& s) { return s.specimen.container.height; },
          "Mould height (m; the diameter of a disc).")
      .def_property_readonly(
          "mortar_density", [](const PySpecimen& s) { return s.specimen.mortar_density; }, "kg/m3")
      .def_property_readonly(
          "aggregate_density", [](const PySpecimen& s) { return s.specimen.aggregate_density; },
          "kg/m3")
      .def_property_readonly(
          "clumps",
          [](const PySpecimen& s) {
            py::list clumps;
            for (const cdem::Clump& c : s.specimen.clumps) {
              py::array_t<double> v({static_cast<py::ssize_t>(c.vertices.size()), py::ssize_t{2}});
              auto w = v.mutable_unchecked<2>();
              for (std::size_t i = 0; i < c.vertices.size(); ++i) {
                w(i, 0) = c.vertices[i].x();
                w(i, 1) = c.vertices[i].y();
              }
              py::dict d;
              d["vertices"] = v;
              d["centroid"] = py::make_tuple(c.centroid.x(), c.centroid.y());
              d["mass"] = c.mass;
              d["inertia"] = c.inertia;
              d["equivalent_diameter"] = c.equivalent_diameter;
              d["bin"] = c.bin;
              clumps.append(d);
            }
            return clumps;
          },
          "The aggregates, a list of dicts: vertices ((k, 2) array, m, counter-clockwise), "
          "centroid (m), mass (kg per m of thickness), inertia (kg m, about the centroid), "
          "equivalent_diameter (m), bin (gradation bin).")
      .def_property_readonly(
          "attributes", [](const PySpecimen& s) { return s.specimen.attributes; },
          "Provenance stored with the specimen (generator input, seed, cdem version, figures).")
      .def_property_readonly(
          "summary_json", [](const PySpecimen& s) { return s.summary; },
          "The generator's summary as JSON text (empty for a specimen read from a file).")
      .def_property_readonly(
          "source", [](const PySpecimen& s) { return s.source; },
          "Where the specimen came from: its file, or cdem.generate(<input>).")
      .def(
          "__len__", [](const PySpecimen& s) { return s.specimen.disc_count(); },
          "Number of discs.")
      .def(
          "write",
          [](const PySpecimen& s, const std::string& path) {
            cdem::OutputTransaction transaction(cdem::check_output_files({}, {{"path", path}}));
            cdem::write_specimen(s.specimen, path);
            transaction.commit();
          },
          py::arg("path"),
          "Writes the specimen file (HDF5, docs/specimen_file.md) to `path`, atomically.");

  m.def("generate", &cdem::python::generate, py::arg("text"), py::arg("path"), py::arg("label"),
        py::arg("seed"), py::arg("output"), py::arg("verbose"),
        "Internal: cdem.generate with TOML text or a path (use cdem.generate).");
  m.def(
      "load_specimen",
      [](const std::string& path) {
        return PySpecimen{cdem::read_specimen(path), std::string(), path};
      },
      py::arg("path"), "Internal: use cdem.load_specimen.");
  m.def("run_test", &cdem::python::run_test, py::arg("text"), py::arg("path"), py::arg("label"),
        py::arg("base_dir"), py::arg("specimen"), py::arg("seed"), py::arg("callback"),
        py::arg("every"), py::arg("output"), py::arg("summary"), py::arg("verbose"),
        py::arg("joints"), "Internal: cdem.run_test with TOML text or a path (use cdem.run_test).");
}
