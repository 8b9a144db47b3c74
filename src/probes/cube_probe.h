#pragma once
// Radiosity mapping for objects that move (after "real-time radiosity II"): a probe looks at the
// static scene from a point through the six 90-degree faces of a cube, each texel the outgoing
// radiance of the static solution seen there (through SurfaceRadiance, so any method's), and a
// vertex near the point takes its irradiance from that view. Three ways, each selectable:
//   Exact    the cosine-weighted sum over every texel with its exact solid angle;
//   Harmonic the view projected once onto order-2 spherical harmonics, then evaluated per normal
//            (R. Ramamoorthi and P. Hanrahan, "An efficient representation for irradiance
//            environment maps", SIGGRAPH 2001): 9 coefficients a channel, constant cost a vertex;
//   Pattern  the published way: texels sampled where the normal meets the cube (see pattern()).
// The lights' own direct light is not in the view (they have no area); it is added per vertex.

#include <radiosity/placed_objects.h>
#include <radiosity/ray_caster.h>
#include <radiosity/surface_radiance.h>

#include <array>
#include <cstdint>
#include <vector>

namespace rad {

class CubeProbe {
 public:
  /// A probe of `resolution` x `resolution` texels a face (1 to 1024), each the mean of
  /// `samples` x `samples` rays through it (1 to 16; more keeps a small bright emitter's edge
  /// from aliasing).
  explicit CubeProbe(int resolution, int samples = 1);

  /// Looks from `centre` at what `caster` finds, each texel the mean radiance `radiance` gives
  /// toward the centre at the hits of its rays (a square grid over the texel; black where a ray
  /// escapes). In parallel.
  void capture(const RayCaster& caster, const SurfaceRadiance& radiance, const Vec3& centre);

  /// The irradiance a surface with unit normal `n` at the centre receives from the view.
  Color irradiance(const Vec3& n, ProbeIrradiance way) const;
  Color exactIrradiance(const Vec3& n) const;
  Color harmonicIrradiance(const Vec3& n) const;
  Color patternIrradiance(const Vec3& n) const;

  int resolution() const { return resolution_; }
  const Vec3& centre() const { return centre_; }
  /// Face f's texel (i, j): its radiance, the unit direction through its centre, its solid angle.
  Color& texel(int face, int i, int j) { return texels_[index(face, i, j)]; }
  Vec3 direction(int face, int i, int j) const { return directions_[index(face, i, j)]; }
  double solidAngle(int i, int j) const { return solidAngle_[size_t(j) * resolution_ + i]; }
  /// Projects the view onto the harmonics again (capture() does; for views filled by hand).
  void project();

 private:
  size_t index(int face, int i, int j) const {
    return (size_t(face) * resolution_ + size_t(j)) * resolution_ + size_t(i);
  }
  /// The texel a unit direction falls in.
  size_t texelOf(const Vec3& d) const;

  int resolution_, samples_;
  Vec3 centre_{0.0f};
  std::vector<Color> texels_;
  std::vector<double> solidAngle_;          ///< per texel of a face (the same on every face)
  std::vector<Vec3> directions_;            ///< per texel: the unit direction through its centre
  std::vector<float> texelSolidAngle_;      ///< per texel: its solid angle
  std::array<Vec3d, 9> harmonics_{};        ///< L_lm per channel
  std::vector<std::array<float, 2>> ring_;  ///< the pattern's offsets, in texels (pattern())
};

}  // namespace rad
