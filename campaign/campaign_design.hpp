#pragma once
// The [design] table of a campaign file turned into design points in natural units, using the
// designs of doe/designs.hpp (coded units) and to_natural.
#include <string>
#include <vector>

#include <Eigen/Dense>

#include "campaign/campaign_spec.hpp"
#include "io/input_table.hpp"

namespace cdem::calib {

// Design types a campaign file may name in `design.type`.
const std::vector<std::string>& campaign_design_types();

// Rows = design points, columns = factors, natural units. Integer factors are not rounded here.
// Throws InputError naming the design key for bad options or a design that cannot hold the
// factors, and for an empty design.
Eigen::MatrixXd campaign_design_points(const InputTable& design,
                                       const std::vector<CampaignFactor>& factors);

}  // namespace cdem::calib
