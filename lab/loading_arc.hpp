#pragma once
// The loading arcs of a Brazilian disc (docs/lab_tests.md "Loading arcs"): the boundary discs
// within an arc 2 alpha about the bottom and the top pole of the disc are driven at the platen
// velocity toward the centre, and the load is the sum of the forces the rest of the specimen
// puts on them. Unlike a platen or a jaw, whose contact with a discrete boundary takes in more
// discs as it presses in, the loaded set is fixed by the geometry at the start of loading: the
// arc of the flattened Brazilian disc and of the ISRM jaws, held at one width.
#include <cstdint>
#include <vector>

#include "dem/world.hpp"

namespace cdem::lab {

using namespace cdem::dem;  // the engine the lab layer drives

// The disc specimen's circle: centre and radius, m.
struct DiscCircle {
  double xc = 0, yc = 0;
  double radius = 0;
};

// The bodies of the two arcs, each in increasing body index.
struct LoadingArcBodies {
  std::vector<std::int32_t> bottom, top;
};

// A disc lies on a loading arc when its centre is within half_angle (rad) of the pole's
// direction as seen from the circle's centre, and it is a boundary disc: its outer edge reaches
// within its own radius of the circle (|c_i - c| + r_i >= R - r_i), which takes the outermost
// layer of a packing cut by a round mould and none of the layer under it. A body (a clump
// reaching into the arc too) is driven whole when any of its active discs lies on the arc.
LoadingArcBodies loading_arc_bodies(const World& world, const DiscCircle& circle,
                                    double half_angle);

}  // namespace cdem::lab
