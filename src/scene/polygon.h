#pragma once
// Planar polygon geometry used by the scene builder: Newell normals, planarity, ear clipping.

#include <radiosity/types.h>

#include <span>
#include <vector>

namespace rad {

/// Newell's normal: its length is twice the polygon's area, its direction the CCW front side.
Vec3d newellNormal(std::span<const Vec3> corners);

/// Largest distance of a corner from the plane through the centroid with the Newell normal.
double planeDeviation(std::span<const Vec3> corners);

/// Triangulates a simple polygon (convex or concave, CCW about `normal`) by ear clipping.
/// Returns corner-index triples in the polygon's own numbering, each CCW about `normal`.
std::vector<UVec3> triangulatePolygon(std::span<const Vec3> corners, const Vec3d& normal);

}  // namespace rad
