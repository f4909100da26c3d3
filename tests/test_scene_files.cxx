// Meshes with their own materials (docs/guide/scene-files.md): an OBJ file read with its MTL
// file by VTK's importer, each part shaded with its own Kd against the closed form, a texture
// decoded and placed texel by texel, a scene's material winning over the file's, and what a
// missing library or texture leaves; a glTF file's lights against the same lights written by
// hand, as .gltf and as .glb, its material's coefficients and sides; an OBJ that VTK's exporter wrote
// read back with its actors' properties.
#include "FilterRun.h"
#include "TestFolder.h"
#include "TestPaths.h"
#include "TwoPartObj.h"

#include "GltfScene.h"
#include "MeshFiles.h"
#include "MetallicRoughness.h"
#include "SceneFile.h"
#include "ShadeLabImportedParts.h"
#include "ShadingFlags.h"

#include "vtkActor.h"
#include "vtkDataArray.h"
#include "vtkFieldData.h"
#include "vtkGLTFExporter.h"
#include "vtkImageData.h"
#include "vtkOBJExporter.h"
#include "vtkPNGWriter.h"
#include "vtkPointData.h"
#include "vtkPolyDataMapper.h"
#include "vtkProperty.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"
#include "vtkSphereSource.h"
#include "vtkUnsignedCharArray.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <tuple>
#include <unistd.h>

#include <nlohmann/json.hpp>

namespace
{
using namespace shadelab;
namespace fs = std::filesystem;

using SceneFiles = shadelab::testing::TestFolder;
using shadelab::testing::partsMtl;
using shadelab::testing::twoPartObj;

/// The 8-bit texels of a 4 x 2 texture, row 0 first (texture v = 0).
const unsigned char texels[2][4][3] = { { { 255, 0, 0 }, { 0, 255, 0 }, { 0, 0, 255 }, { 200, 100, 50 } },
  { { 10, 20, 30 }, { 128, 128, 128 }, { 255, 255, 255 }, { 0, 0, 0 } } };

void writeTexture(const std::string& path)
{
  vtkNew<vtkImageData> image;
  image->SetDimensions(4, 2, 1);
  image->AllocateScalars(VTK_UNSIGNED_CHAR, 3);
  for (int row = 0; row < 2; ++row)
  {
    for (int column = 0; column < 4; ++column)
    {
      for (int c = 0; c < 3; ++c)
      {
        static_cast<unsigned char*>(image->GetScalarPointer(column, row, 0))[c] = texels[row][column][c];
      }
    }
  }
  vtkNew<vtkPNGWriter> writer;
  writer->SetInputData(image);
  writer->SetFileName(path.c_str());
  writer->Write();
}

/// sRGB's decoding (IEC 61966-2-1), written out here rather than called.
double decoded(unsigned char value)
{
  const double c = value / 255.0;
  return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4);
}

/// One white distant light straight down onto the parts, and no material unless given.
Scene sunScene(const std::string& material = "")
{
  return parseScene(R"({ "viewer": { "position": [0, 0, 10] },)" + material +
      R"( "lights": [ { "name": "sun", "type": "distant", "direction": [0, 0, -1] } ] })",
    "scene.json");
}

TEST_F(SceneFiles, EachPartIsShadedWithItsOwnMaterialAndTexture)
{
  writeTexture((folder / "texture.png").string());
  file("parts.mtl", partsMtl);
  vtkSmartPointer<vtkPolyData> mesh = app::readMesh(file("parts.obj", twoPartObj));
  ASSERT_TRUE(hasOwnMaterials(mesh));
  auto* names = vtkStringArray::SafeDownCast(mesh->GetFieldData()->GetAbstractArray(partNamesArrayName));
  ASSERT_NE(names, nullptr);
  ASSERT_EQ(names->GetNumberOfValues(), 2);
  EXPECT_EQ(names->GetValue(0), "red");
  EXPECT_EQ(names->GetValue(1), "tex");

  vtkSmartPointer<vtkPolyData> output =
    shadelab::testing::shadeWithFilter(mesh, sunScene(), { "sun_diffuse", "sun_specular" });
  vtkDataArray* diffuse = output->GetPointData()->GetArray("sun_diffuse");
  vtkDataArray* part = output->GetPointData()->GetArray(partArrayName);
  vtkDataArray* shininess = output->GetPointData()->GetArray(materialShininessArrayName);
  vtkDataArray* uv = output->GetPointData()->GetTCoords();
  ASSERT_TRUE(diffuse && part && shininess && uv);
  int texelsSeen = 0;
  for (vtkIdType p = 0; p < output->GetNumberOfPoints(); ++p)
  {
    // n.s = 1 and the light is white of intensity 1: the diffuse term is kd itself.
    if (part->GetComponent(p, 0) == 0)
    {
      const double kd[3] = { 0.7, 0.2, 0.1 };
      for (int c = 0; c < 3; ++c)
      {
        EXPECT_EQ(diffuse->GetComponent(p, c), double(float(kd[c]))) << "vertex " << p;
      }
      EXPECT_EQ(shininess->GetComponent(p, 0), 20);
      continue;
    }
    const int column = int(std::floor(uv->GetComponent(p, 0) * 4)), row = int(std::floor(uv->GetComponent(p, 1) * 2));
    const double kd[3] = { 0.9, 0.8, 0.6 };
    for (int c = 0; c < 3; ++c)
    {
      EXPECT_NEAR(diffuse->GetComponent(p, c), float(kd[c]) * decoded(texels[row][column][c]), 1e-6)
        << "vertex " << p << ", texel " << column << ", " << row;
    }
    EXPECT_EQ(shininess->GetComponent(p, 0), 64);
    ++texelsSeen;
  }
  EXPECT_EQ(texelsSeen, 18); // the 6 triangles' corners, as the importer keeps them
}

// `map_Kd -s 0.5 1 1`: VTK's importer puts the scale in the texture's transform and its
// renderer samples at (0.5 u, v); so does ShadeLab. Each texel's triangles then fall in the
// texel at half their column.
TEST_F(SceneFiles, AnMtlTexturesScaleIsWhereVtkSamplesIt)
{
  writeTexture((folder / "texture.png").string());
  std::string mtl = partsMtl;
  mtl.replace(mtl.find("map_Kd texture.png"), 18, "map_Kd -s 0.5 1 1 texture.png");
  file("parts.mtl", mtl);
  vtkSmartPointer<vtkPolyData> mesh = app::readMesh(file("parts.obj", twoPartObj));
  vtkPointData* points = mesh->GetPointData();
  vtkDataArray* uv = points->GetTCoords();
  int texelsSeen = 0;
  for (vtkIdType p = 0; p < mesh->GetNumberOfPoints(); ++p)
  {
    if (points->GetArray(partArrayName)->GetComponent(p, 0) != 1)
    {
      continue;
    }
    const int column = int(std::floor(0.5 * uv->GetComponent(p, 0) * 4)),
              row = int(std::floor(uv->GetComponent(p, 1) * 2));
    const double kd[3] = { 0.9, 0.8, 0.6 };
    for (int c = 0; c < 3; ++c)
    {
      EXPECT_NEAR(
        points->GetArray(materialKdArrayName)->GetComponent(p, c), float(kd[c]) * decoded(texels[row][column][c]), 1e-6)
        << "vertex " << p << ", texel " << column << ", " << row;
    }
    ++texelsSeen;
  }
  EXPECT_EQ(texelsSeen, 18);
}

TEST_F(SceneFiles, AScenesMaterialWinsOverTheFiles)
{
  writeTexture((folder / "texture.png").string());
  file("parts.mtl", partsMtl);
  vtkSmartPointer<vtkPolyData> mesh = app::readMesh(file("parts.obj", twoPartObj));
  const Scene scene = sunScene(R"( "material": { "kd": [0.25, 0.5, 0.75] },)");
  EXPECT_FALSE(shadesWithOwnMaterials(scene, mesh, false));
  vtkSmartPointer<vtkPolyData> output = shadelab::testing::shadeWithFilter(mesh, scene, { "sun_diffuse" });
  vtkDataArray* diffuse = output->GetPointData()->GetArray("sun_diffuse");
  for (vtkIdType p = 0; p < output->GetNumberOfPoints(); ++p)
  {
    EXPECT_EQ(diffuse->GetComponent(p, 0), 0.25);
    EXPECT_EQ(diffuse->GetComponent(p, 2), 0.75);
  }
  EXPECT_TRUE(shadesWithOwnMaterials(sunScene(), mesh, false));
  EXPECT_FALSE(shadesWithOwnMaterials(sunScene(), mesh, true)); // coloured by an array instead
}

TEST_F(SceneFiles, FacesTheImporterLeavesOutKeepTheWholeMesh)
{
  // VTK 9.1's importer drops the red faces, which have no texture coordinates where the others
  // have: the file is read whole by the mesh reader instead, without materials.
  std::string obj = twoPartObj;
  obj.replace(obj.find("f 1/1/1 2/2/1 3/6/1"), 19, "f 1//1 2//1 3//1");
  file("parts.mtl", partsMtl);
  vtkSmartPointer<vtkPolyData> mesh = app::readMesh(file("parts.obj", obj));
  EXPECT_FALSE(hasOwnMaterials(mesh));
  EXPECT_EQ(mesh->GetNumberOfPolys(), 8);
}

TEST_F(SceneFiles, TheMtlFilesNumbersAreReadAsTheFileStatesThem)
{
  // illum 1 (no highlights) has no specular term, though Ks is given: VTK's importer would keep
  // Ks but not Ns; a grey Kd given as one number; a material the MTL lacks: VTK's defaults.
  std::string mtl = partsMtl;
  mtl.replace(mtl.find("Ns 20"), 5, "Ns 40\nillum 1");
  mtl.replace(mtl.find("Kd 0.9 0.8 0.6"), 14, "Kd 0.5");
  mtl.replace(mtl.find("map_Kd texture.png"), 18, "");
  file("parts.mtl", mtl);
  vtkSmartPointer<vtkPolyData> mesh = app::readMesh(file("parts.obj", twoPartObj));
  vtkPointData* points = mesh->GetPointData();
  for (vtkIdType p = 0; p < mesh->GetNumberOfPoints(); ++p)
  {
    const bool red = points->GetArray(partArrayName)->GetComponent(p, 0) == 0;
    EXPECT_EQ(points->GetArray(materialKsArrayName)->GetComponent(p, 0), red ? 0 : 0.2f);
    EXPECT_EQ(points->GetArray(materialShininessArrayName)->GetComponent(p, 0), red ? 40 : 64);
    EXPECT_EQ(points->GetArray(materialKdArrayName)->GetComponent(p, 2), red ? 0.1f : 0.5f);
  }
  std::string undefined = twoPartObj;
  undefined.replace(undefined.find("usemtl tex"), 10, "usemtl gone");
  vtkSmartPointer<vtkPolyData> gone = app::readMesh(file("gone.obj", undefined));
  vtkPointData* goneData = gone->GetPointData();
  int defaults = 0;
  for (vtkIdType p = 0; p < gone->GetNumberOfPoints(); ++p)
  {
    if (goneData->GetArray(materialKdArrayName)->GetComponent(p, 0) == 1)
    {
      EXPECT_EQ(goneData->GetArray(materialKsArrayName)->GetComponent(p, 0), 0);
      ++defaults;
    }
  }
  EXPECT_EQ(defaults, 18);
}

TEST_F(SceneFiles, TheSpectralModeAsksForAMaterialOfItsOwn)
{
  writeTexture((folder / "texture.png").string());
  file("parts.mtl", partsMtl);
  vtkSmartPointer<vtkPolyData> mesh = app::readMesh(file("parts.obj", twoPartObj));
  const Scene spectral =
    parseScene(R"({ "spectral": {}, "lights": [ { "type": "distant", "direction": [0, 0, -1] } ] })", "spectral.json");
  EXPECT_EQ(shadelab::testing::filterError(mesh, spectral),
    "the mesh's own materials (a scene file's parts, RGB per point) cannot be shaded in the spectral mode, which "
    "takes spectra or numbers: give the scene a \"material\"");
  Scene withMaterial = spectral;
  withMaterial.materialGiven = true;
  EXPECT_EQ(shadelab::testing::filterError(mesh, withMaterial), "");
}

TEST_F(SceneFiles, AMissingLibraryLeavesTheMeshAlone)
{
  vtkSmartPointer<vtkPolyData> mesh = app::readMesh(file("parts.obj", twoPartObj));
  EXPECT_FALSE(hasOwnMaterials(mesh));
  EXPECT_EQ(mesh->GetNumberOfPolys(), 8);
}

TEST_F(SceneFiles, AMissingTextureLeavesTheDiffuseColour)
{
  file("parts.mtl", partsMtl);
  vtkSmartPointer<vtkPolyData> mesh = app::readMesh(file("parts.obj", twoPartObj));
  vtkSmartPointer<vtkPolyData> output = shadelab::testing::shadeWithFilter(mesh, sunScene(), { "sun_diffuse" });
  vtkDataArray* diffuse = output->GetPointData()->GetArray("sun_diffuse");
  vtkDataArray* part = output->GetPointData()->GetArray(partArrayName);
  for (vtkIdType p = 0; p < output->GetNumberOfPoints(); ++p)
  {
    EXPECT_EQ(diffuse->GetComponent(p, 1), double(part->GetComponent(p, 0) == 0 ? 0.2f : 0.8f));
  }
}
}

namespace
{
/// A glTF file's binary buffer: a unit square at height 0.5 (its node's translation), normals +y,
/// two triangles.
std::string squareBuffer()
{
  const float positions[4][3] = { { -1, 0, -1 }, { 1, 0, -1 }, { 1, 0, 1 }, { -1, 0, 1 } };
  const float normals[4][3] = { { 0, 1, 0 }, { 0, 1, 0 }, { 0, 1, 0 }, { 0, 1, 0 } };
  const std::uint16_t indices[8] = { 0, 2, 1, 0, 3, 2, 0, 0 }; // padded to 4 bytes
  std::string bytes(reinterpret_cast<const char*>(positions), sizeof(positions));
  bytes.append(reinterpret_cast<const char*>(normals), sizeof(normals));
  bytes.append(reinterpret_cast<const char*>(indices), sizeof(indices));
  return bytes;
}

/// The glTF JSON of the square with a point, a spot and a directional light; `buffer` is the
/// buffer's entry (with or without a uri).
std::string lampsGltf(const std::string& buffer)
{
  return R"({ "asset": { "version": "2.0" }, "extensionsUsed": ["KHR_lights_punctual"],
  "extensions": { "KHR_lights_punctual": { "lights": [
    { "name": "bulb", "type": "point", "color": [1, 0.9, 0.8], "intensity": 3, "range": 10 },
    { "type": "spot", "color": [0.5, 0.6, 1], "intensity": 5, "spot": { "innerConeAngle": 0.2, "outerConeAngle": 0.6 } },
    { "type": "directional", "intensity": 0.5 } ] } },
  "scene": 0, "scenes": [ { "nodes": [0, 1, 2, 3] } ],
  "nodes": [ { "mesh": 0, "translation": [0, 0.5, 0] },
    { "extensions": { "KHR_lights_punctual": { "light": 0 } }, "translation": [0.3, 2, 0.1] },
    { "extensions": { "KHR_lights_punctual": { "light": 1 } }, "translation": [0, 3, 0],
      "rotation": [-0.70710678, 0, 0, 0.70710678] },
    { "extensions": { "KHR_lights_punctual": { "light": 2 } }, "rotation": [-0.38268343, 0, 0, 0.92387953] } ],
  "meshes": [ { "primitives": [ { "attributes": { "POSITION": 0, "NORMAL": 1 }, "indices": 2, "material": 0 } ] } ],
  "materials": [ { "pbrMetallicRoughness": { "baseColorFactor": [0.8, 0.5, 0.3, 1], "metallicFactor": 0.1,
    "roughnessFactor": 0.7 } } ],
  "buffers": [ )" +
    buffer + R"( ],
  "bufferViews": [ { "buffer": 0, "byteOffset": 0, "byteLength": 48 }, { "buffer": 0, "byteOffset": 48, "byteLength": 48 },
    { "buffer": 0, "byteOffset": 96, "byteLength": 12 } ],
  "accessors": [ { "bufferView": 0, "componentType": 5126, "count": 4, "type": "VEC3", "min": [-1, 0, -1], "max": [1, 0, 1] },
    { "bufferView": 1, "componentType": 5126, "count": 4, "type": "VEC3" },
    { "bufferView": 2, "componentType": 5123, "count": 6, "type": "SCALAR" } ] })";
}

/// The same lights written by hand in ShadeLab's JSON, from KHR_lights_punctual's conventions:
/// each at its node's origin, pointing down its node's -z (rotated -90 and -45 degrees about x).
const char* const lampsScene = R"({ "lights": [
  { "name": "directional", "type": "distant", "direction": [0, -0.70710678, -0.70710678], "intensity": 0.5 },
  { "name": "spot", "type": "spot", "position": [0, 3, 0], "direction": [0, -1, 0], "color": [0.5, 0.6, 1],
    "intensity": 5, "cone": { "model": "gltf", "inner_angle": 11.459155902616464, "outer_angle": 34.37746770784939 } },
  { "name": "bulb", "type": "point", "position": [0.3, 2, 0.1], "color": [1, 0.9, 0.8], "intensity": 3,
    "attenuation": { "model": "gltf_range", "range": 10 } } ] })";

/// The output's per-light diffuse and specular terms, light by light in the order given.
std::vector<double> lightTerms(vtkPolyData* output, const std::vector<std::string>& lights)
{
  std::vector<double> values;
  for (const std::string& light : lights)
  {
    for (const char* term : { "_diffuse", "_specular" })
    {
      vtkDataArray* array = output->GetPointData()->GetArray((light + term).c_str());
      EXPECT_NE(array, nullptr) << light << term;
      for (vtkIdType i = 0; array && i < array->GetNumberOfValues(); ++i)
      {
        values.push_back(array->GetVariantValue(i).ToDouble());
      }
    }
  }
  return values;
}
}

TEST_F(SceneFiles, AGltfFilesLightsShadeAsTheSameSceneInShadeLabsJson)
{
  std::ofstream(folder / "square.bin", std::ios::binary) << squareBuffer();
  vtkSmartPointer<vtkPolyData> mesh =
    app::readMesh(file("lamps.gltf", lampsGltf(R"({ "byteLength": 112, "uri": "square.bin" })")));
  ASSERT_TRUE(hasOwnMaterials(mesh));
  const Scene fromFile = parseScene(app::fileLightsOf(mesh), "lamps.gltf");
  ASSERT_EQ(fromFile.lights.size(), 3u);
  const std::vector<std::string> names = { fromFile.lights[0].name, fromFile.lights[1].name, fromFile.lights[2].name };
  EXPECT_EQ(names, (std::vector<std::string>{ "directional0", "spot1", "bulb" }));
  std::vector<std::string> arrays;
  for (const std::string& name : names)
  {
    arrays.push_back(name + "_diffuse");
    arrays.push_back(name + "_specular");
  }
  const std::vector<double> imported =
    lightTerms(shadelab::testing::shadeWithFilter(mesh, fromFile, arrays, vtkAlgorithm::SINGLE_PRECISION), names);

  Scene byHand = parseScene(lampsScene, "lamps.json");
  std::vector<std::string> handArrays;
  for (const char* name : { "directional", "spot", "bulb" })
  {
    handArrays.push_back(std::string(name) + "_diffuse");
    handArrays.push_back(std::string(name) + "_specular");
  }
  const std::vector<double> written =
    lightTerms(shadelab::testing::shadeWithFilter(mesh, byHand, handArrays, vtkAlgorithm::SINGLE_PRECISION),
      { "directional", "spot", "bulb" });
  ASSERT_EQ(imported.size(), written.size());
  ASSERT_EQ(imported.size(), 3u * 2 * 4 * 3);
  for (std::size_t i = 0; i < imported.size(); ++i)
  {
    // The file's numbers pass through float32 (the importer's) and radians: float rounding.
    EXPECT_NEAR(imported[i], written[i], 2e-6 * std::max(1.0, std::abs(written[i]))) << "value " << i;
  }

  // The same file as one binary .glb: its JSON chunk, then its buffer.
  std::string json = lampsGltf(R"({ "byteLength": 112 })");
  json.append((4 - json.size() % 4) % 4, ' ');
  const std::string buffer = squareBuffer();
  auto word = [](std::uint32_t value) { return std::string(reinterpret_cast<const char*>(&value), 4); };
  std::ofstream(folder / "lamps.glb", std::ios::binary)
    << "glTF" << word(2) << word(std::uint32_t(12 + 8 + json.size() + 8 + buffer.size()))
    << word(std::uint32_t(json.size())) << "JSON" << json << word(std::uint32_t(buffer.size())) << "BIN" << '\0'
    << buffer;
  vtkSmartPointer<vtkPolyData> binary = app::readMesh((folder / "lamps.glb").string());
  EXPECT_EQ(app::fileLightsOf(binary), app::fileLightsOf(mesh));
}

// glTF's doubleSided: the square (normals up) seen from below and lit from below. Double-sided,
// its underside is shaded, turned round: kd I (n.l) / d^2 with n = -y at each vertex. Not
// double-sided (glTF's default), or with no material at all (glTF's default material, which
// VTK's importer leaves without culling), the light is behind its normals and it is dark.
TEST_F(SceneFiles, AGltfsDoubleSidedMaterialIsShadedOnBothSides)
{
  std::ofstream(folder / "square.bin", std::ios::binary) << squareBuffer();
  const Scene below = parseScene(R"({ "viewer": { "position": [0, -3, 0] },
    "lights": [ { "name": "lamp", "type": "point", "position": [0.3, -1, 0.1], "intensity": 3 } ] })",
    "below.json");
  const std::vector<std::string> arrays{ "lamp_diffuse", "shading_flags" };
  const std::string materials = R"("materials": [ { )", itsMaterial = R"(, "material": 0)";
  for (const std::string& material : { "doubleSided", "one-sided", "none" })
  {
    std::string gltf = lampsGltf(R"({ "byteLength": 112, "uri": "square.bin" })");
    const bool doubleSided = material == "doubleSided";
    gltf.insert(gltf.find(materials) + materials.size(), doubleSided ? R"("doubleSided": true, )" : "");
    if (material == "none")
    {
      gltf.erase(gltf.find(itsMaterial), itsMaterial.size());
    }
    vtkSmartPointer<vtkPolyData> mesh = app::readMesh(file("square.gltf", gltf));
    EXPECT_EQ(ownMaterial(Scene{}, mesh).twoSided, doubleSided) << material;
    vtkSmartPointer<vtkPolyData> shaded =
      shadelab::testing::shadeWithFilter(mesh, below, arrays, vtkAlgorithm::DOUBLE_PRECISION);
    vtkDataArray* kd = mesh->GetPointData()->GetArray(materialKdArrayName);
    vtkDataArray* diffuse = shaded->GetPointData()->GetArray("lamp_diffuse");
    vtkDataArray* flags = shaded->GetPointData()->GetArray("shading_flags");
    ASSERT_EQ(shaded->GetNumberOfPoints(), 4);
    for (vtkIdType i = 0; i < 4; ++i)
    {
      const glm::dvec3 p(shaded->GetPoint(i)[0], shaded->GetPoint(i)[1], shaded->GetPoint(i)[2]);
      const glm::dvec3 toLamp = glm::dvec3(0.3, -1, 0.1) - p;
      const double d = glm::length(toLamp);
      for (int c = 0; c < 3; ++c)
      {
        const double expected = doubleSided ? kd->GetComponent(i, c) * 3 * (-toLamp.y / d) / (d * d) : 0.0;
        EXPECT_NEAR(diffuse->GetComponent(i, c), expected, 1e-12) << material << " " << i << " " << c;
      }
      EXPECT_EQ((int(flags->GetComponent(i, 0)) & FlagNormalFlipped) != 0, doubleSided) << material << " " << i;
    }
  }
}

TEST(MetallicRoughness, TheGltfSplitAndTheBlinnPhongExponent)
{
  const LectureCoefficients dielectric = lectureCoefficients(Rgb(0.8, 0.5, 0.3), 0, 1);
  EXPECT_EQ(dielectric.kd, Rgb(0.8, 0.5, 0.3));
  EXPECT_EQ(dielectric.ks, Rgb(0.04));
  EXPECT_EQ(dielectric.shininess, 0); // alpha 1: 2 / 1 - 2
  const LectureCoefficients metal = lectureCoefficients(Rgb(0.9, 0.6, 0.2), 1, 0.5);
  EXPECT_EQ(metal.kd, Rgb(0.0));
  EXPECT_EQ(metal.ks, Rgb(0.9, 0.6, 0.2));
  EXPECT_DOUBLE_EQ(metal.shininess, 2 / std::pow(0.25, 2) - 2); // 30
  const LectureCoefficients half = lectureCoefficients(Rgb(0.5), 0.5, 0.0);
  EXPECT_DOUBLE_EQ(half.ks.x, 0.5 * 0.04 + 0.5 * 0.5);
  EXPECT_NEAR(half.shininess, 2 / std::pow(0.03, 4) - 2, 1e-3); // clamped at 0.03
}

/// Spheres of radius 0.5 as the actors of a render window, for an exporter to write.
struct SpheresToExport
{
  SpheresToExport() { window->AddRenderer(renderer); }

  /// A sphere at `center`; returns its actor's property.
  vtkProperty* add(const double center[3])
  {
    vtkNew<vtkSphereSource> sphere;
    sphere->SetCenter(center);
    vtkNew<vtkPolyDataMapper> mapper;
    mapper->SetInputConnection(sphere->GetOutputPort());
    vtkNew<vtkActor> actor;
    actor->SetMapper(mapper);
    renderer->AddActor(actor);
    return actor->GetProperty();
  }

  vtkNew<vtkRenderer> renderer;
  vtkNew<vtkRenderWindow> window;
};

TEST_F(SceneFiles, AnObjExportedByVtkComesBackWithItsMaterials)
{
  // Two spheres with properties of their own, written by VTK's vtkOBJExporter, which writes
  // Ka = Ambient x AmbientColor, Kd = Diffuse x DiffuseColor, Ks = Specular x SpecularColor and
  // Ns = SpecularPower.
  struct Look
  {
    double diffuse[3], center[3];
  };
  const Look looks[2] = { { { 0.8, 0.2, 0.1 }, { 0, 0, 0 } }, { { 0.1, 0.3, 0.9 }, { 2, 0, 0 } } };
  SpheresToExport spheres;
  for (const Look& look : looks)
  {
    vtkProperty* property = spheres.add(look.center);
    property->SetDiffuseColor(look.diffuse);
    property->SetDiffuse(0.9);
    property->SetAmbientColor(0.05, 0.1, 0.15);
    property->SetAmbient(0.5);
    property->SetSpecularColor(0.3, 0.3, 0.3);
    property->SetSpecular(0.4);
    property->SetSpecularPower(24);
  }
  vtkNew<vtkOBJExporter> exporter;
  exporter->SetRenderWindow(spheres.window);
  exporter->SetFilePrefix((folder / "spheres").string().c_str());
  exporter->Write();

  vtkSmartPointer<vtkPolyData> mesh = app::readMesh((folder / "spheres.obj").string());
  ASSERT_TRUE(hasOwnMaterials(mesh));
  vtkPointData* points = mesh->GetPointData();
  vtkDataArray* part = points->GetArray(partArrayName);
  int seen[2] = { 0, 0 };
  for (vtkIdType p = 0; p < mesh->GetNumberOfPoints(); ++p)
  {
    const int index = int(part->GetComponent(p, 0));
    ASSERT_TRUE(index == 0 || index == 1);
    ++seen[index];
    double position[3];
    mesh->GetPoint(p, position);
    EXPECT_NEAR(std::hypot(position[0] - looks[index].center[0], position[1], position[2]), 0.5, 1e-6) << p;
    for (int c = 0; c < 3; ++c)
    {
      EXPECT_FLOAT_EQ(points->GetArray(materialKdArrayName)->GetComponent(p, c), 0.9 * looks[index].diffuse[c]);
      EXPECT_FLOAT_EQ(points->GetArray(materialKsArrayName)->GetComponent(p, c), 0.4 * 0.3);
    }
    EXPECT_FLOAT_EQ(points->GetArray(materialKaArrayName)->GetComponent(p, 2), 0.5 * 0.15);
    EXPECT_EQ(points->GetArray(materialShininessArrayName)->GetComponent(p, 0), 24);
  }
  EXPECT_GT(seen[0], 0);
  EXPECT_EQ(seen[0], seen[1]);
}

TEST_F(SceneFiles, AGltfExportedByVtkComesBackWithTheMaterialItWrote)
{
  // Two spheres written by VTK 9.1's vtkGLTFExporter, which turns a Phong property into glTF's
  // metallic-roughness: base colour = DiffuseColor, metallic = Specular, roughness =
  // 1 / (1 + 0.2 Specular SpecularPower). Read back, each part has that glTF material in the
  // lecture model (docs/formulas.md section 7.3) and its sphere's points.
  struct Look
  {
    double diffuse[3], center[3], specular, power;
  };
  const Look looks[2] = { { { 0.8, 0.2, 0.1 }, { 0, 0, 0 }, 0.4, 24 }, { { 0.1, 0.3, 0.9 }, { 2, 0, 0 }, 0.1, 5 } };
  SpheresToExport spheres;
  for (const Look& look : looks)
  {
    vtkProperty* property = spheres.add(look.center);
    property->SetDiffuseColor(look.diffuse);
    property->SetSpecular(look.specular);
    property->SetSpecularPower(look.power);
  }
  vtkNew<vtkGLTFExporter> exporter;
  exporter->SetRenderWindow(spheres.window);
  exporter->SetFileName((folder / "spheres.gltf").string().c_str());
  exporter->SaveNormalOn();
  exporter->Write();

  vtkSmartPointer<vtkPolyData> mesh = app::readMesh((folder / "spheres.gltf").string());
  ASSERT_TRUE(hasOwnMaterials(mesh));
  vtkPointData* points = mesh->GetPointData();
  int seen[2] = { 0, 0 };
  for (vtkIdType p = 0; p < mesh->GetNumberOfPoints(); ++p)
  {
    double position[3];
    mesh->GetPoint(p, position);
    const int index = position[0] > 1 ? 1 : 0; // which sphere, whatever the parts' order
    ++seen[index];
    const Look& look = looks[index];
    EXPECT_NEAR(std::hypot(position[0] - look.center[0], position[1], position[2]), 0.5, 1e-6) << p;
    const LectureCoefficients wrote = lectureCoefficients(Rgb(look.diffuse[0], look.diffuse[1], look.diffuse[2]),
      look.specular, 1 / (1 + 0.2 * look.specular * look.power));
    for (int c = 0; c < 3; ++c)
    {
      EXPECT_FLOAT_EQ(points->GetArray(materialKdArrayName)->GetComponent(p, c), wrote.kd[c]);
      EXPECT_FLOAT_EQ(points->GetArray(materialKsArrayName)->GetComponent(p, c), wrote.ks[c]);
    }
    // VTK's loader keeps the factors as floats, whose rounding the exponent 2 / r^4 - 2 multiplies
    // by about 4.
    EXPECT_NEAR(
      points->GetArray(materialShininessArrayName)->GetComponent(p, 0), wrote.shininess, 1e-6 * wrote.shininess);
  }
  EXPECT_GT(seen[0], 0);
  EXPECT_EQ(seen[0], seen[1]);
}

TEST_F(SceneFiles, AGltfFilesPartsKeepTheirMetallicRoughnessMaterialsForTheVtkPbrModel)
{
  // The bundled lamps: the floor white, metallic 0, roughness 0.9, with the checker texture;
  // the ball (0.9, 0.55, 0.2), metallic 0.6, roughness 0.35, untextured. The base colour carries
  // the texture as kd does: on the floor, whose metallic factor is 0, kd is the base colour.
  vtkSmartPointer<vtkPolyData> mesh = app::readMesh(shadelab::testing::sourcePath("data/scenes/lamps/lamps.gltf"));
  ASSERT_TRUE(hasOwnMicrofacetMaterials(mesh));
  vtkPointData* points = mesh->GetPointData();
  vtkDataArray* part = points->GetArray(partArrayName);
  vtkDataArray* base = points->GetArray(materialBaseColorArrayName);
  vtkDataArray* kd = points->GetArray(materialKdArrayName);
  std::set<double> floorReds;
  for (vtkIdType p = 0; p < mesh->GetNumberOfPoints(); ++p)
  {
    const bool ball = part->GetComponent(p, 0) == 0; // the importer's order: the ball first
    EXPECT_FLOAT_EQ(points->GetArray(materialMetallicArrayName)->GetComponent(p, 0), ball ? 0.6f : 0.0f) << p;
    EXPECT_FLOAT_EQ(points->GetArray(materialRoughnessArrayName)->GetComponent(p, 0), ball ? 0.35f : 0.9f) << p;
    const Rgb ballColor(0.9, 0.55, 0.2);
    for (int c = 0; c < 3; ++c)
    {
      EXPECT_FLOAT_EQ(base->GetComponent(p, c), ball ? float(ballColor[c]) : float(kd->GetComponent(p, c))) << p;
    }
    if (!ball)
    {
      floorReds.insert(base->GetComponent(p, 0));
    }
  }
  EXPECT_GE(floorReds.size(), 2u); // the checker's two colours at least: the texture is in the base colour
  // Under the vtk_pbr model without a material, they are the material's arrays.
  Scene scene;
  scene.model = ShadingModel::VtkPbr;
  EXPECT_TRUE(shadesWithOwnMaterials(scene, mesh, false));
  const Material own = ownMaterial(scene, mesh);
  EXPECT_EQ(own.arrays[MaterialCoefficient::Diffuse]->array, materialBaseColorArrayName);
  EXPECT_EQ(own.arrays[MaterialCoefficient::Metallic]->array, materialMetallicArrayName);
  EXPECT_EQ(own.arrays[MaterialCoefficient::Roughness]->array, materialRoughnessArrayName);
  EXPECT_FALSE(own.arrays[MaterialCoefficient::Specular].has_value());
}

TEST_F(SceneFiles, AGltfFilesMetallicRoughnessTextureScalesItsFactorsAtEachVertex)
{
  // The lamps' floor alone, with a metallic-roughness texture (read linearly: green the
  // roughness, blue the metallic factor) beside a base colour texture, which VTK's importer
  // needs to apply it; each of two rows, so that the orientation shows. glTF's images start at
  // their top row (texture coordinate v = 0), VTK's at their bottom one (vtkPNGWriter writes row
  // 1 first), and vtkGLTFImporter samples at v -> 1 - v: a vertex at v in (0.1, 0.4) takes the
  // top row, at (0.6, 0.9) the bottom one.
  for (const char* resource : { "lamps.bin", "checker.png" })
  {
    fs::copy_file(shadelab::testing::sourcePath(std::string("data/scenes/lamps/") + resource), folder / resource);
  }
  using Texel = std::array<unsigned char, 3>;
  const Texel ormTop{ 255, 60, 30 }, ormBottom{ 255, 200, 240 }, baseTop{ 255, 128, 64 }, baseBottom{ 64, 255, 128 };
  for (const auto& [name, top, bottom] :
    { std::tuple{ "orm.png", ormTop, ormBottom }, std::tuple{ "base.png", baseTop, baseBottom } })
  {
    vtkNew<vtkImageData> image;
    image->SetDimensions(1, 2, 1);
    image->AllocateScalars(VTK_UNSIGNED_CHAR, 3);
    for (int c = 0; c < 3; ++c)
    {
      static_cast<unsigned char*>(image->GetScalarPointer(0, 0, 0))[c] = bottom[c];
      static_cast<unsigned char*>(image->GetScalarPointer(0, 1, 0))[c] = top[c];
    }
    vtkNew<vtkPNGWriter> writer;
    writer->SetInputData(image);
    writer->SetFileName((folder / name).string().c_str());
    writer->Write();
  }
  std::ifstream original(shadelab::testing::sourcePath("data/scenes/lamps/lamps.gltf"));
  nlohmann::json gltf = nlohmann::json::parse(original);
  ASSERT_EQ(gltf["nodes"][1]["name"], "ball");
  gltf["scenes"][0]["nodes"] = { 0, 2, 3, 4 }; // the floor alone, with its texture coordinates
  gltf["images"].push_back({ { "uri", "orm.png" } });
  gltf["images"].push_back({ { "uri", "base.png" } });
  gltf["textures"].push_back({ { "source", 1 } });
  gltf["textures"].push_back({ { "source", 2 } });
  nlohmann::json& floor = gltf["materials"][0]["pbrMetallicRoughness"];
  floor["metallicRoughnessTexture"] = { { "index", 1 } };
  floor["baseColorTexture"] = { { "index", 2 } };
  floor["baseColorFactor"] = { 1.0, 0.5, 0.25, 1.0 };
  floor["metallicFactor"] = 0.8;
  floor["roughnessFactor"] = 1.0;
  vtkSmartPointer<vtkPolyData> mesh = app::readMesh(file("orm.gltf", gltf.dump(1)));
  vtkPointData* points = mesh->GetPointData();
  vtkDataArray* tcoords = points->GetTCoords();
  ASSERT_NE(tcoords, nullptr);
  const Rgb factor(1.0, 0.5, 0.25);
  int checked[2] = { 0, 0 };
  for (vtkIdType p = 0; p < mesh->GetNumberOfPoints(); ++p)
  {
    const double v = tcoords->GetComponent(p, 1) - std::floor(tcoords->GetComponent(p, 1)); // the texture repeats
    const bool top = v > 0.1 && v<0.4, bottom = v> 0.6 && v < 0.9;
    if (!top && !bottom)
    {
      continue;
    }
    ++checked[top ? 0 : 1];
    const Texel& orm = top ? ormTop : ormBottom;
    const Texel& texel = top ? baseTop : baseBottom;
    const double metallic = 0.8 * orm[2] / 255.0, roughness = orm[1] / 255.0;
    Rgb textured;
    for (int c = 0; c < 3; ++c)
    {
      textured[c] = factor[c] * srgbToLinear(texel[c] / 255.0);
    }
    const LectureCoefficients own = lectureCoefficients(factor, metallic, roughness);
    const LectureCoefficients withTexture = lectureCoefficients(textured, metallic, roughness);
    EXPECT_FLOAT_EQ(points->GetArray(materialMetallicArrayName)->GetComponent(p, 0), float(metallic)) << p;
    EXPECT_FLOAT_EQ(points->GetArray(materialRoughnessArrayName)->GetComponent(p, 0), float(roughness)) << p;
    for (int c = 0; c < 3; ++c)
    {
      EXPECT_NEAR(points->GetArray(materialBaseColorArrayName)->GetComponent(p, c), textured[c], 1e-6) << p;
      EXPECT_NEAR(points->GetArray(materialKdArrayName)->GetComponent(p, c), withTexture.kd[c], 1e-6) << p;
      EXPECT_NEAR(points->GetArray(materialKaArrayName)->GetComponent(p, c), own.kd[c], 1e-6) << p;
      EXPECT_NEAR(points->GetArray(materialKsArrayName)->GetComponent(p, c), own.ks[c], 1e-6) << p;
    }
    EXPECT_NEAR(points->GetArray(materialShininessArrayName)->GetComponent(p, 0), own.shininess, 1e-6 * own.shininess)
      << p;
  }
  EXPECT_GT(checked[0], 100);
  EXPECT_GT(checked[1], 100);
  // Without the base colour texture VTK's importer leaves it out, and so does ShadeLab, saying so.
  floor.erase("baseColorTexture");
  std::vector<std::string> notes;
  vtkSmartPointer<vtkPolyData> alone = app::importGltfScene(file("alone.gltf", gltf.dump(1)), notes);
  vtkDataArray* aloneRoughness = alone->GetPointData()->GetArray(materialRoughnessArrayName);
  EXPECT_EQ(aloneRoughness->GetRange()[0], 1.0); // the factor alone
  EXPECT_EQ(aloneRoughness->GetRange()[1], 1.0);
  EXPECT_NE(std::find(notes.begin(), notes.end(),
              "material 'floor' has a metallicRoughnessTexture but no baseColorTexture, without which VTK's importer "
              "does not apply it: shaded with its metallic and roughness factors alone"),
    notes.end());
}

TEST_F(SceneFiles, AGltfFilesLightsKeepTheirOwnDefinitionsWhereverTheirNodesAre)
{
  // Two point lights alike but for their range, one of them used by two nodes, one under a
  // parent that is moved and turned; a spot whose cone is the widest glTF allows.
  std::ofstream(folder / "square.bin", std::ios::binary) << squareBuffer();
  std::string gltf = lampsGltf(R"({ "byteLength": 112, "uri": "square.bin" })");
  const std::string lights = R"("lights": [
    { "name": "near", "type": "point", "intensity": 2, "range": 1 },
    { "name": "near", "type": "point", "intensity": 2, "range": 100 },
    { "type": "spot", "spot": { "innerConeAngle": 0.5, "outerConeAngle": 1.5707963267948966 } } ])";
  gltf.replace(gltf.find("\"lights\": ["), gltf.find("] } },") + 1 - gltf.find("\"lights\": ["), lights);
  const std::string nodes = R"("nodes": [ { "mesh": 0 },
    { "translation": [1, 0, 0], "rotation": [0, 0.70710678, 0, 0.70710678], "children": [2] },
    { "translation": [0, 0, 2], "extensions": { "KHR_lights_punctual": { "light": 0 } } },
    { "translation": [0, 5, 0], "extensions": { "KHR_lights_punctual": { "light": 1 } } },
    { "translation": [0, 6, 0], "extensions": { "KHR_lights_punctual": { "light": 1 } } },
    { "translation": [0, 7, 0], "extensions": { "KHR_lights_punctual": { "light": 2 } } } ],
  "meshes")";
  gltf.replace(
    gltf.find("\"nodes\": [ { \"mesh\""), gltf.find("\"meshes\"") + 8 - gltf.find("\"nodes\": [ { \"mesh\""), nodes);
  gltf.replace(gltf.find("\"nodes\": [0, 1, 2, 3]"), 21, "\"nodes\": [0, 1, 3, 4, 5]");
  const Scene scene = parseScene(app::fileLightsOf(app::readMesh(file("nested.gltf", gltf))), "nested.gltf");
  ASSERT_EQ(scene.lights.size(), 4u);
  std::set<std::string> names;
  std::map<double, double> rangeAtHeight; // the point lights' ranges by their positions' y
  for (const NamedLight& light : scene.lights)
  {
    names.insert(light.name);
    if (const auto* point = std::get_if<PointLight>(&light.source))
    {
      rangeAtHeight[point->position.y] = point->attenuation.range;
      // The parent turns its child's offset (0, 0, 2) by 90 degrees about y to (2, 0, 0), then
      // moves it by (1, 0, 0).
      if (point->attenuation.range == 1)
      {
        EXPECT_NEAR(glm::distance(point->position, glm::dvec3(3, 0, 0)), 0, 1e-6);
      }
    }
    if (const auto* spot = std::get_if<SpotLight>(&light.source))
    {
      EXPECT_NEAR(spot->cone.innerAngleDegrees, 0.5 * 180 / M_PI, 1e-9);
      EXPECT_NEAR(spot->cone.outerAngleDegrees, 90, 1e-9);
    }
  }
  // Named in the importer's order (the last node first), made unique.
  EXPECT_EQ(names, (std::set<std::string>{ "spot0", "near", "near_2", "near_3" }));
  EXPECT_EQ(rangeAtHeight, (std::map<double, double>{ { 0, 1 }, { 5, 100 }, { 6, 100 } }));
}

namespace
{
TEST_F(SceneFiles, AGltfFilesPartsAreNamedByTheirMaterialsInTheImportersOrder)
{
  // vtkGLTFImporter 9.1 makes its actors popping the scene's nodes off a stack (children pushed
  // after their parent), so here D, C, then A's two primitives. Each part is named by its
  // material, else its mesh, else numbered; a name met twice gets _2. Each node stands at its
  // own x, which says which part is which.
  std::ofstream(folder / "square.bin", std::ios::binary) << squareBuffer();
  const std::string primitive = R"({ "attributes": { "POSITION": 0, "NORMAL": 1 }, "indices": 2)";
  const std::string gltf = R"({ "asset": { "version": "2.0" }, "scene": 0, "scenes": [ { "nodes": [0, 1] } ],
  "nodes": [ { "name": "A", "mesh": 0 }, { "name": "B", "children": [2, 3] },
    { "name": "C", "mesh": 1, "translation": [10, 0, 0] }, { "name": "D", "mesh": 2, "translation": [20, 0, 0] } ],
  "meshes": [ { "name": "pair", "primitives": [ )" +
    primitive + R"(, "material": 0 }, )" + primitive + R"(, "material": 1 } ] },
    { "name": "lone", "primitives": [ )" +
    primitive + R"(, "material": 2 } ] }, { "primitives": [ )" + primitive + R"( } ] } ],
  "materials": [ { "name": "paint" }, { "pbrMetallicRoughness": { "metallicFactor": 0.2 } }, { "name": "paint" } ],
  "buffers": [ { "byteLength": 112, "uri": "square.bin" } ],
  "bufferViews": [ { "buffer": 0, "byteOffset": 0, "byteLength": 48 }, { "buffer": 0, "byteOffset": 48, "byteLength": 48 },
    { "buffer": 0, "byteOffset": 96, "byteLength": 12 } ],
  "accessors": [ { "bufferView": 0, "componentType": 5126, "count": 4, "type": "VEC3", "min": [-1, 0, -1], "max": [1, 0, 1] },
    { "bufferView": 1, "componentType": 5126, "count": 4, "type": "VEC3" },
    { "bufferView": 2, "componentType": 5123, "count": 6, "type": "SCALAR" } ] })";
  vtkSmartPointer<vtkPolyData> mesh = app::readMesh(file("parts.gltf", gltf));
  auto* names = vtkStringArray::SafeDownCast(mesh->GetFieldData()->GetAbstractArray(partNamesArrayName));
  ASSERT_NE(names, nullptr);
  ASSERT_EQ(names->GetNumberOfValues(), 4);
  const std::vector<std::pair<std::string, double>> expected = { { "part0", 20 }, { "paint", 10 }, { "paint_2", 0 },
    { "pair", 0 } };
  vtkDataArray* part = mesh->GetPointData()->GetArray(partArrayName);
  for (vtkIdType p = 0; p < 4; ++p)
  {
    EXPECT_EQ(names->GetValue(p), expected[std::size_t(p)].first);
    int points = 0;
    for (vtkIdType i = 0; i < mesh->GetNumberOfPoints(); ++i)
    {
      if (part->GetComponent(i, 0) == double(p))
      {
        EXPECT_NEAR(mesh->GetPoint(i)[0], expected[std::size_t(p)].second, 1.0) << names->GetValue(p);
        ++points;
      }
    }
    EXPECT_EQ(points, 4) << names->GetValue(p);
  }
}
}
