#include "Colorimetry.h"

#include <glm/matrix.hpp>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>
#include <stdexcept>

#ifndef SHADELAB_COLORD_FOLDER
#define SHADELAB_COLORD_FOLDER "/usr/share/colord"
#endif

namespace shadelab
{
std::string colordFolder()
{
  return SHADELAB_COLORD_FOLDER;
}

namespace
{
/// The number after `key` in a CGATS header, or NaN.
double headerNumber(const std::string& text, const std::string& key)
{
  const std::size_t at = text.find(key);
  if (at == std::string::npos)
  {
    return std::nan("");
  }
  std::istringstream value(text.substr(at + key.size()));
  double number = std::nan("");
  value >> number;
  return number;
}
}

SampledSpectrum readColordSpectrum(const std::string& path, int set)
{
  std::ifstream file(path);
  if (!file)
  {
    throw std::runtime_error(path + ": cannot be read (colord-data ships it: apt-get install colord-data)");
  }
  const std::string text((std::istreambuf_iterator<char>(file)), std::istreambuf_iterator<char>());
  auto fail = [&](const std::string& why) { throw std::runtime_error(path + ": " + why); };
  const double start = headerNumber(text, "SPECTRAL_START_NM");
  const double end = headerNumber(text, "SPECTRAL_END_NM");
  const double bands = headerNumber(text, "SPECTRAL_BANDS");
  if (!(start > 0 && end > start && bands >= 2))
  {
    fail("no SPECTRAL_START_NM, SPECTRAL_END_NM and SPECTRAL_BANDS of a spectrum");
  }
  const std::size_t begin = text.find("\nBEGIN_DATA\n");
  const std::size_t finish = text.find("\nEND_DATA", begin == std::string::npos ? 0 : begin + 1);
  if (begin == std::string::npos || finish == std::string::npos)
  {
    fail("no BEGIN_DATA ... END_DATA block");
  }
  // One line of values per set.
  std::istringstream lines(text.substr(begin + 12, finish - begin - 12));
  std::string line;
  for (int s = 0; s <= set; ++s)
  {
    if (!std::getline(lines, line))
    {
      fail("has no set " + std::to_string(set));
    }
  }
  SampledSpectrum spectrum;
  spectrum.startNm = start;
  spectrum.stepNm = (end - start) / (bands - 1);
  std::istringstream values(line);
  for (double value = 0; values >> value;)
  {
    spectrum.values.push_back(value);
  }
  if (spectrum.values.size() != std::size_t(bands))
  {
    fail("set " + std::to_string(set) + " has " + std::to_string(spectrum.values.size()) + " values for " +
      std::to_string(std::size_t(bands)) + " bands");
  }
  return spectrum;
}

ColorMatchingFunctions cie1931Observer(const std::string& folder)
{
  const std::string path = folder + "/cmf/CIE1931-2deg-XYZ.cmf";
  return { readColordSpectrum(path, 0), readColordSpectrum(path, 1), readColordSpectrum(path, 2) };
}

const std::vector<std::string>& cieIlluminantNames()
{
  static const std::vector<std::string> names{ "A", "B", "C", "D50", "D55", "D65", "D93", "E", "F1", "F2", "F3", "F4",
    "F5", "F6", "F7", "F8", "F9", "F10", "F11", "F12" };
  return names;
}

SampledSpectrum cieIlluminant(const std::string& name, const std::string& folder)
{
  const std::vector<std::string>& names = cieIlluminantNames();
  if (std::find(names.begin(), names.end(), name) == names.end())
  {
    throw std::runtime_error("'" + name + "' is not one of the CIE illuminants colord ships");
  }
  return readColordSpectrum(folder + "/illuminant/CIE-" + name + ".sp");
}

glm::dvec3 tristimulus(
  const std::function<double(double)>& stimulus, const ColorMatchingFunctions& observer, double bandNm)
{
  glm::dvec3 xyz(0.0);
  const auto bands = std::size_t(std::lround((observer.y.endNm() - observer.y.startNm) / bandNm)) + 1;
  for (std::size_t b = 0; b < bands; ++b)
  {
    const double nm = observer.y.startNm + double(b) * bandNm;
    const double s = stimulus(nm) * bandNm;
    xyz += s * glm::dvec3(observer.x.at(nm), observer.y.at(nm), observer.z.at(nm));
  }
  return xyz;
}

glm::dvec2 chromaticity(const glm::dvec3& xyz)
{
  return glm::dvec2(xyz.x, xyz.y) / (xyz.x + xyz.y + xyz.z);
}

glm::dmat3 xyzToLinearSrgb()
{
  // IEC 61966-2-1's primaries and white point (D65); each primary's XYZ at Y = 1 is
  // (x / y, 1, (1 - x - y) / y), scaled so that the three sum to the white's XYZ.
  auto atUnitY = [](double x, double y) { return glm::dvec3(x / y, 1.0, (1 - x - y) / y); };
  const glm::dmat3 primaries(atUnitY(0.64, 0.33), atUnitY(0.30, 0.60), atUnitY(0.15, 0.06)); // columns
  const glm::dvec3 white = atUnitY(0.3127, 0.3290);
  const glm::dvec3 scales = glm::inverse(primaries) * white;
  const glm::dmat3 rgbToXyz(primaries[0] * scales.x, primaries[1] * scales.y, primaries[2] * scales.z);
  return glm::inverse(rgbToXyz);
}
}
