#pragma once
// Relighting: the patch solution kept up to date while lights move, dim or switch, at frame
// rate. Form factors depend on the geometry only, so a change of the lights changes only the
// direct light the patches get; the Relighter finds the patches a changed light reaches (a moved
// spot: those of its old and new beam), and shoots the difference of their injected radiosity
// through the form factors it keeps, warm-started from the last solution (progressive
// refinement of the change), until what is left unshot is below its tolerance. Where
// the lights move a beam or shadow edge, the quadtree is refined anew and the rows of its new
// nodes come from the model's master table (cast once, the first time a node is needed).
// After: G. Drettakis and F. Sillion, "Interactive update of global illumination using a
// line-space hierarchy", SIGGRAPH 1997; S. Chen, "Incremental radiosity: an extension of
// progressive radiosity to an interactive image synthesis system", SIGGRAPH 1990.

#include <radiosity/patch_radiosity.h>

#include <cstddef>
#include <cstdint>
#include <memory>
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

class Relighter {
 public:
  /// Solves the model for `lights` (its settings' solver) and keeps what relighting needs: the
  /// form factors of the patches and the light's state. Needs the hemisphere estimator (its
  /// master table makes the rows of a changed quadtree); throws InputError otherwise, and
  /// rad::Cancelled if `progress` returns false. The model must outlive the relighter.
  Relighter(const PatchModel& model, std::span<const Light> lights,
            const RelightSettings& settings = {}, const ProgressCallback& progress = {});
  /// Continues from `solved`, a solution of `model` (one loaded from a solution file: nothing
  /// is solved; the form factors of its patches come from the master table). Throws InputError
  /// as above, and for a solution whose light groups are scaled (one state holds all lights).
  Relighter(const PatchModel& model, PatchRadiosity solved, const RelightSettings& settings = {},
            const ProgressCallback& progress = {});
  ~Relighter();
  Relighter(Relighter&&) noexcept;
  Relighter& operator=(Relighter&&) noexcept;

  /// Brings the solution to `lights` and says what it did. A light is matched to the one at its
  /// place in the last list; with another count every light counts as changed.
  /// `emissionScales`: per scene material, a factor on its emission (a dimmer on glowing
  /// surfaces; empty: the scene's own), shot as a change like the lights'. Throws
  /// std::invalid_argument for a count that is not the scene's materials'.
  /// `shadowCaster`: what shadows the lights' direct light (the scene with its dynamic objects
  /// placed as now; null: the model's scene alone); with one, every light's direct light is
  /// evaluated anew (the objects may have moved).
  const RelightStats& relight(std::span<const Light> lights,
                              std::span<const Color> emissionScales = {},
                              const RayCaster* shadowCaster = nullptr);
  /// The solution for the last lights: the ambient term of progressive refinement stands in
  /// for what is left unshot. Valid until the next relight.
  const PatchRadiosity& solution() const;
  const RelightStats& lastRelight() const;
  /// Writes the model's master form-factor table to its disk cache (when it has one and rows
  /// were cast since it was read or written): relighting does not write it at every change of
  /// the quadtree. A failure is a warning, returned.
  std::string saveFormFactors();

 private:
  struct State;
  void start(PatchRadiosity solved, const RelightSettings& settings);
  std::unique_ptr<State> state_;
};

}  // namespace rad
