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
#include <radiosity/relighting.h>

#include <cstddef>
#include <cstdint>
#include <memory>
#include <span>
#include <string>

namespace rad {

class Relighter : public Relighting {
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
  ~Relighter() override;
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
                              const RayCaster* shadowCaster = nullptr) override;
  /// The solution for the last lights: the ambient term of progressive refinement stands in
  /// for what is left unshot. Valid until the next relight.
  const PatchRadiosity& solution() const override;
  const RelightStats& lastRelight() const;
  /// Writes the model's master form-factor table to its disk cache (when it has one and rows
  /// were cast since it was read or written): relighting does not write it at every change of
  /// the quadtree. A failure is a warning, returned.
  std::string saveFormFactors();
  std::string saveCaches() override { return saveFormFactors(); }

 private:
  struct State;
  void start(PatchRadiosity solved, const RelightSettings& settings);
  std::unique_ptr<State> state_;
};

}  // namespace rad
