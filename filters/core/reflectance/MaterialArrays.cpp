#include "MaterialArrays.h"

#include "NumberText.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace shadelab
{
const char* coefficientKey(MaterialCoefficient coefficient)
{
  switch (coefficient)
  {
    case MaterialCoefficient::Ambient: return "ka";
    case MaterialCoefficient::Diffuse: return "kd";
    case MaterialCoefficient::Specular: return "ks";
    case MaterialCoefficient::Shininess: return "shininess";
    case MaterialCoefficient::Metallic: return "metallic";
    case MaterialCoefficient::Roughness: return "roughness";
  }
  return "";
}

bool MaterialArrays::any() const
{
  return std::any_of(coefficients.begin(), coefficients.end(), [](const auto& c) { return c.has_value(); });
}

bool MaterialArrays::clamps() const
{
  return std::any_of(coefficients.begin(), coefficients.end(), [](const auto& c) { return c && c->clamp; });
}

const std::vector<std::string>& colorMapNames()
{
  // ShadeLabMaterialArrays.cxx builds each with VTK's own classes.
  static const std::vector<std::string> names{ "cool to warm", "rainbow", "grayscale" };
  return names;
}

bool isColorMapName(const std::string& name)
{
  const std::vector<std::string>& names = colorMapNames();
  return std::find(names.begin(), names.end(), name) != names.end();
}

std::string colorMapNameList()
{
  std::string list;
  for (const std::string& name : colorMapNames())
  {
    list += (list.empty() ? "\"" : ", \"") + name + "\"";
  }
  return list;
}

double srgbToLinear(double encoded)
{
  // IEC 61966-2-1:1999, the decoding: linear below the 0.04045 knee, a 2.4 power above it.
  return encoded <= 0.04045 ? encoded / 12.92 : std::pow((encoded + 0.055) / 1.055, 2.4);
}

double linearToSrgb(double linear)
{
  // IEC 61966-2-1:1999, the encoding: the inverse of srgbToLinear.
  return linear <= 0.0031308 ? 12.92 * linear : 1.055 * std::pow(linear, 1 / 2.4) - 0.055;
}

ArrayEncoding defaultEncoding(bool eightBit, bool vtkModel)
{
  return eightBit && !vtkModel ? ArrayEncoding::Srgb : ArrayEncoding::Linear;
}

double decodeByte(std::uint8_t byte, ArrayEncoding encoding, double scale)
{
  // 256 decodings, computed once: a pow per vertex and channel would cost more than shading.
  static const std::array<double, 256> srgbTable = []
  {
    std::array<double, 256> table{};
    for (int i = 0; i < 256; ++i)
    {
      table[i] = srgbToLinear(i / 255.0);
    }
    return table;
  }();
  return (encoding == ArrayEncoding::Srgb ? srgbTable[byte] : byte / 255.0) * scale;
}

bool isUsableValue(double raw, MaterialCoefficient coefficient)
{
  switch (coefficient)
  {
    case MaterialCoefficient::Shininess: return std::isfinite(raw) && raw >= 0;
    case MaterialCoefficient::Roughness: return raw > 0 && raw <= 1;
    default: return raw >= 0 && raw <= 1;
  }
}

std::string unusableValueReason(double raw, MaterialCoefficient coefficient)
{
  if (!std::isfinite(raw))
  {
    return std::string("it is ") + (std::isnan(raw) ? "NaN" : "infinite");
  }
  return "it is " + withDigits(raw, 6) +
    (coefficient == MaterialCoefficient::Shininess      ? ", below 0"
        : coefficient == MaterialCoefficient::Roughness ? ", outside (0, 1] (at 0, VTK's GGX distribution is 0/0 in "
                                                          "the mirror direction)"
                                                        : ", outside [0, 1]");
}

double decodeReal(double raw, MaterialCoefficient coefficient, ArrayEncoding encoding, double scale)
{
  const double high = coefficient == MaterialCoefficient::Shininess ? HUGE_VAL : 1.0;
  const double usable = std::isnan(raw) ? 0.0 : std::clamp(raw, 0.0, high);
  const double finite = std::isinf(usable) ? std::numeric_limits<double>::max() : usable;
  return (encoding == ArrayEncoding::Srgb ? srgbToLinear(finite) : finite) * scale;
}

std::string vertexValueProblem(const ArrayCoefficient& source, long long vertex, const std::string& why)
{
  return "array '" + source.array + "', vertex " + std::to_string(vertex) + ": " + why;
}

bool operator==(const ArrayCoefficient& a, const ArrayCoefficient& b)
{
  return a.array == b.array && a.encoding == b.encoding && a.scale == b.scale && a.colorMap == b.colorMap &&
    a.range == b.range && a.clamp == b.clamp && a.colorMapForFieldsOnly == b.colorMapForFieldsOnly &&
    a.ownMaterial == b.ownMaterial;
}

double VertexMaterial::largest(MaterialCoefficient c) const
{
  const auto& doubles = values[int(c)];
  const auto& floats = floatValues[int(c)];
  const double fromDoubles = doubles.empty() ? 0.0 : *std::max_element(doubles.begin(), doubles.end());
  const double fromFloats = floats.empty() ? 0.0 : double(*std::max_element(floats.begin(), floats.end()));
  return std::max(fromDoubles, fromFloats);
}

void VertexMaterial::withFloat32()
{
  for (int c = 0; c < MaterialCoefficientCount; ++c)
  {
    if (floatValues[c].empty())
    {
      floatValues[c].assign(values[c].begin(), values[c].end());
    }
  }
}
}
