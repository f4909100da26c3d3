#pragma once
// An RGB reflectance as a smooth spectrum, by Jakob and Hanika's method ("A Low-Dimensional
// Function Space for Efficient Spectral Upsampling", Eurographics 2019; docs/formulas.md
// section 22): r(lambda) = S(c0 + c1 t + c2 t^2), t the wavelength scaled to [0, 1] over the
// observer's range, S(x) = 1/2 + x / (2 sqrt(1 + x^2)), which keeps it within (0, 1). The three
// coefficients are fitted here, with no precomputed table, so that the spectrum's linear sRGB
// under D65 is the given RGB.
#include "Colorimetry.h"

namespace shadelab
{
/// The fitted spectrum and how closely it gives the RGB back.
struct UpsampledReflectance
{
  SampledSpectrum spectrum; // on the observer's wavelengths
  double rgbResidual = 0;   // the largest |RGB of the spectrum - the RGB asked for|
};

/// A reflectance spectrum whose linear sRGB, as the D65 white's (1, 1, 1) is, equals rgb (each
/// channel in [0, 1]). A grey is the constant spectrum exactly; other colours are fitted by
/// damped Gauss-Newton (Levenberg-Marquardt) steps from grey. The residual says how far the fit
/// got (below 1e-9 for every colour the tests try, the sRGB cube's corners included).
UpsampledReflectance upsampleReflectance(
  const glm::dvec3& rgb, const ColorMatchingFunctions& observer, const SampledSpectrum& d65);

/// The linear sRGB of a reflectance under D65, normalised so that a flat 1.0 gives (1, 1, 1).
glm::dvec3 reflectanceRgb(
  const SampledSpectrum& reflectance, const ColorMatchingFunctions& observer, const SampledSpectrum& d65);
}
