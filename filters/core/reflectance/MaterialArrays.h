#pragma once
// A material whose coefficients come from the mesh's own point-data arrays (a scan's colours, a
// segmentation, a field through a colour map), and how their values become linear coefficients
// (docs/formulas.md section 7.1). VTK-free: the VTK layer (ShadeLabMaterialArrays.h) reads the
// arrays and maps fields through VTK's own colour maps; the decoding and its checks are here.
#include "Vec3.h"

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <type_traits>
#include <vector>

namespace shadelab
{
/// How an array's values become reflectances.
enum class ArrayEncoding
{
  /// sRGB-encoded (IEC 61966-2-1): decoded to linear by the sRGB transfer function. The
  /// default for 8-bit arrays and for colour maps, whose colours are display colours.
  Srgb,
  /// Already linear: used as they are (an 8-bit value over 255). The default for floating-point
  /// arrays, and for every array in the vtk model, since VTK's mapper uses colours as they are.
  Linear,
};

/// One coefficient (ka, kd, ks, shininess, or the vtk_pbr model's base colour, metallic factor
/// or roughness) read from a point-data array.
struct ArrayCoefficient
{
  std::string array;
  /// Empty: the default for the array's type and the scene's model (ArrayEncoding).
  std::optional<ArrayEncoding> encoding;
  double scale = 1.0; // multiplies the decoded value (the vtk model: vtkProperty's Diffuse and so on)
  /// Empty: the array's own colours (3 or 4 components, or 1 for a grey). Otherwise a colour
  /// map's name (colorMapNames), through which a 1-component array gives the colour.
  std::string colorMap;
  /// The values the colour map's ends stand for; empty: the array's range over the whole mesh.
  std::optional<std::array<double, 2>> range;
  /// The colour map is for 1-component fields only, and colours (3 or 4 components) are used as
  /// they are: a choice made before the array is seen (ParaView's panel), not a scene file's.
  bool colorMapForFieldsOnly = false;
  /// Values that cannot be used (NaN, or outside [0, 1] once decoded) are clamped into [0, 1],
  /// NaN to 0, and marked in the material_clamped array, rather than refused.
  bool clamp = false;
  /// An array of the mesh's own materials (a scene file's parts), which the scene did not ask
  /// for: messages say so.
  bool ownMaterial = false;
};

/// Which of the material's coefficients come from arrays; the others are the Material's numbers.
enum class MaterialCoefficient
{
  Ambient,
  Diffuse, // also the vtk_pbr model's base colour
  Specular,
  Shininess,
  Metallic,  // the vtk_pbr model's metallic factor
  Roughness, // the vtk_pbr model's roughness
};
constexpr int MaterialCoefficientCount = 6;

/// Whether the coefficient is a colour (3 channels per vertex: ka, kd, ks) rather than one
/// number (the shininess, the metallic factor, the roughness).
constexpr bool isColorCoefficient(MaterialCoefficient c)
{
  return c == MaterialCoefficient::Ambient || c == MaterialCoefficient::Diffuse || c == MaterialCoefficient::Specular;
}

/// The bit of material_clamped (VertexMaterial::clamped) that marks coefficient c.
constexpr std::uint8_t clampedBit(MaterialCoefficient c)
{
  return std::uint8_t(1u << int(c));
}

/// The scene file's key for each coefficient ("ka", "kd", "ks", "shininess", "metallic",
/// "roughness").
const char* coefficientKey(MaterialCoefficient coefficient);

/// Per coefficient, the array it comes from, if any.
struct MaterialArrays
{
  std::array<std::optional<ArrayCoefficient>, MaterialCoefficientCount> coefficients;

  const std::optional<ArrayCoefficient>& operator[](MaterialCoefficient c) const { return coefficients[int(c)]; }
  std::optional<ArrayCoefficient>& operator[](MaterialCoefficient c) { return coefficients[int(c)]; }
  bool any() const;
  /// Whether any coefficient clamps its values (and so has them marked in material_clamped).
  bool clamps() const;
};

/// The colour maps a 1-component array can be read through, as ParaView and VTK draw them.
const std::vector<std::string>& colorMapNames();
/// Whether name is one of them; "\"cool to warm\", \"rainbow\", ..." for messages.
bool isColorMapName(const std::string& name);
std::string colorMapNameList();

/// docs/formulas.md section 7.1, the sRGB transfer function (IEC 61966-2-1) inverted: an encoded
/// value in [0, 1] to linear light.
double srgbToLinear(double encoded);
/// The sRGB transfer function itself: linear light in [0, 1] to its display encoding.
double linearToSrgb(double linear);

/// What an array of this kind is read as when the scene does not say.
ArrayEncoding defaultEncoding(bool eightBit, bool vtkModel);

/// Whether two coefficients read the same values (ka following kd's array, say).
bool operator==(const ArrayCoefficient& a, const ArrayCoefficient& b);

/// Each vertex's coefficient, decoded and scaled: 3 values per vertex (r g b) for ka, kd and
/// ks, 1 for the others; empty where the coefficient is the Material's number, or (ka) where
/// ambientIsDiffuse. values holds them in float64, floatValues in float32 for the float32 kernel
/// (which then reads half the bytes): either, or both once withFloat32 has run.
struct VertexMaterial
{
  std::array<std::vector<double>, MaterialCoefficientCount> values;
  std::array<std::vector<float>, MaterialCoefficientCount> floatValues;
  /// ka reads the same array as kd, the same way: its values are kd's.
  bool ambientIsDiffuse = false;
  /// Per vertex, bit c set where coefficient c's value was clamped (ArrayCoefficient::clamp);
  /// empty where nothing asked to clamp.
  std::vector<std::uint8_t> clamped;

  /// The largest value of coefficient c over the vertices (0 where it has none).
  double largest(MaterialCoefficient c) const;
  /// Fills floatValues from values (rounded to float32) where only values holds them.
  void withFloat32();
  /// Coefficient c's values in the precision T, or nullptr where it has none of its own.
  template<typename T>
  const T* of(MaterialCoefficient c) const
  {
    const int i = int(c == MaterialCoefficient::Ambient && ambientIsDiffuse ? MaterialCoefficient::Diffuse : c);
    if constexpr (std::is_same_v<T, float>)
    {
      return floatValues[i].empty() ? nullptr : floatValues[i].data();
    }
    else
    {
      return values[i].empty() ? nullptr : values[i].data();
    }
  }
};

/// One vertex's value of a coefficient from an 8-bit array: the byte over 255, through the
/// encoding (by table), times the scale. Always usable.
double decodeByte(std::uint8_t byte, ArrayEncoding encoding, double scale);

/// Whether a floating-point array's value can be used: finite, and in [0, 1] for ka, kd, ks
/// (reflectances) and the metallic factor, in (0, 1] for the roughness (VTK's GGX distribution
/// is 0/0 at 0), >= 0 for the shininess.
bool isUsableValue(double raw, MaterialCoefficient coefficient);
/// Why it cannot: "it is NaN", "it is 1.5, outside [0, 1]", ...
std::string unusableValueReason(double raw, MaterialCoefficient coefficient);

/// One vertex's value of a coefficient from a floating-point array: clamped into its domain
/// where it is not usable (NaN to 0), through the encoding, times the scale.
double decodeReal(double raw, MaterialCoefficient coefficient, ArrayEncoding encoding, double scale);

/// "array 'Colors', vertex 17: <why>", the message for a value that cannot be used.
std::string vertexValueProblem(const ArrayCoefficient& source, long long vertex, const std::string& why);
}
