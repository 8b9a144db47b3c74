#pragma once
// The voxel method behind the method seam (radiosity_method.h): its settings and its model,
// registered as "voxel".

#include <radiosity/radiosity_method.h>

#include <memory>

namespace rad {

std::unique_ptr<RadiosityMethod> makeVoxelMethod();

}  // namespace rad
