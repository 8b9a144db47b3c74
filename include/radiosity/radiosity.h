#pragma once
// The radiosity library's public API in one include: load a scene, compute light transport,
// write images. See examples/render_scene.cpp for a complete program.

#include <radiosity/error.h>
#include <radiosity/ies_profile.h>
#include <radiosity/image.h>
#include <radiosity/object_radiometry.h>
#include <radiosity/path_tracer.h>
#include <radiosity/progress.h>
#include <radiosity/scene.h>
#include <radiosity/scene_builder.h>
#include <radiosity/scene_loader.h>
#include <radiosity/surface_radiance.h>
#include <radiosity/types.h>
#include <radiosity/version.h>
#include <radiosity/voxel_radiosity.h>
