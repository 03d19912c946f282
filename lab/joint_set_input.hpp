#pragma once
// The joint sets of a lab test, `[[test.joints]]` tables (docs/smooth_joint.md): each gives its
// lines (dip_deg + spacing_mm [+ offset_mm], or points_mm = [[x1, y1], [x2, y2]]) and its
// smooth-joint properties, units in the keys. Every failure is an InputError naming the file,
// the key and the allowed range.
#include <string>
#include <vector>

#include "dem/smooth_joint_install.hpp"
#include "io/input_table.hpp"

namespace cdem::lab {

using namespace cdem::dem;  // the engine the lab layer drives

// Reads `joints` of the [test] table `test` (none: an empty list).
std::vector<JointSet> read_joint_sets(const InputTable& test);

// Installs the sets on the world (install_smooth_joints) and returns what it installed; throws
// InputError naming `file` and the set's key when a set crosses no bonded or touching pair (its
// lines miss the specimen).
InstalledJoints install_test_joints(World& world, const std::vector<JointSet>& sets,
                                    double gap_ratio, const std::string& file);

}  // namespace cdem::lab
