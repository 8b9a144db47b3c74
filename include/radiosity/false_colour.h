#pragma once
// A lighting designer's false-colour picture: the irradiance each pixel sees, in lux (or in W per
// square scene unit), through a colour ramp, with isolux lines at the legend's steps and the
// legend beside the picture.

#include <radiosity/image.h>

#include <string>

namespace rad {

struct FalseColourScale {
  /// The shown unit per W per square scene unit of luminance (lux: 179 / metres^2).
  double perIrradiance = 1.0;
  std::string unit = "lx";  ///< the legend's label
  /// The top of the ramp, in the shown unit; 0: the 98th percentile of the lit pixels, rounded
  /// up to a step of the legend.
  double max = 0.0;
};

/// The picture of `irradiance` (per pixel, W per square scene unit) in false colour: the
/// luminance times `scale.perIrradiance` through a Turbo-like ramp from 0 to the top, a dark
/// isoline where a pixel and its right or lower neighbour fall between different steps of the
/// legend, and the legend (a bar with the steps' values and the unit) in a strip to the right.
/// Colours are linear: a PNG written at exposure 0 shows the ramp's sRGB colours.
Image falseColourPicture(const Image& irradiance, const FalseColourScale& scale);

/// The legend's step for a top value: 1, 2 or 5 times a power of ten, about a fifth of it.
double falseColourStep(double top);

}  // namespace rad
