#pragma once
// The smooth joints of a lab test as the result file records them (docs/result_file.md
// "/joints"): each set's lines cut to the specimen, and per joint its pair and its state (bonded
// or broken, how and when it broke, its forces) at a given moment of the run.
#include <cstdint>
#include <vector>

#include "dem/crack_log.hpp"
#include "dem/smooth_joint_install.hpp"
#include "dem/world.hpp"

namespace cdem::lab {

using namespace cdem::dem;  // the engine the lab layer drives

// The state of every smooth joint of a world, in the order of its entries
// (ContactStore::smooth_joints, so index e is the joint InstalledJoints::touching[e] describes).
struct JointStates {
  std::vector<std::int32_t> first, second;  // the two world discs (first < second)
  std::vector<std::int32_t> set;            // its [[test.joints]] set, 0 ..
  std::vector<double> nx, ny;               // joint unit normal, from first's side to second's
  std::vector<double> area;                 // m^2, A = 2 lambda min(R1, R2) t
  std::vector<std::uint8_t> bonded;         // 1 while its bond is intact
  std::vector<std::int32_t> mode;           // its failure: 0 none, 1 tension, 2 shear
  std::vector<double> time;                 // s, loading time of the failure, -1 none
  std::vector<double> gap;                  // m, opening along nj since installation
  std::vector<double> normal_force;         // N per m, on `second` along nj, compression positive
  std::vector<double> shear_force;          // N per m, on `second` along tj = (-ny, nx)

  std::size_t size() const { return set.size(); }
  // first, second of every joint, interleaved (n x 2, row-major).
  std::vector<std::int32_t> pairs() const;
};

// The joints of `world` now. `cracks` is the crack log whose times are loading times plus
// `time0` (s): the world's own log with the loading's start, or a result's with 0.
JointStates joint_states(const World& world, const std::vector<Crack>& cracks, double time0);

// The lines of every set of `installed`, set by set: x1, y1, x2, y2 per line (m) in `ends`, the
// line's set in `set`.
void joint_line_table(const InstalledJoints& installed, std::vector<double>& ends,
                      std::vector<std::int32_t>& set);

// The joint lines of `installed` cut to the box [xmin, xmax] x [ymin, ymax] (m); a line that
// misses the box is dropped.
void clip_joint_lines(InstalledJoints& installed, double xmin, double ymin, double xmax,
                      double ymax);

}  // namespace cdem::lab
