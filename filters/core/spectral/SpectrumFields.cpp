#include "SpectrumFields.h"

#include "ReflectanceUpsampling.h"

#include <glm/common.hpp>
#include <glm/matrix.hpp>

#include <cmath>

namespace shadelab
{
const ColorMatchingFunctions& standardObserver()
{
  static const ColorMatchingFunctions tables = cie1931Observer();
  return tables;
}

const SampledSpectrum& d65Illuminant()
{
  static const SampledSpectrum spectrum = cieIlluminant("D65");
  return spectrum;
}

SampledSpectrum readSpectrum(const JsonNode& node)
{
  node.expectObject({ "illuminant", "blackbody", "start_nm", "step_nm", "values" });
  const int kinds = int(node.has("illuminant")) + int(node.has("blackbody")) + int(node.has("values"));
  if (kinds != 1)
  {
    node.fail("give one of \"illuminant\" (a CIE name), \"blackbody\" (kelvin), or \"start_nm\", \"step_nm\" and "
              "\"values\" (a table)");
  }
  if (node.has("illuminant"))
  {
    std::vector<std::pair<std::string, std::string>> options;
    for (const std::string& name : cieIlluminantNames())
    {
      options.emplace_back(name, name);
    }
    const std::string name = node.at("illuminant").choiceAmong(options);
    return withColorTables(node, [&] { return cieIlluminant(name); });
  }
  if (node.has("blackbody"))
  {
    const double kelvin = node.at("blackbody").number();
    if (!(kelvin >= 500 && kelvin <= 1e6))
    {
      node.at("blackbody").fail("must be a temperature in kelvin from 500 to 1e6");
    }
    const SampledSpectrum& grid =
      withColorTables(node, [&]() -> const SampledSpectrum& { return standardObserver().y; });
    return blackbody(kelvin, grid.startNm, grid.endNm(), grid.stepNm);
  }
  SampledSpectrum table;
  table.startNm = node.at("start_nm").number();
  table.stepNm = node.at("step_nm").number();
  if (!(table.startNm > 0 && table.startNm < 1e4))
  {
    node.at("start_nm").fail("must be a wavelength in nm > 0");
  }
  if (!(table.stepNm > 0 && table.stepNm <= 100))
  {
    node.at("step_nm").fail("must be a number of nm > 0 and <= 100");
  }
  const JsonNode values = node.at("values");
  if (!values.isArray() || values.size() < 2)
  {
    values.fail("must be an array of at least 2 numbers");
  }
  for (std::size_t i = 0; i < values.size(); ++i)
  {
    const double value = values.element(i).number();
    if (!(value >= 0 && std::isfinite(value)))
    {
      values.element(i).fail("must be a number >= 0");
    }
    table.values.push_back(value);
  }
  return table;
}

namespace
{
/// Linear sRGB with its negative channels set to 0: the colour of a spectrum outside sRGB's
/// gamut (a blackbody below about 1900 K, a narrow band) as the nearest colour the RGB model can
/// hold channel by channel.
glm::dvec3 clippedToGamut(const glm::dvec3& rgb)
{
  return glm::max(rgb, glm::dvec3(0.0));
}
}

glm::dvec3 reflectorRgb(const SampledSpectrum& reflectance)
{
  return clippedToGamut(reflectanceRgb(reflectance, standardObserver(), d65Illuminant()));
}

glm::dvec3 emitterRgb(const SampledSpectrum& emission)
{
  const glm::dvec3 xyz =
    tristimulus([&](double nm) { return emission.at(nm); }, standardObserver(), standardObserver().y.stepNm);
  const glm::dvec3 clipped = clippedToGamut(xyzToLinearSrgb() * (xyz / xyz.y));
  return clipped / (glm::inverse(xyzToLinearSrgb()) * clipped).y;
}
}
