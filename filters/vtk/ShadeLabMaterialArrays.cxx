#include "ShadeLabMaterialArrays.h"

#include "Microfacet.h"
#include "NumberText.h"
#include "ShadeLabImportedParts.h"

#include "vtkArrayDispatch.h"
#include "vtkCommunicator.h"
#include "vtkDataArray.h"
#include "vtkDataArrayRange.h"
#include "vtkDiscretizableColorTransferFunction.h"
#include "vtkFieldData.h"
#include "vtkLookupTable.h"
#include "vtkMultiProcessController.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkSMPTools.h"
#include "vtkStringArray.h"
#include "vtkUnsignedCharArray.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <type_traits>

namespace shadelab
{
namespace
{
/// The range of a 1-component array's finite values over every process, or (VTK_DOUBLE_MAX,
/// VTK_DOUBLE_MIN) where there are none. Every process takes part, whatever its piece holds.
std::array<double, 2> wholeFiniteRange(vtkDataArray* array, vtkMultiProcessController* processes)
{
  std::array<double, 2> mine{ VTK_DOUBLE_MAX, VTK_DOUBLE_MIN };
  if (array && array->GetNumberOfComponents() == 1 && array->GetNumberOfTuples() > 0)
  {
    double range[2];
    array->GetFiniteRange(range, 0);
    if (range[0] <= range[1])
    {
      mine = { range[0], range[1] };
    }
  }
  std::array<double, 2> all = mine;
  if (processes && processes->GetNumberOfProcesses() > 1)
  {
    processes->AllReduce(&mine[0], &all[0], 1, vtkCommunicator::MIN_OP);
    processes->AllReduce(&mine[1], &all[1], 1, vtkCommunicator::MAX_OP);
  }
  return all;
}

/// Decodes every vertex's channels of a coefficient from an array of any value type, in
/// parallel, into values (width per vertex, stored as Stored: float or double); finds the first
/// vertex whose value cannot be used.
template<typename Stored>
struct ChannelDecoding
{
  MaterialCoefficient coefficient;
  const ArrayCoefficient& source;
  ArrayEncoding encoding;
  int width; // 3 for a colour, 1 for a number (isColorCoefficient)
  std::vector<Stored>& values;
  std::vector<std::uint8_t>& clamped;
  vtkIdType firstUnusable = -1;

  template<typename Array>
  void operator()(Array* array)
  {
    using Value = vtk::GetAPIType<Array>;
    const auto tuples = vtk::DataArrayTupleRange(array);
    const int components = array->GetNumberOfComponents();
    const std::uint8_t bit = clampedBit(coefficient);
    std::atomic<vtkIdType> first{ VTK_ID_MAX };
    vtkSMPTools::For(0, array->GetNumberOfTuples(),
      [&](vtkIdType begin, vtkIdType end)
      {
        for (vtkIdType i = begin; i < end; ++i)
        {
          for (int channel = 0; channel < width; ++channel)
          {
            // A grey (1 component) gives all three channels; RGBA's alpha is not a reflectance.
            const Value raw = tuples[i][components == 1 ? 0 : channel];
            Stored& value = values[std::size_t(width) * i + channel];
            // A byte is over 255: only a roughness of 0 is then out of its domain.
            constexpr bool byte = std::is_same_v<Value, unsigned char>;
            if (!isUsableValue(byte ? double(raw) / 255.0 : double(raw), coefficient))
            {
              if (!source.clamp)
              {
                // Only this vertex's channels are left: the scan goes on, for the first such vertex.
                for (vtkIdType known = first; i < known && !first.compare_exchange_weak(known, i);)
                {
                }
                break;
              }
              clamped[i] |= bit;
            }
            if constexpr (byte)
            {
              value = Stored(decodeByte(raw, encoding, source.scale));
            }
            else
            {
              value = Stored(decodeReal(double(raw), coefficient, encoding, source.scale));
            }
          }
        }
      });
    firstUnusable = first == VTK_ID_MAX ? -1 : first.load();
  }
};

/// Why vertex i's value in the array cannot be used.
std::string unusableVertex(vtkDataArray* array, vtkIdType i, MaterialCoefficient coefficient, int width)
{
  for (int channel = 0; channel < width; ++channel)
  {
    const double raw = array->GetComponent(i, array->GetNumberOfComponents() == 1 ? 0 : channel);
    if (!isUsableValue(raw, coefficient))
    {
      return unusableValueReason(raw, coefficient);
    }
  }
  return "";
}

/// A field's 8-bit colours through the colour map, as VTK's mapper makes them (RGBA). A NaN is
/// refused (the returned vertex), or where the source clamps, given the colour of the range's
/// low end and marked.
vtkSmartPointer<vtkUnsignedCharArray> mappedColors(vtkDataArray* field, const ArrayCoefficient& source,
  MaterialCoefficient coefficient, const std::array<double, 2>& range, std::vector<std::uint8_t>& clamped,
  vtkIdType& firstNaN)
{
  const vtkSmartPointer<vtkScalarsToColors> map = namedColorMap(source.colorMap, range);
  vtkSmartPointer<vtkUnsignedCharArray> colors;
  colors.TakeReference(map->MapScalars(field, VTK_COLOR_MODE_MAP_SCALARS, 0));
  const unsigned char* low = map->MapValue(range[0]);
  const std::array<unsigned char, 3> lowColor{ low[0], low[1], low[2] };
  firstNaN = -1;
  for (vtkIdType i = 0; i < field->GetNumberOfTuples(); ++i)
  {
    if (std::isnan(field->GetComponent(i, 0)))
    {
      if (!source.clamp)
      {
        firstNaN = i;
        break;
      }
      clamped[i] |= clampedBit(coefficient);
      std::copy(lowColor.begin(), lowColor.end(), colors->GetPointer(4 * i));
    }
  }
  return colors;
}

/// Whether the array's values go through the source's colour map.
bool mapsColors(const ArrayCoefficient& source, vtkDataArray* array)
{
  return !source.colorMap.empty() && !(source.colorMapForFieldsOnly && array->GetNumberOfComponents() != 1);
}

/// Why the array cannot give the coefficient at all (its kind, its length, its components), or
/// "", after `at` (where the coefficient was asked for).
std::string arrayProblem(vtkDataArray* array, vtkPolyData* piece, MaterialCoefficient coefficient,
  const ArrayCoefficient& source, const std::string& at)
{
  if (!array)
  {
    std::string names;
    vtkPointData* data = piece->GetPointData();
    for (int a = 0; a < data->GetNumberOfArrays(); ++a)
    {
      if (vtkDataArray* other = data->GetArray(a))
      {
        names += (names.empty() ? "'" : ", '") + std::string(other->GetName() ? other->GetName() : "") + "'";
      }
    }
    return at + "the mesh has no numeric point-data array '" + source.array +
      "' (its point arrays: " + (names.empty() ? "none" : names) + ")";
  }
  const std::string named = at + "array '" + source.array + "' ";
  if (array->GetNumberOfTuples() != piece->GetNumberOfPoints())
  {
    return named + "has " + std::to_string(array->GetNumberOfTuples()) + " values for the mesh's " +
      std::to_string(piece->GetNumberOfPoints()) + " points";
  }
  // 8-bit values are read over 255; other integers have no such rule, and would all be refused
  // as outside [0, 1].
  if (array->GetDataType() != VTK_UNSIGNED_CHAR && array->GetDataType() != VTK_FLOAT &&
    array->GetDataType() != VTK_DOUBLE)
  {
    return named + "holds " + array->GetDataTypeAsString() +
      " values; a material reads 8-bit (unsigned char) or floating-point ones: convert it (16-bit colours "
      "divided by 65535 into a float array, say)";
  }
  const int components = array->GetNumberOfComponents();
  if ((!isColorCoefficient(coefficient) || mapsColors(source, array)) && components != 1)
  {
    return named + "has " + std::to_string(components) + " components; " +
      (!source.colorMap.empty() ? "a colour map takes a field of 1"
          : coefficient == MaterialCoefficient::Metallic
          ? "a metallic factor takes 1"
          : "a " + std::string(coefficientKey(coefficient)) + " takes 1");
  }
  if (components != 1 && components != 3 && components != 4)
  {
    return named + "has " + std::to_string(components) +
      " components; a colour takes 3 (RGB), 4 (RGBA, alpha unused) or 1 (a grey, or a field through a colour map)";
  }
  return "";
}
}

vtkSmartPointer<vtkScalarsToColors> namedColorMap(const std::string& name, const std::array<double, 2>& range)
{
  if (name == "cool to warm")
  {
    // ParaView 5.11's default preset: Moreland's diverging map ("Diverging Color Maps for
    // Scientific Visualization", ISVC 2009) through its three points, discretised to 256
    // colours as ParaView draws it.
    auto map = vtkSmartPointer<vtkDiscretizableColorTransferFunction>::New();
    map->SetColorSpaceToDiverging();
    const double middle = 0.5 * (range[0] + range[1]);
    map->AddRGBPoint(range[0], 0.23137254902, 0.298039215686, 0.752941176471);
    map->AddRGBPoint(middle, 0.865, 0.865, 0.865);
    map->AddRGBPoint(range[1], 0.705882352941, 0.0156862745098, 0.149019607843);
    map->DiscretizeOn();
    map->SetNumberOfValues(256);
    map->Build();
    return map;
  }
  auto table = vtkSmartPointer<vtkLookupTable>::New();
  if (name == "grayscale")
  {
    table->SetHueRange(0, 0);
    table->SetSaturationRange(0, 0);
    table->SetValueRange(0, 1);
  }
  // "rainbow": vtkLookupTable's defaults, 256 hues from red to blue, the table a vtkMapper
  // makes when given none.
  table->SetTableRange(range[0], range[1]);
  table->Build();
  return table;
}

void colorMaterialBy(Scene& scene, const std::string& name, const std::string& colorMap)
{
  Material& m = scene.material;
  ArrayCoefficient source;
  source.array = name;
  source.colorMap = colorMap;
  source.colorMapForFieldsOnly = true;
  if (scene.model == ShadingModel::VtkPbr)
  {
    // The base colour, as a grey, scales the colour as the PBR property's Diffuse does.
    source.scale = largestComponent(m.microfacet.baseColor);
    m.arrays[MaterialCoefficient::Diffuse] = source;
    m.microfacet.baseColor = Rgb(source.scale);
    return;
  }
  const bool vtk = scene.model == ShadingModel::VtkOpenGL2;
  source.scale = vtk ? largestComponent(m.kd) : 1.0;
  m.arrays[MaterialCoefficient::Diffuse] = source;
  m.kd = Rgb(source.scale);
  source.scale = vtk ? largestComponent(m.ka) : 1.0;
  m.arrays[MaterialCoefficient::Ambient] = source;
  m.ka = Rgb(source.scale);
}

std::string materialClampedArrayName(const std::string& prefix)
{
  return prefix + "material_clamped";
}

namespace
{
/// The values a coefficient's colour map spans: its source's range, or the field's finite range
/// over the whole mesh (a collective call on a split mesh). A constant field spans one unit from
/// its value (a colour map's ends must differ).
std::array<double, 2> colorMapRange(
  const ArrayCoefficient& source, vtkDataArray* array, vtkMultiProcessController* processes)
{
  std::array<double, 2> range = source.range ? *source.range : wholeFiniteRange(array, processes);
  range[1] = range[0] == range[1] ? range[0] + 1 : range[1];
  return range;
}

/// How a coefficient's channels are decoded: a number (a shininess, metallic factor or
/// roughness) as it is; a colour as its source says, or else as defaultEncoding reads its kind
/// (8-bit values and colours from a colour map are 8-bit).
ArrayEncoding encodingOf(
  MaterialCoefficient coefficient, const ArrayCoefficient& source, vtkDataArray* array, bool mapped, ShadingModel model)
{
  const bool eightBit = array->GetDataType() == VTK_UNSIGNED_CHAR || mapped;
  return !isColorCoefficient(coefficient)
    ? ArrayEncoding::Linear
    : source.encoding.value_or(defaultEncoding(eightBit, reproducesVtkRenderer(model)));
}

/// Where the coefficient was asked for, as a message begins: the scene's material, the filter's
/// colour array, or the mesh's own materials (naming the part, where one is given).
std::string requestedAt(
  const ArrayCoefficient& source, MaterialCoefficient coefficient, ShadingModel model, const std::string& part = "")
{
  return source.colorMapForFieldsOnly ? "the material's colour array (MaterialColorArray, --color-by): "
    : source.ownMaterial ? "the mesh's own materials" + (part.empty() ? "" : ", part '" + part + "'") + ": "
                         : std::string("scene /material/") + materialKey(coefficient, model) + ": ";
}

/// The name of the part that the piece's vertex belongs to (ShadeLabImportedParts.h), or "".
std::string partNameAt(vtkPolyData* piece, vtkIdType vertex)
{
  vtkDataArray* parts = piece->GetPointData()->GetArray(partArrayName);
  auto* names = vtkStringArray::SafeDownCast(piece->GetFieldData()->GetAbstractArray(partNamesArrayName));
  const double part = parts && vertex < parts->GetNumberOfTuples() ? parts->GetComponent(vertex, 0) : -1;
  return names && part >= 0 && part < double(names->GetNumberOfValues()) ? names->GetValue(vtkIdType(part)) : "";
}

/// The message for a vertex whose value cannot be used: where it was asked for, the array, the
/// vertex (by its id) and why.
std::string vertexProblem(vtkPolyData* piece, const ArrayCoefficient& source, MaterialCoefficient coefficient,
  ShadingModel model, vtkIdType vertex, long long id, const std::string& why)
{
  const std::string part = source.ownMaterial ? partNameAt(piece, vertex) : "";
  return requestedAt(source, coefficient, model, part) + vertexValueProblem(source, id, why);
}

/// Why the smallest roughness that the array gave cannot be shaded in this precision (the
/// scene's own roughnessPrecisionProblem, at that vertex), or is below the smallest that the
/// scene's overflow checks bound (smallestArrayRoughness); "" where it can be.
template<typename VertexId>
std::string arrayRoughnessProblem(vtkPolyData* piece, const VertexMaterial& material, const ArrayCoefficient& source,
  Precision storage, ShadingModel model, VertexId&& idOf)
{
  const int c = int(MaterialCoefficient::Roughness);
  const auto smallestAt = [&](const auto& values)
  { return vtkIdType(std::min_element(values.begin(), values.end()) - values.begin()); };
  const bool narrow = storage == Precision::Float32;
  if (narrow ? material.floatValues[c].empty() : material.values[c].empty())
  {
    return "";
  }
  const vtkIdType vertex = narrow ? smallestAt(material.floatValues[c]) : smallestAt(material.values[c]);
  const double roughness = narrow ? material.floatValues[c][vertex] : material.values[c][vertex];
  std::string why = roughnessPrecisionProblem(roughness, storage);
  if (why.empty() && roughness < smallestArrayRoughness(storage))
  {
    why = "at roughness " + withDigits(roughness, 3) + " D's peak, 1/(pi r^4), is beyond what the run's overflow " +
      "checks bound: a roughness from an array must be at least " + withDigits(smallestArrayRoughness(storage), 3);
  }
  return why.empty() ? ""
                     : vertexProblem(piece, source, MaterialCoefficient::Roughness, model, vertex, idOf(vertex), why);
}
}

MaterialReading readVertexMaterial(vtkPolyData* piece, const Scene& scene, Precision storage,
  vtkMultiProcessController* processes, const std::vector<vtkIdType>* vertexIds)
{
  MaterialReading reading;
  const MaterialArrays& arrays = scene.material.arrays;
  const vtkIdType count = piece->GetNumberOfPoints();
  reading.material.clamped.assign(arrays.clamps() ? std::size_t(count) : 0, 0);
  auto idOf = [&](vtkIdType i) { return vertexIds ? (*vertexIds)[i] : i; };
  // ka that reads kd's array the same way (the lecture model's default) shares kd's values.
  reading.material.ambientIsDiffuse = arrays[MaterialCoefficient::Ambient] && arrays[MaterialCoefficient::Diffuse] &&
    *arrays[MaterialCoefficient::Ambient] == *arrays[MaterialCoefficient::Diffuse];
  // In the scene file's order, so that a problem of kd's array is kd's where ka follows it.
  for (const MaterialCoefficient coefficient :
    { MaterialCoefficient::Diffuse, MaterialCoefficient::Ambient, MaterialCoefficient::Specular,
      MaterialCoefficient::Shininess, MaterialCoefficient::Metallic, MaterialCoefficient::Roughness })
  {
    const int c = int(coefficient);
    const std::optional<ArrayCoefficient>& source = arrays[coefficient];
    if (!source || (coefficient == MaterialCoefficient::Ambient && reading.material.ambientIsDiffuse))
    {
      continue;
    }
    const std::string at = requestedAt(*source, coefficient, scene.model);
    vtkDataArray* array = piece->GetPointData()->GetArray(source->array.c_str());
    // Collective, so before anything that may stop this process.
    const std::array<double, 2> range =
      source->colorMap.empty() ? std::array<double, 2>{} : colorMapRange(*source, array, processes);
    if (!reading.problem.empty() || count == 0) // an empty piece of a split mesh may have no arrays
    {
      continue;
    }
    reading.problem = arrayProblem(array, piece, coefficient, *source, at);
    const bool mapped = reading.problem.empty() && mapsColors(*source, array);
    if (mapped && range[0] > range[1])
    {
      reading.problem =
        at + "array '" + source->array + "' has no finite value to span the colour map: give its \"range\"";
    }
    if (!reading.problem.empty())
    {
      continue;
    }
    const ArrayEncoding encoding = encodingOf(coefficient, *source, array, mapped, scene.model);
    const int width = isColorCoefficient(coefficient) ? 3 : 1;
    const std::size_t size = std::size_t(width) * count;
    vtkSmartPointer<vtkDataArray> channels = array;
    if (mapped)
    {
      vtkIdType firstNaN = -1;
      channels = mappedColors(array, *source, coefficient, range, reading.material.clamped, firstNaN);
      if (firstNaN >= 0)
      {
        reading.problem = at +
          vertexValueProblem(*source, idOf(firstNaN),
            "it is NaN, which has no colour in the colour map (\"clamp\": true gives it the colour of the range's low "
            "end)");
        continue;
      }
    }
    auto decode = [&](auto& values)
    {
      values.resize(size);
      ChannelDecoding<typename std::decay_t<decltype(values)>::value_type> decoding{ coefficient, *source, encoding,
        width, values, reading.material.clamped };
      if (!vtkArrayDispatch::Dispatch::Execute(channels, decoding))
      {
        decoding(channels.Get()); // other value types, through vtkDataArray's own API
      }
      return decoding.firstUnusable;
    };
    const vtkIdType firstUnusable =
      storage == Precision::Float32 ? decode(reading.material.floatValues[c]) : decode(reading.material.values[c]);
    if (firstUnusable >= 0)
    {
      reading.problem = vertexProblem(piece, *source, coefficient, scene.model, firstUnusable, idOf(firstUnusable),
        unusableVertex(channels, firstUnusable, coefficient, width));
    }
  }
  if (reading.problem.empty() && arrays[MaterialCoefficient::Roughness])
  {
    reading.problem = arrayRoughnessProblem(
      piece, reading.material, *arrays[MaterialCoefficient::Roughness], storage, scene.model, idOf);
  }
  if (!reading.problem.empty())
  {
    reading.material = VertexMaterial();
  }
  else if (reading.material.ambientIsDiffuse)
  {
    for (std::uint8_t& bits : reading.material.clamped) // ka's values are kd's, clamped alike
    {
      bits |= (bits & clampedBit(MaterialCoefficient::Diffuse)) ? clampedBit(MaterialCoefficient::Ambient) : 0;
    }
  }
  return reading;
}
}
