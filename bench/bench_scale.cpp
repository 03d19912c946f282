// The scale benchmark of issue 18: the C30 bonded world of a specimen file of any size, under
// platen loading, timed per disc-step, with the solver's memory per disc measured twice: as the
// resident size the process gains while it builds the world and runs its first steps
// (/proc/self/statm), and as the sum of the engine's array capacities (dem/memory_footprint.hpp),
// by what they grow with. The two agree when the accounting misses no array.
//
// The world is built as a uniaxial test builds it (floating mortar discs removed, the bonds of
// samples/c30_materials.toml or of the flat-joint table installed on every contact, two platens
// overhanging the specimen by a quarter of its width each side, moving at 0.02 m/s each), without
// the genesis relaxation: the step costs the same with or without it (every bond stays intact
// while timing: `bonds_broken` says so), and at 10^6 discs it would cost more than the timing.
//
//   build/bin/bench_scale SPECIMEN.h5 [--steps N] [--repeats R] [--warmup N] [--threads T]
//                         [--law 0|1] [--tile NX NY] [--order auto|specimen|spatial]
//                         [--pair-results records|every]
//
// --tile NX NY places NX x NY copies of the specimen side by side (clumps and all) before the
// world is built: a large world from a small generated section, for when generating the large
// one would take longer than the benchmark (docs/performance.md "Scale"). --order numbers the
// world's bodies as dem/world_from_specimen.hpp's BodyOrder (default auto, as a lab test does).
// --pair-results: the timed steps keep the per-pair results only at the end of each repeat, as
// a lab test's loading keeps them only at its records (records, the default), or every step.
#include <malloc.h>

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <exception>
#include <filesystem>
#include <fstream>
#include <numeric>
#include <string>
#include <vector>

#include "core/resident_size.hpp"
#include "dem/bond_installation.hpp"
#include "dem/memory_footprint.hpp"
#include "dem/world_from_specimen.hpp"
#include "io/specimen_file.hpp"
#include "lab/material_genesis.hpp"
#include "lab/material_table.hpp"

namespace {

namespace fs = std::filesystem;
using cdem::dem::World;

constexpr double kPlatenVelocity = 0.02;  // m/s, each platen (SPEC 8)
constexpr double kPlatenOverhang = 0.25;  // platens reach this fraction of the width beyond
                                          // each side (lab_test default)
const char* const kMaterials[] = {"samples/c30_materials.toml",
                                  "samples/materials/c30_flat_joint.toml"};

struct Options {
  fs::path specimen;
  long steps = 200;  // cycles per timed repeat
  int repeats = 3;   // timed repeats; the median is reported
  long warmup = 20;  // cycles before the memory is measured and the timing starts
  int threads = 1;
  int law = 0;  // 0 = parallel bonds, 1 = flat joints (kMaterials)
  int tile_x = 1, tile_y = 1;
  cdem::dem::BodyOrder order = cdem::dem::BodyOrder::Automatic;
  bool pair_results_every_step = false;
};

[[noreturn]] void usage_error(const std::string& what) {
  std::fprintf(stderr,
               "bench_scale: %s\nusage: bench_scale SPECIMEN.h5 [--steps N >= 1] [--repeats R "
               ">= 1] [--warmup N >= 1] [--threads 1..64] [--law 0|1] [--tile NX NY, 1..100 "
               "each] [--order auto|specimen|spatial] [--pair-results records|every]\n",
               what.c_str());
  std::exit(2);
}

// The integer after argv[i] (i moves onto it), for option `key`, within [lo, hi].
long integer_argument(const std::string& key, int argc, char** argv, int& i, long lo, long hi) {
  if (i + 1 >= argc) usage_error(key + " needs a value");
  const std::string text = argv[++i];
  char* end = nullptr;
  const long value = std::strtol(text.c_str(), &end, 10);
  if (text.empty() || *end != '\0' || value < lo || value > hi)
    usage_error(key + " = '" + text + "': an integer in [" + std::to_string(lo) + ", " +
                std::to_string(hi) + "] is needed");
  return value;
}

Options parse(int argc, char** argv) {
  Options o;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--steps")
      o.steps = integer_argument(a, argc, argv, i, 1, 1'000'000);
    else if (a == "--repeats")
      o.repeats = static_cast<int>(integer_argument(a, argc, argv, i, 1, 100));
    else if (a == "--warmup")
      o.warmup = integer_argument(a, argc, argv, i, 1, 1'000'000);
    else if (a == "--threads")
      o.threads = static_cast<int>(integer_argument(a, argc, argv, i, 1, 64));
    else if (a == "--law")
      o.law = static_cast<int>(integer_argument(a, argc, argv, i, 0, 1));
    else if (a == "--tile") {
      o.tile_x = static_cast<int>(integer_argument(a, argc, argv, i, 1, 100));
      o.tile_y = static_cast<int>(integer_argument(a, argc, argv, i, 1, 100));
    } else if (a == "--order") {
      if (i + 1 >= argc) usage_error(a + " needs a value");
      const std::string v = argv[++i];
      if (v == "auto")
        o.order = cdem::dem::BodyOrder::Automatic;
      else if (v == "specimen")
        o.order = cdem::dem::BodyOrder::Specimen;
      else if (v == "spatial")
        o.order = cdem::dem::BodyOrder::Spatial;
      else
        usage_error(a + " = '" + v + "': auto, specimen or spatial");
    } else if (a == "--pair-results") {
      if (i + 1 >= argc) usage_error(a + " needs a value");
      const std::string v = argv[++i];
      if (v != "records" && v != "every") usage_error(a + " = '" + v + "': records or every");
      o.pair_results_every_step = v == "every";
    } else if (a.rfind("--", 0) == 0)
      usage_error("unknown option " + a);
    else if (o.specimen.empty())
      o.specimen = a;
    else
      usage_error("one specimen file only (got '" + o.specimen.string() + "' and '" + a + "')");
  }
  if (o.specimen.empty()) usage_error("no specimen file given");
  if (!fs::is_regular_file(o.specimen))
    usage_error("specimen file '" + o.specimen.string() + "' does not exist");
  return o;
}

std::string load_average() {
  std::ifstream f("/proc/loadavg");
  std::string one, five, fifteen;
  f >> one >> five >> fifteen;
  return one + " " + five + " " + fifteen;
}

double cpu_seconds() {
  timespec t{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

// nx x ny copies of `s` side by side: copy (a, b) is shifted by (a width, b height), its clump
// indices by the clumps of the copies before it. The mould is the whole tiled rectangle.
cdem::Specimen tiled(const cdem::Specimen& s, int nx, int ny) {
  if (nx == 1 && ny == 1) return s;
  cdem::Specimen out;
  out.container = s.container;
  out.container.width *= nx;
  out.container.height *= ny;
  out.mortar_density = s.mortar_density;
  out.aggregate_density = s.aggregate_density;
  out.attributes = s.attributes;
  for (int b = 0; b < ny; ++b)
    for (int a = 0; a < nx; ++a) {
      const double dx = a * s.container.width, dy = b * s.container.height;
      const auto clump_offset = static_cast<std::int32_t>(out.clumps.size());
      for (std::size_t i = 0; i < s.disc_count(); ++i) {
        out.x.push_back(s.x[i] + dx);
        out.y.push_back(s.y[i] + dy);
        out.r.push_back(s.r[i]);
        out.clump.push_back(s.clump[i] < 0 ? -1 : s.clump[i] + clump_offset);
        out.contact_active.push_back(s.contact_active[i]);
      }
      for (cdem::Clump c : s.clumps) {
        for (auto& v : c.vertices) v += Eigen::Vector2d(dx, dy);
        c.centroid += Eigen::Vector2d(dx, dy);
        out.clumps.push_back(std::move(c));
      }
    }
  return out;
}

void add_platens(World& w) {
  const auto& d = w.discs();
  double xmin = 1e300, xmax = -1e300, ymin = 1e300, ymax = -1e300;
  for (std::size_t i = 0; i < d.size(); ++i) {
    xmin = std::min(xmin, d.x[i] - d.r[i]);
    xmax = std::max(xmax, d.x[i] + d.r[i]);
    ymin = std::min(ymin, d.y[i] - d.r[i]);
    ymax = std::max(ymax, d.y[i] + d.r[i]);
  }
  const double over = kPlatenOverhang * (xmax - xmin);
  const int bottom = w.add_wall(xmin - over, ymin, xmax + over, ymin);
  const int top = w.add_wall(xmax + over, ymax, xmin - over, ymax);
  w.set_wall_velocity(bottom, 0, kPlatenVelocity);
  w.set_wall_velocity(top, 0, -kPlatenVelocity);
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  const std::size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

void print_footprint(const cdem::dem::MemoryFootprint& m, double discs, double pairs,
                     double bodies) {
  const auto row = [&](const char* name, std::size_t bytes, const char* per, double count) {
    std::printf("  %-14s %12.0f B  %7.1f B/disc", name, static_cast<double>(bytes),
                static_cast<double>(bytes) / discs);
    if (per) std::printf("  %7.1f B/%s", static_cast<double>(bytes) / count, per);
    std::printf("\n");
  };
  row("bodies", m.bodies, "body", bodies);
  row("discs", m.discs, nullptr, 0);
  row("pairs", m.pairs, "pair", pairs);
  row("wall_pairs", m.wall_pairs, nullptr, 0);
  row("joints", m.joints, nullptr, 0);
  row("merge_scratch", m.merge_scratch, "pair", pairs);
  row("neighbor_list", m.neighbor_list, nullptr, 0);
  row("thread_plan", m.thread_plan, nullptr, 0);
  row("other", m.other, nullptr, 0);
  row("total", m.total(), nullptr, 0);
}

// How many of the arrays a step walks at one index start at the same offset within a 4 KB page
// (the same L1 set for the same index; dem/staggered_array.hpp): the most that share one.
int most_at_one_page_offset(const World& w) {
  const auto& b = w.bodies();
  const auto& d = w.discs();
  const auto& c = w.contacts();
  const auto& f = w.pair_forces();
  const void* arrays[] = {b.x.data(),
                          b.y.data(),
                          b.theta.data(),
                          b.vx.data(),
                          b.vy.data(),
                          b.omega.data(),
                          b.fx.data(),
                          b.fy.data(),
                          b.moment.data(),
                          b.inv_mass_dyn.data(),
                          b.inv_inertia_dyn.data(),
                          b.first_disc.data(),
                          b.is_clump.data(),
                          b.prescribed.data(),
                          d.state.data(),
                          d.load.data(),
                          c.first.data(),
                          c.second.data(),
                          c.contact_class.data(),
                          c.state.shear_force.data(),
                          c.state.bond.data(),
                          c.state.bond_normal.data(),
                          c.state.bond_shear.data(),
                          c.state.bond_moment.data(),
                          f.normal.data(),
                          f.overlap.data(),
                          f.fx.data(),
                          f.fy.data()};
  std::vector<int> count(4096 / 64, 0);
  for (const void* p : arrays) ++count[(reinterpret_cast<std::uintptr_t>(p) % 4096) / 64];
  return *std::max_element(count.begin(), count.end());
}

int run(const Options& o) {
  using namespace cdem::dem;
  using namespace cdem::lab;
  std::printf("load average at start: %s\n", load_average().c_str());
  const cdem::Specimen source = cdem::read_specimen(o.specimen);
  WorldSettings settings;
  read_material_table(fs::path(CDEM_SOURCE_DIR) / kMaterials[o.law]).apply(settings);
  settings.threads = o.threads;
  GenesisOptions genesis;
  GenesisReport report;
  // The floating discs are removed from the generated specimen, before it is tiled: at a seam
  // between copies, each side lay against its mould wall, and without the wall the removal
  // peels the copies from their seams inwards (36 passes and 11.8 % of the mortar on C30 tiled
  // 9 x 5, against 1 pass and 4.9 % for the specimen alone).
  const cdem::Specimen cleaned =
      tiled(remove_floating_discs(source, settings, genesis, report), o.tile_x, o.tile_y);
  const cdem::Specimen& specimen = cleaned;
  // The resident size measures the world only if what was freed before is given back and every
  // array of the world is mapped afresh: glibc otherwise raises its mmap threshold after the
  // floating removal's world is freed and serves the new world from heap pages still resident
  // (the growth then read 190 B per disc against 606 accounted on C30).
  mallopt(M_MMAP_THRESHOLD, 128 * 1024);
  malloc_trim(0);
  const double resident_before = cdem::resident_bytes();
  const double cpu_build = cpu_seconds();
  World w = world_from_specimen(cleaned, settings, nullptr, o.order);
  BondInstallation installation;
  installation.gap_ratio = genesis.bond_gap_ratio;
  const long bonds = install_bonds(w, installation).total();
  add_platens(w);
  // Two forced neighbour rebuilds: the contact store's merge buffers and the lists reach their
  // working size (a run rebuilds every few hundred steps).
  for (int rebuild = 0; rebuild < 2; ++rebuild) {
    w.invalidate_neighbors();
    w.step();
  }
  w.cycle(o.warmup);
  const double build_cpu_s = cpu_seconds() - cpu_build;
  const double resident_growth = cdem::resident_bytes() - resident_before;
  const MemoryFootprint footprint = memory_footprint(w);

  const double discs = static_cast<double>(w.discs().size());
  const double pairs = static_cast<double>(w.contacts().keys.size());
  const double bodies = static_cast<double>(w.bodies().size());
  std::printf(
      "specimen %s (%ld discs, %ld floating removed) tiled %d x %d: %zu discs, %zu "
      "clumps, mould %.1f x %.1f mm\n",
      o.specimen.c_str(), report.discs_in_specimen, report.floating_removed, o.tile_x, o.tile_y,
      specimen.disc_count(), specimen.clumps.size(), 1e3 * specimen.container.width,
      1e3 * specimen.container.height);
  std::printf(
      "world: %.0f discs, %.0f bodies, %.0f candidate pairs "
      "(%.3f per disc), %ld bonds (%s), dt %.4g ns, threads %d, per-pair results %s\n",
      discs, bodies, pairs, pairs / discs, bonds,
      o.law == 0 ? "parallel bonds" : "flat-joint elements", w.time_step() * 1e9, o.threads,
      o.pair_results_every_step ? "every step" : "at the end of each repeat");
  std::printf("build (world, bonds, 2 + %ld warm-up steps): %.2f s CPU\n", o.warmup, build_cpu_s);
  std::printf("memory, resident growth over the build: %.0f B, %.1f B/disc\n", resident_growth,
              resident_growth / discs);
  std::printf("memory, accounted (array capacities):    %.0f B, %.1f B/disc\n",
              static_cast<double>(footprint.total()),
              static_cast<double>(footprint.total()) / discs);
  print_footprint(footprint, discs, pairs, bodies);
  std::printf("arrays of the step (30) starting in one cache line of a page: at most %d\n",
              most_at_one_page_offset(w));

  std::vector<double> cpu_ns, wall_ns;
  w.set_pair_results_on_request(!o.pair_results_every_step);
  for (int r = 0; r < o.repeats; ++r) {
    const double c0 = cpu_seconds();
    const auto t0 = std::chrono::steady_clock::now();
    w.cycle(o.steps - 1);
    w.request_pair_results();
    w.step();
    const std::chrono::duration<double> wall = std::chrono::steady_clock::now() - t0;
    const double disc_steps = discs * static_cast<double>(o.steps);
    cpu_ns.push_back(1e9 * (cpu_seconds() - c0) / disc_steps);
    wall_ns.push_back(1e9 * wall.count() / disc_steps);
    std::printf("repeat %d: %ld steps, %.2f ns CPU and %.2f ns wall per disc-step\n", r + 1,
                o.steps, cpu_ns.back(), wall_ns.back());
  }
  std::printf("bonds broken while timing: %zu\n", w.cracks().size());
  const MemoryFootprint after = memory_footprint(w);
  std::printf(
      "memory after timing: resident growth %.1f B/disc, accounted %.1f B/disc, %.0f "
      "candidate pairs (%.3f per disc), %ld neighbour builds\n",
      (cdem::resident_bytes() - resident_before) / discs,
      static_cast<double>(after.total()) / discs, static_cast<double>(w.contacts().keys.size()),
      static_cast<double>(w.contacts().keys.size()) / discs, w.neighbors().build_count);
  print_footprint(after, discs, static_cast<double>(w.contacts().keys.size()), bodies);
  std::printf("load average at end: %s\n", load_average().c_str());
  std::printf(
      "RESULT discs %.0f pairs_per_disc %.3f ns_cpu %.2f ns_wall %.2f "
      "resident_B_per_disc %.1f accounted_B_per_disc %.1f order %s\n",
      discs, pairs / discs, median(cpu_ns), median(wall_ns), resident_growth / discs,
      static_cast<double>(footprint.total()) / discs,
      resolve_body_order(specimen, o.order) == BodyOrder::Spatial ? "spatial" : "specimen");
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  const Options options = parse(argc, argv);
  try {
    return run(options);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "bench_scale: %s: %s\n", options.specimen.c_str(), e.what());
    return 1;
  }
}
