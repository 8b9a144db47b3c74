#pragma once
// The exact, unoccluded form factor from a differential area to a planar polygon.

#include <radiosity/types.h>

#include <span>

namespace rad {

/// F from the differential area at x (unit normal n) to the polygon (planar, any winding; only
/// its part above x's tangent plane counts). Visibility is not considered. Dimensionless, in
/// [0, 1]; 0 when the polygon's front (the side its CCW winding faces) does not face x.
double pointPolygonFormFactor(const Vec3d& x, const Vec3d& n, std::span<const Vec3d> polygon);

}  // namespace rad
