#pragma once
// CIE colorimetry (docs/formulas.md section 22): the CIE 1931 2-degree observer and the CIE
// illuminants as Debian's colord-data package ships them, tristimulus values, chromaticity, and
// linear sRGB. The tables are read from colord's files, not retyped.
#include "Spectrum.h"

#include <glm/mat3x3.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include <functional>
#include <string>
#include <vector>

namespace shadelab
{
/// The folder colord-data installs its tables in (/usr/share/colord on Debian).
std::string colordFolder();

/// A spectrum from one of colord's CGATS files (illuminant/*.sp, cmf/*.cmf): its set `set`
/// (the colour-matching functions' files hold x, y and z as sets 0, 1 and 2). Throws
/// std::runtime_error naming the file and what is wrong with it, or to install colord-data.
SampledSpectrum readColordSpectrum(const std::string& path, int set = 0);

/// The CIE 1931 2-degree standard observer: x, y and z bar, 360 to 830 nm every 5 nm.
struct ColorMatchingFunctions
{
  SampledSpectrum x, y, z;
};
ColorMatchingFunctions cie1931Observer(const std::string& folder = colordFolder());

/// The CIE illuminants colord ships: "A", "B", "C", "D50", "D55", "D65", "D93", "E", "F1" to "F12".
const std::vector<std::string>& cieIlluminantNames();
/// One of them by name; throws std::runtime_error for another name.
SampledSpectrum cieIlluminant(const std::string& name, const std::string& folder = colordFolder());

/// The tristimulus values X, Y, Z of a stimulus (light reaching the eye, per nm), summed over
/// bands of bandNm from the observer's first wavelength to its last, each band's stimulus and
/// observer taken at its wavelength (CIE 015:2018's sums).
glm::dvec3 tristimulus(
  const std::function<double(double)>& stimulus, const ColorMatchingFunctions& observer, double bandNm);

/// The chromaticity (x, y) = (X, Y) / (X + Y + Z).
glm::dvec2 chromaticity(const glm::dvec3& xyz);

/// The matrix from XYZ to linear sRGB (IEC 61966-2-1): built from the sRGB primaries'
/// chromaticities and D65's, so that Y = 1 white is (1, 1, 1).
glm::dmat3 xyzToLinearSrgb();
}
