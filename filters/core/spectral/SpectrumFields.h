#pragma once
// Spectra in scene files (docs/guide/scene-files.md, "Spectra"): a light's emission as a CIE
// illuminant, a blackbody or a sampled table, and what they are in the RGB model.
#include "Colorimetry.h"
#include "JsonNode.h"

#include <stdexcept>

namespace shadelab
{
/// The CIE 1931 observer and D65 from colordFolder(), read once: every spectrum in a scene is
/// weighed with them. Throw std::runtime_error where colord's tables are missing.
const ColorMatchingFunctions& standardObserver();
const SampledSpectrum& d65Illuminant();

/// compute(), or node's failure saying why where colord's tables are missing.
template<typename Compute>
auto withColorTables(const JsonNode& node, Compute&& compute)
{
  try
  {
    return compute();
  }
  catch (const std::runtime_error& missing)
  {
    node.fail(missing.what());
  }
}

/// A spectrum from a scene file: {"illuminant": "F11"} (colordFolder()'s CIE tables),
/// {"blackbody": 2700} (kelvin) or {"start_nm": 400, "step_nm": 10, "values": [...]}.
/// Fails with the JSON path of what is wrong; the tables' files missing is an error too.
SampledSpectrum readSpectrum(const JsonNode& node);

/// The linear sRGB of light with this spectrum, its luminance Y scaled to 1: what it is in the
/// RGB model (D65 is (1, 1, 1)). Outside sRGB's gamut (a blackbody below about 1900 K) its
/// negative channels are set to 0 before the scaling. Infinite where Y is 0. Throws
/// std::runtime_error where colord's tables are missing.
glm::dvec3 emitterRgb(const SampledSpectrum& emission);

/// A reflectance's linear sRGB under D65, a flat 1.0 being (1, 1, 1): what it is in the RGB
/// model, negative channels (outside sRGB's gamut) set to 0. Throws std::runtime_error where colord's tables are
/// missing.
glm::dvec3 reflectorRgb(const SampledSpectrum& reflectance);
}
