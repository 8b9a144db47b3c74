#pragma once
// The radiosity library's public API in one include: load a scene, compute light transport,
// write images. See examples/render_scene.cpp for a complete program.

#include <radiosity/atomic_file.h>
#include <radiosity/cache_directory.h>
#include <radiosity/error.h>
#include <radiosity/ies_profile.h>
#include <radiosity/image.h>
#include <radiosity/kernel_timing.h>
#include <radiosity/message_text.h>
#include <radiosity/object_radiometry.h>
#include <radiosity/patch_radiosity.h>
#include <radiosity/path_tracer.h>
#include <radiosity/placed_objects.h>
#include <radiosity/process_memory.h>
#include <radiosity/progress.h>
#include <radiosity/radiosity_engine.h>
#include <radiosity/radiosity_method.h>
#include <radiosity/relighter.h>
#include <radiosity/relighting.h>
#include <radiosity/run_stats.h>
#include <radiosity/scene.h>
#include <radiosity/scene_builder.h>
#include <radiosity/scene_loader.h>
#include <radiosity/sensors.h>
#include <radiosity/solution_file.h>
#include <radiosity/solver_settings.h>
#include <radiosity/surface_radiance.h>
#include <radiosity/surface_solution.h>
#include <radiosity/types.h>
#include <radiosity/version.h>
#include <radiosity/voxel_radiosity.h>
