#include "ShadeLabImportedParts.h"

#include "vtkActor.h"
#include "vtkAlgorithm.h"
#include "vtkAppendPolyData.h"
#include "vtkCellArray.h"
#include "vtkCleanPolyData.h"
#include "vtkDataArray.h"
#include "vtkFieldData.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkInformationDoubleVectorKey.h"
#include "vtkMapper.h"
#include "vtkMatrix4x4.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkProp.h"
#include "vtkStringArray.h"
#include "vtkTexture.h"
#include "vtkTransform.h"
#include "vtkTransformPolyDataFilter.h"
#include "vtkUnsignedCharArray.h"

#include "ImageFile.h"
#include "MaterialArrays.h"
#include "MetallicRoughness.h"
#include "NumberText.h"
#include "ShadeLabMeshPolygons.h"
#include "TextureFootprint.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
#include <memory>
#include <optional>

namespace shadelab
{
namespace
{
/// How a texture's integer texels encode their values: a colour's in sRGB (MTL's and glTF's
/// convention for a base colour), a metallic-roughness texture's linearly.
enum class TexelEncoding
{
  Srgb,
  Linear,
};

/// The texture's image as linear RGB: 8- and 16-bit channels over their largest value, decoded
/// as `encoding` says; floating-point ones taken as linear; one or two channels are a grey (as
/// VTK's renderer draws them). An empty image where it has none.
RgbImage linearImage(vtkTexture* texture, TexelEncoding encoding)
{
  RgbImage image;
  if (vtkAlgorithm* source = texture->GetInputAlgorithm())
  {
    source->Update();
  }
  vtkImageData* data = texture->GetInput();
  vtkDataArray* scalars = data ? data->GetPointData()->GetScalars() : nullptr;
  int dimensions[3] = { 0, 0, 0 };
  if (data)
  {
    data->GetDimensions(dimensions);
  }
  if (!scalars || dimensions[0] < 1 || dimensions[1] < 1 || scalars->GetNumberOfTuples() == 0)
  {
    return image;
  }
  const bool encoded = scalars->GetDataType() != VTK_FLOAT && scalars->GetDataType() != VTK_DOUBLE;
  const double scale = encoded ? scalars->GetDataTypeMax() : 1.0;
  const int components = scalars->GetNumberOfComponents();
  auto channel = [&](vtkIdType texel, int c)
  {
    const double value = scalars->GetComponent(texel, components < 3 ? 0 : c) / scale;
    return encoded && encoding == TexelEncoding::Srgb ? srgbToLinear(value) : value;
  };
  image.width = dimensions[0];
  image.height = dimensions[1];
  image.texels.resize(std::size_t(image.width) * std::size_t(image.height));
  for (vtkIdType t = 0; t < vtkIdType(image.texels.size()); ++t)
  {
    image.texels[std::size_t(t)] = Rgb(channel(t, 0), channel(t, 1), channel(t, 2));
  }
  return image;
}

/// The largest texture read through OpenImageIO: 8192 x 8192 texels, 1.6 GB as linear RGB.
constexpr std::size_t maxTextureTexels = std::size_t(8192) * 8192;

/// A texture file that VTK's importer does not read (OpenEXR, Radiance .hdr, ...), read through
/// OpenImageIO (ImageFile.h) as linear RGB: floating-point channels as they are, integer ones
/// sRGB-decoded as linearImage decodes a colour's (an MTL's map_Kd), one or two channels a grey. Empty, with problem
/// set to why, where it cannot be read.
RgbImage imageFileTexture(const std::string& fileName, std::string& problem)
{
  RgbImage image;
  try
  {
    const std::unique_ptr<ImageFile> file = ImageFile::open(fileName);
    const std::size_t width = std::size_t(std::max(file->width(), 0)),
                      height = std::size_t(std::max(file->height(), 0));
    std::error_code ignored;
    if (width == 0 || height == 0 || width * height > maxTextureTexels ||
      width * height > mostTexelsIn(std::filesystem::file_size(fileName, ignored)))
    {
      problem = "its header declares " + std::to_string(width) + " x " + std::to_string(height) +
        " texels, which ShadeLab does not take (at most 8192 x 8192, and no more than the file can hold)";
      return image;
    }
    const int channels = file->channels() >= 3 ? 3 : 1;
    std::vector<float> pixels(width * height * std::size_t(channels));
    file->read(channels, pixels.data());
    const bool linear = file->floatingPoint();
    image.width = int(width);
    image.height = int(height);
    image.texels.resize(width * height);
    for (std::size_t row = 0; row < height; ++row)
    {
      for (std::size_t column = 0; column < width; ++column)
      {
        // The file's rows run from the top, the image's from texture coordinate v = 0, the bottom.
        const float* pixel = &pixels[((height - 1 - row) * width + column) * std::size_t(channels)];
        Rgb& texel = image.texels[row * width + column];
        for (int c = 0; c < 3; ++c)
        {
          const double value = pixel[channels == 3 ? c : 0];
          texel[c] = linear ? value : srgbToLinear(value);
        }
      }
    }
  }
  catch (const std::bad_alloc&)
  {
    throw; // the reader's own message for memory that ran out
  }
  catch (const std::exception& error)
  {
    // ImageFile's messages start with the path, which the note gives already.
    const std::string why = error.what();
    problem = why.rfind(fileName + ": ", 0) == 0 ? why.substr(fileName.size() + 2) : why;
    problem = problem.size() > 160 ? problem.substr(0, 157) + "..." : problem; // the note's end must fit
    image = RgbImage{};
  }
  return image;
}

/// Clamps each texel value outside [0, 1] (a floating-point texture's HDR value, a negative or
/// NaN one) into it, since the texture multiplies what must stay in [0, 1] (`multiplies`: "kd,
/// a reflectance"); says so in skipped, naming the texture (`texture`: "its texture").
void clampIntoUnitRange(RgbImage& image, const std::string& partName, const std::string& texture,
  const std::string& multiplies, std::vector<std::string>& skipped)
{
  std::size_t clamped = 0, notANumber = 0;
  double lowest = 0, highest = 1;
  for (Rgb& texel : image.texels)
  {
    for (int c = 0; c < 3; ++c)
    {
      const double value = texel[c];
      notANumber += std::isnan(value) ? 1 : 0;
      lowest = std::isnan(value) ? lowest : std::min(lowest, value);
      highest = std::isnan(value) ? highest : std::max(highest, value);
      texel[c] = std::isnan(value) ? 0.0 : std::clamp(value, 0.0, 1.0);
      clamped += texel[c] != value ? 1 : 0;
    }
  }
  if (clamped > 0)
  {
    std::string range = lowest < 0 ? "as low as " + withDigits(lowest, 4) : "";
    range += highest > 1 ? (range.empty() ? "" : ", ") + std::string("as high as ") + withDigits(highest, 4) : "";
    range += notANumber > 0 ? (range.empty() ? "" : ", ") + countOf(notANumber, "NaN") : "";
    skipped.push_back("part '" + partName + "': " + texture + " has " + countOf(clamped, "texel value") +
      " outside [0, 1] (" + range + "): clamped into it, since the texture multiplies " + multiplies);
  }
}

/// The transform through which VTK's renderer samples the part's textures: the transform of the
/// actor's texture where it has one (vtkOBJImporter's `map_Kd -s`, which vtkActor puts in place
/// of the other at render time), else the actor's GeneralTextureTransform (vtkGLTFImporter's
/// v -> 1 - v, since glTF's images start at their top row and VTK's at their bottom one): a
/// row-major 4 x 4 matrix, which VTK's mapper multiplies (u, v, 0, 1) by. None where it has neither.
std::optional<std::array<double, 16>> textureTransform(vtkActor* actor)
{
  std::array<double, 16> m{};
  vtkInformation* keys = actor->GetPropertyKeys();
  if (vtkTexture* texture = actor->GetTexture(); texture && texture->GetTransform())
  {
    vtkMatrix4x4::DeepCopy(m.data(), texture->GetTransform()->GetMatrix());
    return m;
  }
  if (keys && keys->Has(vtkProp::GeneralTextureTransform()) && keys->Length(vtkProp::GeneralTextureTransform()) == 16)
  {
    std::copy_n(keys->Get(vtkProp::GeneralTextureTransform()), 16, m.begin());
    return m;
  }
  return std::nullopt;
}

/// The texture coordinates (u, v) through the transform m, where VTK samples the texture.
std::array<double, 2> sampledCoordinates(const std::optional<std::array<double, 16>>& m, double u, double v)
{
  const double w = m ? (*m)[12] * u + (*m)[13] * v + (*m)[15] : 0.0;
  return w == 0
    ? std::array<double, 2>{ u, v }
    : std::array<double, 2>{ ((*m)[0] * u + (*m)[1] * v + (*m)[3]) / w, ((*m)[4] * u + (*m)[5] * v + (*m)[7]) / w };
}

/// The texture's colour at each point, averaged over the texels it stands for (TextureFootprint.h),
/// where the actor's renderer samples it (textureTransform).
std::vector<Rgb> textureColors(vtkActor* actor, vtkPolyData* part, const RgbImage& image, vtkDataArray* tcoords)
{
  const std::optional<std::array<double, 16>> transform = textureTransform(actor);
  const vtkIdType points = part->GetNumberOfPoints();
  std::vector<std::array<double, 3>> positions(std::size_t(points), std::array<double, 3>{});
  std::vector<std::array<double, 2>> uv(std::size_t(points), std::array<double, 2>{});
  for (vtkIdType p = 0; p < points; ++p)
  {
    part->GetPoint(p, positions[std::size_t(p)].data());
    uv[std::size_t(p)] = sampledCoordinates(transform, tcoords->GetComponent(p, 0), tcoords->GetComponent(p, 1));
  }
  const std::vector<double> sides =
    texelFootprints(positions, uv, MeshPolygons(part).list(), image.width, image.height);
  const BoxFilteredTexture texture(image);
  std::vector<Rgb> colors(static_cast<std::size_t>(points));
  for (std::size_t p = 0; p < colors.size(); ++p)
  {
    colors[p] = texture.mean(uv[p][0], uv[p][1], sides[p]);
  }
  return colors;
}

vtkSmartPointer<vtkFloatArray> constantArray(const char* name, vtkIdType points, const std::vector<double>& value)
{
  auto array = vtkSmartPointer<vtkFloatArray>::New();
  array->SetName(name);
  array->SetNumberOfComponents(int(value.size()));
  array->SetNumberOfTuples(points);
  for (int c = 0; c < int(value.size()); ++c)
  {
    array->FillComponent(c, value[std::size_t(c)]);
  }
  return array;
}

/// Whether every point of the part is a corner of one of its cells.
bool everyPointUsed(vtkPolyData* part)
{
  std::vector<bool> used(std::size_t(part->GetNumberOfPoints()), false);
  vtkIdType count;
  const vtkIdType* ids;
  for (vtkCellArray* cells : { part->GetVerts(), part->GetLines(), part->GetPolys(), part->GetStrips() })
  {
    for (cells->InitTraversal(); cells->GetNextCell(count, ids);)
    {
      for (vtkIdType k = 0; k < count; ++k)
      {
        used[std::size_t(ids[k])] = true;
      }
    }
  }
  return std::find(used.begin(), used.end(), false) == used.end();
}

/// The part's polygons where the actor places them, with only the points they use: VTK's
/// OBJ importer gives every part the whole file's points, and the glTF importer a node its
/// transform.
vtkSmartPointer<vtkPolyData> placedPart(vtkActor* actor, vtkPolyData* polygons)
{
  auto part = vtkSmartPointer<vtkPolyData>::New();
  part->ShallowCopy(polygons);
  if (!everyPointUsed(part))
  {
    vtkNew<vtkCleanPolyData> usedPoints;
    usedPoints->SetInputData(part);
    usedPoints->PointMergingOff();
    usedPoints->ConvertLinesToPointsOff();
    usedPoints->ConvertPolysToLinesOff();
    usedPoints->ConvertStripsToPolysOff();
    usedPoints->Update();
    part->ShallowCopy(usedPoints->GetOutput());
  }
  if (!actor->GetMatrix()->IsIdentity())
  {
    vtkNew<vtkTransform> placement;
    placement->SetMatrix(actor->GetMatrix());
    vtkNew<vtkTransformPolyDataFilter> placed;
    placed->SetInputData(part);
    placed->SetTransform(placement);
    placed->Update();
    part->ShallowCopy(placed->GetOutput());
  }
  return part;
}

/// Multiplies each point's colour in the array by colors' (a texture's at the point).
void multiplyColors(vtkFloatArray* array, const std::vector<Rgb>& colors)
{
  for (vtkIdType p = 0; p < array->GetNumberOfTuples(); ++p)
  {
    for (int c = 0; c < 3; ++c)
    {
      array->SetComponent(p, c, array->GetComponent(p, c) * colors[std::size_t(p)][c]);
    }
  }
}

/// glTF's metallic-roughness texture as VTK's importer gives it (its ORM texture: roughness in
/// green, metallic in blue, linear): each point's metallic factor and roughness multiplied by
/// the texture's averaged over the texels the point stands for, and its lecture coefficients
/// made again from them (docs/formulas.md section 7.3). What cannot be used is added to skipped.
void applyMetallicRoughnessTexture(const ImportedPart& part, vtkPolyData* copy, std::vector<std::string>& skipped)
{
  vtkPointData* pointData = copy->GetPointData();
  vtkDataArray* tcoords = pointData->GetTCoords();
  RgbImage image = linearImage(part.metallicRoughnessTexture, TexelEncoding::Linear);
  if (image.texels.empty() || !tcoords || tcoords->GetNumberOfComponents() < 2)
  {
    skipped.push_back("part '" + part.name + "': its metallic-roughness texture cannot be read: " +
      (image.texels.empty() ? "it has no image" : "the part has no texture coordinates") +
      "; shaded with its metallic and roughness factors alone");
    return;
  }
  clampIntoUnitRange(image, part.name, "its metallic-roughness texture", "the metallic factor and roughness", skipped);
  const std::vector<Rgb> means = textureColors(part.actor, copy, image, tcoords);
  vtkDataArray* metallic = pointData->GetArray(materialMetallicArrayName);
  vtkDataArray* roughness = pointData->GetArray(materialRoughnessArrayName);
  vtkDataArray* base = pointData->GetArray(materialBaseColorArrayName);
  std::size_t smooth = 0;
  for (vtkIdType p = 0; p < copy->GetNumberOfPoints(); ++p)
  {
    // A mean of texels in [0, 1] may round just outside (a summed-area table's differences).
    const Rgb& mean = means[std::size_t(p)];
    const double m = metallic->GetComponent(p, 0) * std::clamp(mean.z, 0.0, 1.0);
    const double factor = roughness->GetComponent(p, 0);
    const double r = factor * std::clamp(mean.y, 0.0, 1.0);
    metallic->SetComponent(p, 0, m);
    roughness->SetComponent(p, 0, r);
    smooth += r == 0 && factor > 0 ? 1 : 0; // a factor of 0 has the file's own note
    // As without the texture (partWithMaterial, docs/formulas.md section 7.3): kd from the
    // textured base colour, ka, ks (F0) and the shininess from the part's own.
    const double* textured = base->GetTuple3(p);
    const LectureCoefficients own = lectureCoefficients(part.material.microfacet->baseColor, m, r);
    const Rgb kd = lectureCoefficients(Rgb(textured[0], textured[1], textured[2]), m, r).kd;
    pointData->GetArray(materialKaArrayName)->SetTuple3(p, own.kd.x, own.kd.y, own.kd.z);
    pointData->GetArray(materialKdArrayName)->SetTuple3(p, kd.x, kd.y, kd.z);
    pointData->GetArray(materialKsArrayName)->SetTuple3(p, own.ks.x, own.ks.y, own.ks.z);
    pointData->GetArray(materialShininessArrayName)->SetComponent(p, 0, own.shininess);
  }
  if (smooth > 0)
  {
    skipped.push_back("part '" + part.name + "': its metallic-roughness texture makes the roughness 0 at " +
      (smooth == 1 ? std::string("1 vertex") : std::to_string(smooth) + " vertices") +
      ", which the vtk_pbr model refuses (VTK's GGX distribution is 0/0 "
      "in the mirror direction)");
  }
}

/// The part with its index and material as point arrays, the metallic-roughness ones too where
/// withMicrofacet; a texture that cannot be used is added to skipped.
vtkSmartPointer<vtkPolyData> partWithMaterial(
  const ImportedPart& part, vtkPolyData* polygons, int index, bool withMicrofacet, std::vector<std::string>& skipped)
{
  vtkSmartPointer<vtkPolyData> copy = placedPart(part.actor, polygons);
  vtkPointData* pointData = copy->GetPointData();
  const vtkIdType points = copy->GetNumberOfPoints();
  // vtkOBJImporter leaves its normals and texture coordinates unnamed, which a .vtp cannot hold.
  for (vtkDataArray* array : { pointData->GetNormals(), pointData->GetTCoords() })
  {
    if (array && !array->GetName())
    {
      array->SetName(array == pointData->GetNormals() ? "Normals" : "TCoords");
    }
  }
  const PartMaterial& m = part.material;
  pointData->AddArray(constantArray(partArrayName, points, { double(index) }));
  pointData->AddArray(constantArray(materialKaArrayName, points, { m.ka.x, m.ka.y, m.ka.z }));
  pointData->AddArray(constantArray(materialKsArrayName, points, { m.ks.x, m.ks.y, m.ks.z }));
  pointData->AddArray(constantArray(materialShininessArrayName, points, { m.shininess }));
  vtkSmartPointer<vtkFloatArray> kd = constantArray(materialKdArrayName, points, { m.kd.x, m.kd.y, m.kd.z });
  vtkSmartPointer<vtkFloatArray> baseColor;
  if (withMicrofacet)
  {
    const MicrofacetMaterial& pbr = *m.microfacet;
    baseColor =
      constantArray(materialBaseColorArrayName, points, { pbr.baseColor.x, pbr.baseColor.y, pbr.baseColor.z });
    pointData->AddArray(constantArray(materialMetallicArrayName, points, { pbr.metallic }));
    pointData->AddArray(constantArray(materialRoughnessArrayName, points, { pbr.roughness }));
  }
  // A texture VTK's readers did not take is read through OpenImageIO.
  std::string unread;
  RgbImage image = part.kdTexture ? linearImage(part.kdTexture, TexelEncoding::Srgb)
    : part.textureFile.empty()    ? RgbImage{}
                                  : imageFileTexture(part.textureFile, unread);
  if (!unread.empty())
  {
    skipped.push_back("material '" + part.name + "' names the texture " + part.textureFile +
      ", which neither VTK nor OpenImageIO could read (" + unread + "): shaded with its diffuse colour alone");
  }
  else if (part.kdTexture || !part.textureFile.empty())
  {
    vtkDataArray* tcoords = pointData->GetTCoords();
    if (image.texels.empty())
    {
      skipped.push_back("part '" + part.name + "': its texture has no image: shaded with its diffuse colour alone");
    }
    else if (!tcoords || tcoords->GetNumberOfComponents() < 2)
    {
      skipped.push_back(
        "part '" + part.name + "': textured, but without texture coordinates: shaded with its diffuse colour alone");
    }
    else
    {
      clampIntoUnitRange(image, part.name, "its texture", "kd, a reflectance", skipped);
      const std::vector<Rgb> colors = textureColors(part.actor, copy, image, tcoords);
      multiplyColors(kd, colors);
      if (baseColor)
      {
        multiplyColors(baseColor, colors);
      }
    }
  }
  pointData->AddArray(kd);
  if (baseColor)
  {
    pointData->AddArray(baseColor);
    if (part.metallicRoughnessTexture)
    {
      applyMetallicRoughnessTexture(part, copy, skipped);
    }
  }
  return copy;
}

/// Where some parts are two-sided and others not, the line that says how all are shaded
/// (ownMaterial), naming the two-sided ones; "" where they agree.
std::string mixedSidesNote(vtkStringArray* names, vtkUnsignedCharArray* twoSided)
{
  std::string list;
  vtkIdType count = 0;
  for (vtkIdType p = 0; p < twoSided->GetNumberOfValues(); ++p)
  {
    if (twoSided->GetValue(p) != 0)
    {
      list += (count++ ? ", '" : "'") + names->GetValue(p) + "'";
    }
  }
  if (count == 0 || count == twoSided->GetNumberOfValues())
  {
    return "";
  }
  return std::string(count == 1 ? "part " : "parts ") + list + (count == 1 ? " is" : " are") +
    " double-sided and the others are not: a mesh is shaded on one side or on both, not part by part, so its own "
    "materials shade every part on the side of its normals (a scene's material with \"two_sided\": true shades all "
    "on both, in its own colours; the vtk_pbr model shades all on both, as VTK's PBR shader does)";
}
}

vtkSmartPointer<vtkPolyData> meshOfParts(const std::vector<ImportedPart>& parts, std::vector<std::string>& skipped)
{
  std::vector<vtkSmartPointer<vtkPolyData>> withMaterials;
  auto names = vtkSmartPointer<vtkStringArray>::New();
  names->SetName(partNamesArrayName);
  auto twoSided = vtkSmartPointer<vtkUnsignedCharArray>::New();
  twoSided->SetName(partTwoSidedArrayName);
  // The parts' arrays are appended, so each part needs them all.
  const bool withMicrofacet = !parts.empty() &&
    std::all_of(parts.begin(), parts.end(), [](const ImportedPart& part) { return part.material.microfacet; });
  for (const ImportedPart& part : parts)
  {
    vtkMapper* mapper = part.actor->GetMapper();
    if (mapper && mapper->GetInputAlgorithm())
    {
      mapper->GetInputAlgorithm()->Update();
    }
    auto* polygons = vtkPolyData::SafeDownCast(mapper ? mapper->GetInput() : nullptr);
    if (!polygons || polygons->GetNumberOfCells() == 0)
    {
      continue;
    }
    withMaterials.push_back(partWithMaterial(part, polygons, int(names->GetNumberOfValues()), withMicrofacet, skipped));
    names->InsertNextValue(part.name);
    twoSided->InsertNextValue(part.material.twoSided ? 1 : 0);
  }
  const std::string mixedSides = mixedSidesNote(names, twoSided);
  if (!mixedSides.empty())
  {
    skipped.push_back(mixedSides);
  }
  auto mesh = vtkSmartPointer<vtkPolyData>::New();
  if (withMaterials.size() == 1)
  {
    mesh->ShallowCopy(withMaterials.front()); // one part: nothing to append, nor to copy
  }
  else if (!withMaterials.empty())
  {
    vtkNew<vtkAppendPolyData> append;
    for (vtkPolyData* part : withMaterials)
    {
      append->AddInputData(part);
    }
    append->Update();
    mesh->ShallowCopy(append->GetOutput());
  }
  mesh->GetFieldData()->AddArray(names);
  mesh->GetFieldData()->AddArray(twoSided);
  return mesh;
}

bool hasOwnMaterials(vtkPolyData* mesh)
{
  vtkPointData* pointData = mesh->GetPointData();
  return pointData->HasArray(partArrayName) && pointData->HasArray(materialKaArrayName) &&
    pointData->HasArray(materialKdArrayName) && pointData->HasArray(materialKsArrayName) &&
    pointData->HasArray(materialShininessArrayName);
}

bool hasOwnMicrofacetMaterials(vtkPolyData* mesh)
{
  vtkPointData* pointData = mesh->GetPointData();
  return hasOwnMaterials(mesh) && pointData->HasArray(materialBaseColorArrayName) &&
    pointData->HasArray(materialMetallicArrayName) && pointData->HasArray(materialRoughnessArrayName);
}

bool shadesWithOwnMaterials(const Scene& scene, vtkPolyData* mesh, bool colorByArray)
{
  const bool modelsArrays = (scene.model == ShadingModel::Lecture && hasOwnMaterials(mesh)) ||
    (scene.model == ShadingModel::VtkPbr && hasOwnMicrofacetMaterials(mesh));
  return !scene.materialGiven && !colorByArray && modelsArrays;
}

bool everyPartTwoSided(vtkPolyData* mesh)
{
  auto* twoSided = vtkUnsignedCharArray::SafeDownCast(mesh->GetFieldData()->GetAbstractArray(partTwoSidedArrayName));
  return twoSided && twoSided->GetNumberOfValues() > 0 &&
    std::all_of(twoSided->Begin(), twoSided->End(), [](unsigned char value) { return value != 0; });
}

Material ownMaterial(const Scene& scene, vtkPolyData* mesh)
{
  Material material = scene.material;
  material.spectra = {};
  material.twoSided = everyPartTwoSided(mesh);
  auto fromArray = [&](MaterialCoefficient coefficient, const char* name)
  {
    ArrayCoefficient array;
    array.array = name;
    array.encoding = ArrayEncoding::Linear;
    array.ownMaterial = true;
    material.arrays[coefficient] = array;
  };
  if (scene.model == ShadingModel::VtkPbr)
  {
    fromArray(MaterialCoefficient::Diffuse, materialBaseColorArrayName);
    fromArray(MaterialCoefficient::Metallic, materialMetallicArrayName);
    fromArray(MaterialCoefficient::Roughness, materialRoughnessArrayName);
    // An array's number in the material is its scale, 1 (Material).
    material.microfacet.baseColor = Rgb(1.0);
    material.microfacet.metallic = material.microfacet.roughness = 1.0;
    return material;
  }
  fromArray(MaterialCoefficient::Ambient, materialKaArrayName);
  fromArray(MaterialCoefficient::Diffuse, materialKdArrayName);
  fromArray(MaterialCoefficient::Specular, materialKsArrayName);
  fromArray(MaterialCoefficient::Shininess, materialShininessArrayName);
  // An array's number in the material is its bound (Material): the scale, 1.
  material.ka = material.kd = material.ks = Rgb(1.0);
  material.shininess = 1.0;
  return material;
}
}
