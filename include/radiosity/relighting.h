#pragma once
// A solution kept up to date while lights move, dim or switch (a method's relighting:
// RadiosityMethod's relight capability), what it is asked to keep to, and what each relight did.

#include <radiosity/light_groups.h>
#include <radiosity/ray_caster.h>
#include <radiosity/scene.h>
#include <radiosity/surface_solution.h>

#include <cstddef>
#include <cstdint>
#include <span>
#include <string>

namespace rad {

struct RelightSettings {
  /// A patch's direct light is brought up to date when it changed by more than this fraction of
  /// the brightest patch's direct light; smaller changes wait, until together they add up to
  /// this fraction of the light put into the scene (then every patch is brought up to date).
  double threshold = 1e-4;
  /// Shooting stops when the unshot power is below this fraction of the light put in (the
  /// ambient term stands in for it; what a relight leaves unshot, the next one shoots, so the
  /// error does not grow from frame to frame). Measured on bench relight's scenarios against
  /// converged fresh solves, the worst patch off by 0.08-0.12% of the mean radiosity at 5e-4
  /// (0.02-0.09% at 2e-4, 0.13-0.14% at 1e-3, with a sweep of the table fewer each step).
  double tolerance = 5e-4;
  /// Relight through the precomputed transfer (the response of every patch to light put into
  /// every patch, T = (I - rho F)^-1: one column per changed patch, no shooting) when the mesh
  /// has at most this many patches and no light refines it (refineLevels 0); it costs 12 N^2
  /// bytes and an N^3 factorization at the start (2,000 patches: 48 MB, 1.6 s on 2 cores, then
  /// 1.0 ms per relight of a swinging spot against 2.2 ms shooting). 0: always shoot.
  size_t transferPatches = 2000;
};

/// What one relight did.
struct RelightStats {
  double milliseconds = 0.0;  ///< the whole relight
  double directMs = 0.0;      ///< the lights' direct light on the patches (and refinement)
  /// The table of a changed quadtree and the state carried over to it (0 when it stayed).
  double formFactorMs = 0.0;
  double bounceMs = 0.0;  ///< shooting the change, and the solution's shading
  size_t patches = 0;
  size_t lightsChanged = 0;
  size_t patchesUpdated = 0;  ///< patches whose direct light was brought up to date
  size_t patchesSkipped = 0;  ///< patches whose direct light changed less than the threshold
  bool meshChanged = false;   ///< the quadtree changed (refined or coarsened somewhere)
  bool reanchored = false;    ///< the changes waiting below the threshold were applied
  size_t rowsComputed = 0, rowsReused = 0;  ///< form-factor rows cast now, kept (mesh change)
  uint64_t shots = 0;                       ///< patches shot
  double unshot = 0.0;                      ///< unshot power left, relative to the light put in
};

/// The solution of a light state, brought to the next one by relight() without a solve.
class Relighting {
 public:
  virtual ~Relighting() = default;
  /// Brings the solution to `lights` and says what it did. A light is matched to the one at its
  /// place in the last list; with another count every light counts as changed.
  /// `emissionScales`: per scene material, a factor on its emission (empty: the scene's own).
  /// `shadowCaster`: what shadows the lights' direct light (the scene with its dynamic objects
  /// placed as now; null: the scene alone).
  virtual const RelightStats& relight(std::span<const Light> lights,
                                      std::span<const Color> emissionScales = {},
                                      const RayCaster* shadowCaster = nullptr) = 0;
  /// The solution for the last lights; valid until the next relight.
  virtual const SurfaceSolution& solution() const = 0;
  /// Writes what relighting computed and a later run could reuse (the patch method: its master
  /// form-factor table) to the model's cache; a failure is a warning, returned ("" when none).
  virtual std::string saveCaches() = 0;
};

}  // namespace rad
