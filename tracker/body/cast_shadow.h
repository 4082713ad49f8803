// The shadow a body casts on the floor under a distant light (the sun, a far lamp), drawn
// into a camera's image. A capsule is the convex hull of its two end spheres, and a
// parallel projection keeps hulls, so its shadow on the floor is the hull of the two
// spheres' shadows: ellipses, the projections along the light of each sphere's great
// circle across the light. A pinhole camera keeps the hull convex, so each part is drawn as
// filled convex polygons, one per 400 mm of its shadow's length (over which a lens's
// distortion bends the edges by under a pixel). As for the silhouettes (silhouette.h), a part whose shadow reaches beyond
// the lens's monotone range or behind the camera is left out (the distortion polynomial
// would fold it back into the image). Where something nearer hides the floor is not known
// here: the drawing is where the shadow would be seen on a bare floor.
#pragma once

#include <vector>

#include <Eigen/Core>
#include <opencv2/core/mat.hpp>

#include "tracker/body/bit_silhouette.h"
#include "tracker/body/body_model.h"
#include "tracker/body/silhouette.h"

namespace jgpm {

// Sets the pixels of `mask` (the camera's size), within `clip`, where the floor, the plane
// y = floor_mm, lies in the shadow of `capsules` under a light from the unit direction
// `light` (towards it; light.y() > 0), as `projector`'s camera sees it: a pixel is in when
// its centre is inside a piece's polygon, as for the bodies' silhouettes.
void DrawCastShadow(const CapsuleProjector& projector, const std::vector<Capsule>& capsules,
                    const Eigen::Vector3d& light, double floor_mm, const cv::Rect& clip, BitMask* mask);

}  // namespace jgpm
