// The vtk and vtk_pbr models against what VTK 9.1's OpenGL2 renderer really draws. Each vertex
// of a sphere is rendered as a one-pixel point carrying its normal: the shader then lights it
// with exactly that position and normal, with no interpolation, so the pixel must hold
// ShadeLab's total (for PBR, raised to 1/2.2 as VTK's PBR shader encodes it), clamped to
// [0, 1] and rounded to 8 bits. Runs under Xvfb (Mesa's software OpenGL).
#include "TestFolder.h"
#include "TestMeshes.h"
#include "TestPaths.h"
#include "VtkLightSets.h"

#include "GltfScene.h"
#include "OffScreenImage.h"

#include "ShadeLabImportedParts.h"
#include "ShadeLabMaterialArrays.h"

#include "vtkActor.h"
#include "vtkActorCollection.h"
#include "vtkCamera.h"
#include "vtkCellArray.h"
#include "vtkDoubleArray.h"
#include "vtkGLTFImporter.h"
#include "vtkIdList.h"
#include "vtkImageData.h"
#include "vtkMatrix4x4.h"
#include "vtkPNGWriter.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyDataMapper.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"
#include "vtkRendererCollection.h"
#include "vtkUnsignedCharArray.h"

#include <array>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <random>
#include <set>

#include <nlohmann/json.hpp>

namespace
{
using shadelab::testing::litSphereCentre;
using shadelab::testing::litSphereRadius;

constexpr int windowSize = 800;

/// Renders a mesh's vertices as one-pixel points, carrying its normals and arrays, under these
/// lights, property and camera, and compares each pixel with the total ShadeLab computed at its
/// vertex (for PBR, raised to 1/2.2 as VTK's PBR shader encodes it). mapWith sets the mapper's
/// scalar colouring, where the material comes from an array. Only pixels that exactly one vertex
/// lands in, well inside the pixel, on the side facing the camera, are compared: there the pixel
/// is that vertex.
struct ComparedPixels
{
  int count = 0;
  int midTones = 0; // those with a channel whose expected value is within (1, 254): neither black nor clipped
};

ComparedPixels expectPixelsMatchTotal(vtkPolyData* mesh, vtkDataArray* total, vtkProperty* property,
  vtkLightCollection* lights, vtkCamera* camera, const std::function<void(vtkPolyDataMapper*)>& mapWith = {})
{
  // The same vertices, normals and arrays as a cloud of vertex cells.
  vtkNew<vtkPolyData> cloud;
  cloud->SetPoints(mesh->GetPoints());
  cloud->GetPointData()->ShallowCopy(mesh->GetPointData());
  vtkNew<vtkCellArray> vertices;
  for (vtkIdType i = 0; i < mesh->GetNumberOfPoints(); ++i)
  {
    vertices->InsertNextCell(1, &i);
  }
  cloud->SetVerts(vertices);
  vtkNew<vtkPolyDataMapper> mapper;
  mapper->SetInputData(cloud);
  mapper->SetScalarVisibility(bool(mapWith));
  if (mapWith)
  {
    mapWith(mapper);
  }
  vtkNew<vtkActor> actor;
  actor->SetMapper(mapper);
  actor->SetProperty(property);
  vtkNew<vtkRenderer> renderer;
  renderer->AddActor(actor);
  renderer->SetActiveCamera(camera);
  renderer->SetLightCollection(lights);
  renderer->ResetCameraClippingRange();
  vtkSmartPointer<vtkImageData> image = shadelab::app::renderOffScreen(renderer, windowSize, windowSize);
  if (image->GetDimensions()[0] != windowSize || image->GetDimensions()[1] != windowSize)
  {
    ADD_FAILURE() << "the render is " << image->GetDimensions()[0] << " x " << image->GetDimensions()[1];
    return {};
  }

  std::map<std::pair<int, int>, std::vector<vtkIdType>> landings;
  vtkMatrix4x4* projection = camera->GetCompositeProjectionTransformMatrix(1.0, -1, 1);
  std::map<vtkIdType, bool> clearlyInside;
  for (vtkIdType i = 0; i < mesh->GetNumberOfPoints(); ++i)
  {
    double p[3];
    mesh->GetPoint(i, p);
    // Where the vertex lands: the camera's projection (square window, so aspect 1) takes it
    // to normalised device coordinates, whose [-1, 1] spans the window's pixels.
    double h[4] = { p[0], p[1], p[2], 1.0 };
    projection->MultiplyPoint(h, h);
    const double d[2] = { (h[0] / h[3] + 1) * 0.5 * windowSize, (h[1] / h[3] + 1) * 0.5 * windowSize };
    const std::pair<int, int> pixel{ int(std::floor(d[0])), int(std::floor(d[1])) };
    landings[pixel].push_back(i);
    const double fx = d[0] - pixel.first, fy = d[1] - pixel.second;
    double n[3];
    mesh->GetPointData()->GetNormals()->GetTuple(i, n);
    const double* eye = camera->GetPosition();
    const double facing = n[0] * (eye[0] - p[0]) + n[1] * (eye[1] - p[1]) + n[2] * (eye[2] - p[2]);
    const bool inWindow =
      h[3] > 0 && pixel.first >= 0 && pixel.first < windowSize && pixel.second >= 0 && pixel.second < windowSize;
    clearlyInside[i] = inWindow && fx > 0.1 && fx < 0.9 && fy > 0.1 && fy < 0.9 && facing > 0.5;
  }
  // docs/vtk-renderer.md section 11.5: the PBR shader writes color^(1/2.2).
  const bool pbr = property->GetInterpolation() == VTK_PBR;
  auto encoded = [pbr](double value) { return pbr ? std::pow(std::max(value, 0.0), 1.0 / 2.2) : value; };
  // Half a level is the 8-bit rounding itself; 0.001 more covers the shader's float32, 0.005
  // in the PBR shader, whose 1/2.2 power steepens near 0 and whose GGX distribution cancels
  // digits in (n.h)^2 (alpha^2 - 1) + 1 near n.h = 1 (measured: 0.0021 at most).
  const double tolerance = pbr ? 0.505 : 0.501;
  ComparedPixels compared;
  double worst = 0;
  for (const auto& [pixel, ids] : landings)
  {
    if (ids.size() != 1 || !clearlyInside[ids[0]])
    {
      continue;
    }
    bool midTone = false;
    for (int c = 0; c < 3; ++c)
    {
      const double expected = 255.0 * std::clamp(encoded(total->GetComponent(ids[0], c)), 0.0, 1.0);
      midTone = midTone || (expected > 1 && expected < 254);
      const double drawn = image->GetScalarComponentAsDouble(pixel.first, pixel.second, 0, c);
      worst = std::max(worst, std::abs(drawn - expected));
      EXPECT_LE(std::abs(drawn - expected), tolerance)
        << "vertex " << ids[0] << " channel " << c << " at pixel " << pixel.first << ", " << pixel.second;
    }
    ++compared.count;
    compared.midTones += midTone ? 1 : 0;
  }
  std::cout << "compared " << compared.count << " vertices with their pixels (" << compared.midTones
            << " in mid-tones); largest difference " << worst << "/255\n";
  return compared;
}

class RealRender : public shadelab::testing::VtkLightSets
{
protected:
  /// Renders the sphere's vertices and compares each pixel with the model's total
  /// (expectPixelsMatchTotal). With colorBy, the sphere carries the arrays it adds and the scene
  /// takes its material from them; mapWith then sets the mapper's scalar colouring to match.
  void expectPixelsMatch(bool lone, const std::function<void(vtkPolyData*, shadelab::Scene&)>& colorBy = {},
    const std::function<void(vtkPolyDataMapper*)>& mapWith = {})
  {
    const auto [sphere, total] = shadeLitSphere(120, lone, colorBy);
    ASSERT_NE(total, nullptr);
    const ComparedPixels compared = expectPixelsMatchTotal(sphere, total, property, lights, camera, mapWith);
    EXPECT_GT(compared.count, 2000);
    EXPECT_GT(compared.midTones, 1000);
  }
};

TEST_F(RealRender, LoneHeadlight)
{
  addLoneHeadlight();
  expectPixelsMatch(true);
}

TEST_F(RealRender, LightKitOfDirectionalLights)
{
  addLightKit();
  expectPixelsMatch(false);
}

TEST_F(RealRender, SwitchedOffSceneLightStillEndsTheLoneHeadlightShader)
{
  addHeadlightAndSwitchedOffSceneLight();
  expectPixelsMatch(false);
}

TEST_F(RealRender, PositionalSpotAndPointLights)
{
  addPositionalLights();
  expectPixelsMatch(false);
}

/// A metal-and-dielectric mix of medium roughness, with a base IOR other than the default.
void makePbr(vtkProperty* property)
{
  property->SetInterpolationToPBR();
  property->SetMetallic(0.4);
  property->SetRoughness(0.35);
  property->SetBaseIOR(1.8);
}

TEST_F(RealRender, PbrLoneHeadlightAtTheEye)
{
  makePbr(property);
  addLoneHeadlight();
  expectPixelsMatch(true);
}

TEST_F(RealRender, PbrLightKitOfDirectionalLights)
{
  makePbr(property);
  addLightKit();
  expectPixelsMatch(false);
}

TEST_F(RealRender, PbrPositionalLightsAndADirectionalOneShiningFromItsPosition)
{
  makePbr(property);
  property->SetEdgeTint(0.9, 0.6, 0.3);
  addPositionalLights();
  expectPixelsMatch(false);
}

TEST_F(RealRender, PbrRoughMetalAndSmoothDielectric)
{
  makePbr(property);
  property->SetMetallic(1.0);
  property->SetRoughness(1.0);
  addLightKit();
  expectPixelsMatch(false);
  property->SetMetallic(0.0);
  property->SetRoughness(0.08);
  expectPixelsMatch(false);
}

/// The material's diffuse and ambient colours from an array, as VTK's mapper colours both with
/// the scalars' colour (times the property's Diffuse and Ambient).
void colorFromArray(shadelab::Scene& scene, const vtkProperty* property, shadelab::ArrayCoefficient source)
{
  using shadelab::MaterialCoefficient;
  source.scale = const_cast<vtkProperty*>(property)->GetDiffuse();
  scene.material.arrays[MaterialCoefficient::Diffuse] = source;
  scene.material.kd = shadelab::Rgb(source.scale);
  source.scale = const_cast<vtkProperty*>(property)->GetAmbient();
  scene.material.arrays[MaterialCoefficient::Ambient] = source;
  scene.material.ka = shadelab::Rgb(source.scale);
}

/// A field over the sphere that sweeps the colour map several times round it.
void addField(vtkPolyData* sphere)
{
  vtkNew<vtkDoubleArray> field;
  field->SetName("field");
  for (vtkIdType i = 0; i < sphere->GetNumberOfPoints(); ++i)
  {
    double p[3];
    sphere->GetPoint(i, p);
    field->InsertNextValue(std::sin(3 * p[0]) + p[1] * p[2]);
  }
  sphere->GetPointData()->AddArray(field);
}

constexpr std::array<double, 2> fieldRange{ -0.8, 1.1 }; // inside the field's: both ends clamp

TEST_F(RealRender, FieldThroughTheMappersDefaultLookupTable)
{
  addLightKit();
  expectPixelsMatch(
    false,
    [&](vtkPolyData* sphere, shadelab::Scene& scene)
    {
      addField(sphere);
      colorFromArray(scene, property, { "field", {}, 1.0, "rainbow", fieldRange });
    },
    [](vtkPolyDataMapper* mapper)
    {
      // The mapper's own lookup table (a default vtkLookupTable), only its range set.
      mapper->SetScalarModeToUsePointFieldData();
      mapper->SelectColorArray("field");
      mapper->SetScalarRange(fieldRange[0], fieldRange[1]);
    });
}

TEST_F(RealRender, FieldThroughAColorTransferFunction)
{
  addPositionalLights();
  expectPixelsMatch(
    false,
    [&](vtkPolyData* sphere, shadelab::Scene& scene)
    {
      addField(sphere);
      colorFromArray(scene, property, { "field", {}, 1.0, "cool to warm", fieldRange });
    },
    [](vtkPolyDataMapper* mapper)
    {
      mapper->SetScalarModeToUsePointFieldData();
      mapper->SelectColorArray("field");
      mapper->SetLookupTable(shadelab::namedColorMap("cool to warm", fieldRange));
      mapper->UseLookupTableScalarRangeOn();
    });
}

/// Random 8-bit colours at the sphere's vertices, as a "Colors" point array.
void addRandomColors(vtkPolyData* sphere)
{
  std::mt19937 random(7);
  vtkNew<vtkUnsignedCharArray> colors;
  colors->SetName("Colors");
  colors->SetNumberOfComponents(3);
  for (vtkIdType i = 0; i < 3 * sphere->GetNumberOfPoints(); ++i)
  {
    colors->InsertNextValue(static_cast<unsigned char>(random() % 256));
  }
  sphere->GetPointData()->AddArray(colors);
}

/// The mapper drawing the "Colors" array's bytes as they are.
void mapDirectColors(vtkPolyDataMapper* mapper)
{
  mapper->SetScalarModeToUsePointFieldData();
  mapper->SelectColorArray("Colors");
  mapper->SetColorModeToDirectScalars();
}

TEST_F(RealRender, DirectEightBitColors)
{
  addLoneHeadlight();
  expectPixelsMatch(
    true,
    [&](vtkPolyData* sphere, shadelab::Scene& scene)
    {
      addRandomColors(sphere);
      colorFromArray(scene, property, { "Colors" });
    },
    mapDirectColors);
}
// VTK's scalar colouring under PBR: each vertex's colour, times Diffuse, is its albedo (and
// moves its F0 and F90); the scene's base colour, a grey, stands for Diffuse.
TEST_F(RealRender, PbrDirectEightBitColors)
{
  makePbr(property);
  property->SetEdgeTint(0.9, 0.6, 0.3);
  property->SetDiffuse(0.85);
  property->SetDiffuseColor(1.0, 1.0, 1.0);
  addPositionalLights();
  expectPixelsMatch(
    false,
    [&](vtkPolyData* sphere, shadelab::Scene& scene)
    {
      addRandomColors(sphere);
      shadelab::colorMaterialBy(scene, "Colors", "");
    },
    mapDirectColors);
}

/// The vtk_pbr model against VTK's own render of an imported scene: the bundled lamps' ball
/// (metallic 0.6, roughness 0.35, no texture) with its property as vtkGLTFImporter makes it,
/// under the file's three lights as the importer makes them (a point light whose range becomes
/// VTK's attenuation, a spot whose outer cone becomes VTK's, and a directional light, which the
/// positional ones make shine from its position).
TEST(RealRenderOfImportedScene, GltfBallUnderTheFilesOwnLights)
{
  vtkNew<vtkGLTFImporter> importer;
  importer->SetFileName(shadelab::testing::sourcePath("data/scenes/lamps/lamps.gltf").c_str());
  vtkNew<vtkRenderWindow> window;
  importer->SetRenderWindow(window);
  importer->Update();
  vtkRenderer* imported = window->GetRenderers()->GetFirstRenderer();
  ASSERT_NE(imported, nullptr);
  vtkActor* ball = nullptr;
  vtkActorCollection* actors = imported->GetActors();
  actors->InitTraversal();
  while (vtkActor* actor = actors->GetNextActor())
  {
    ball = std::abs(actor->GetProperty()->GetMetallic() - 0.6) < 1e-6 ? actor : ball; // a float in the file
  }
  ASSERT_NE(ball, nullptr);
  EXPECT_EQ(ball->GetProperty()->GetInterpolation(), VTK_PBR);
  EXPECT_TRUE(ball->GetMatrix()->IsIdentity()); // its points are where the renderer draws them
  vtkPolyData* surface = vtkPolyData::SafeDownCast(ball->GetMapper()->GetInput());
  ASSERT_NE(surface, nullptr);

  vtkNew<vtkCamera> camera;
  camera->SetPosition(0.5, 1.3, 1.8);
  camera->SetFocalPoint(0.0, 0.5, 0.0);
  const shadelab::Scene scene = shadelab::sceneFromVtk(imported->GetLights(), ball->GetProperty(), camera);
  EXPECT_EQ(scene.model, shadelab::ShadingModel::VtkPbr);
  EXPECT_EQ(scene.lights.size(), 3u);
  vtkSmartPointer<vtkPolyData> shaded = shadelab::testing::shadeWithFilter(surface, scene, { "total" });
  vtkDataArray* total = shaded->GetPointData()->GetArray("total");
  ASSERT_NE(total, nullptr);
  const ComparedPixels compared =
    expectPixelsMatchTotal(shaded, total, ball->GetProperty(), imported->GetLights(), camera);
  EXPECT_GT(compared.count, 300);
  EXPECT_GT(compared.midTones, 300);
}

/// The shaded mesh's points of one part (its `part` array's value), with their normals and total,
/// and the texture coordinates of the importer's polydata of that part (the same points, in
/// order: the parts' mesh keeps only the arrays every part has).
std::pair<vtkSmartPointer<vtkPolyData>, vtkSmartPointer<vtkDataArray>> pointsOfPart(
  vtkPolyData* mesh, int part, vtkPolyData* imported)
{
  vtkPointData* data = mesh->GetPointData();
  vtkDataArray* parts = data->GetArray(shadelab::partArrayName);
  vtkNew<vtkIdList> ids;
  for (vtkIdType i = 0; i < mesh->GetNumberOfPoints(); ++i)
  {
    if (parts->GetComponent(i, 0) == part)
    {
      ids->InsertNextId(i);
    }
  }
  auto points = vtkSmartPointer<vtkPolyData>::New();
  vtkNew<vtkPoints> positions;
  mesh->GetPoints()->GetPoints(ids, positions);
  points->SetPoints(positions);
  vtkSmartPointer<vtkDataArray> normals, total;
  normals.TakeReference(data->GetNormals()->NewInstance());
  total.TakeReference(data->GetArray("total")->NewInstance());
  for (vtkDataArray* array : { normals.Get(), total.Get() })
  {
    array->SetNumberOfComponents(3);
    array->SetNumberOfTuples(ids->GetNumberOfIds());
  }
  data->GetNormals()->GetTuples(ids, normals);
  data->GetArray("total")->GetTuples(ids, total);
  normals->SetName("Normals");
  points->GetPointData()->SetNormals(normals);
  if (vtkDataArray* tcoords = imported->GetPointData()->GetTCoords()) // for a texture VTK samples at the vertex
  {
    EXPECT_EQ(imported->GetNumberOfPoints(), ids->GetNumberOfIds());
    points->GetPointData()->SetTCoords(tcoords);
  }
  return { points, total };
}

class RealRenderOfImportedParts : public shadelab::testing::TestFolder
{
protected:
  /// The vtk_pbr model with a glTF file's own materials, part by part, against VTK's own render
  /// of the parts the importer makes: the bundled lamps, with their floor's base colour texture
  /// taken out (VTK samples it per pixel, ShadeLab averages it per vertex) and changed by
  /// `edit`, each part drawn by VTK with its own property and shaded by ShadeLab in one run from
  /// the material_base_color, material_metallic and material_roughness arrays, under the file's
  /// lights. texturedFloor: `edit` gives the floor constant textures, which VTK must then apply.
  void expectEachPartAsVtkDrawsIt(const std::function<void(nlohmann::json&)>& edit, bool texturedFloor = false)
  {
    std::ifstream original(shadelab::testing::sourcePath("data/scenes/lamps/lamps.gltf"));
    nlohmann::json gltf = nlohmann::json::parse(original);
    ASSERT_EQ(gltf["materials"][0]["name"], "floor");
    ASSERT_EQ(gltf["materials"][0]["pbrMetallicRoughness"].erase("baseColorTexture"), 1u);
    edit(gltf);
    const std::string path = file("lamps.gltf", gltf.dump(1));
    for (const char* resource : { "lamps.bin", "checker.png" }) // the image stays in the file, unused
    {
      std::filesystem::copy_file(
        shadelab::testing::sourcePath(std::string("data/scenes/lamps/") + resource), folder / resource);
    }

    std::vector<std::string> notes;
    vtkSmartPointer<vtkPolyData> mesh = shadelab::app::importGltfScene(path, notes);
    EXPECT_TRUE(notes.empty()) << notes.front();
    ASSERT_TRUE(shadelab::hasOwnMicrofacetMaterials(mesh));
    vtkNew<vtkGLTFImporter> importer;
    importer->SetFileName(path.c_str());
    vtkNew<vtkRenderWindow> window;
    importer->SetRenderWindow(window);
    importer->Update();
    vtkRenderer* imported = window->GetRenderers()->GetFirstRenderer();
    ASSERT_NE(imported, nullptr);
    vtkActorCollection* actors = imported->GetActors();
    ASSERT_EQ(actors->GetNumberOfItems(), 2);

    vtkNew<vtkCamera> camera;
    camera->SetPosition(0.5, 1.3, 1.8);
    camera->SetFocalPoint(0.0, 0.5, 0.0);
    actors->InitTraversal();
    // The first part's property, for the model and the lights; its material is the mesh's own.
    shadelab::Scene scene =
      shadelab::sceneFromVtk(imported->GetLights(), actors->GetNextActor()->GetProperty(), camera);
    EXPECT_TRUE(scene.materialGiven);
    EXPECT_FALSE(shadelab::shadesWithOwnMaterials(scene, mesh, false)); // the property's material wins
    scene.materialGiven = false;
    EXPECT_TRUE(shadelab::shadesWithOwnMaterials(scene, mesh, false));
    vtkSmartPointer<vtkPolyData> shaded = shadelab::testing::shadeWithFilter(mesh, scene, { "total" });
    std::set<std::pair<double, double>> metallicRoughness;
    actors->InitTraversal();
    for (int part = 0; part < 2; ++part)
    {
      vtkActor* actor = actors->GetNextActor();
      vtkProperty* property = actor->GetProperty();
      const bool floor = part == 1; // the importer's order: the ball first
      EXPECT_EQ(property->GetTexture("albedoTex") != nullptr, floor && texturedFloor) << "part " << part;
      EXPECT_EQ(property->GetTexture("materialTex") != nullptr, floor && texturedFloor) << "part " << part;
      metallicRoughness.insert({ property->GetMetallic(), property->GetRoughness() });
      const auto [points, total] =
        pointsOfPart(shaded, part, vtkPolyData::SafeDownCast(actor->GetMapper()->GetInput()));
      const ComparedPixels compared = expectPixelsMatchTotal(points, total, property, imported->GetLights(), camera);
      EXPECT_GT(compared.count, 100) << "part " << part;
      EXPECT_GT(compared.midTones, 100) << "part " << part;
    }
    EXPECT_EQ(metallicRoughness.size(), 2u); // the parts differ in both
  }
};

/// The floor white, metallic 0, roughness 0.9; the ball metallic 0.6, roughness 0.35.
TEST_F(RealRenderOfImportedParts, EachPartOfAGltfFileAsVtkDrawsIt)
{
  expectEachPartAsVtkDrawsIt([](nlohmann::json&) {});
}

/// The floor with a metallic-roughness texture, constant so that VTK's per-pixel sample and
/// ShadeLab's per-vertex average agree: VTK's shader multiplies the roughness by its green and
/// the metallic factor by its blue, read linearly (green 160 and blue 96 of 255, under factors
/// 1 and 0.8: roughness 0.627, metallic 0.301). VTK 9.1's importer applies it only beside a base
/// colour texture: a white one.
TEST_F(RealRenderOfImportedParts, AMetallicRoughnessTextureAsVtkDrawsIt)
{
  for (const auto& [name, color] : { std::pair{ "orm.png", std::array<double, 3>{ 255, 160, 96 } },
         std::pair{ "white.png", std::array<double, 3>{ 255, 255, 255 } } })
  {
    vtkNew<vtkImageData> texels;
    texels->SetDimensions(8, 8, 1);
    texels->AllocateScalars(VTK_UNSIGNED_CHAR, 3);
    for (int c = 0; c < 3; ++c)
    {
      texels->GetPointData()->GetScalars()->FillComponent(c, color[c]);
    }
    vtkNew<vtkPNGWriter> writer;
    writer->SetInputData(texels);
    writer->SetFileName((folder / name).string().c_str());
    writer->Write();
  }
  expectEachPartAsVtkDrawsIt(
    [](nlohmann::json& gltf)
    {
      gltf["images"].push_back({ { "uri", "orm.png" } });
      gltf["images"].push_back({ { "uri", "white.png" } });
      gltf["textures"].push_back({ { "source", 1 }, { "sampler", 0 } });
      gltf["textures"].push_back({ { "source", 2 }, { "sampler", 0 } });
      nlohmann::json& floor = gltf["materials"][0]["pbrMetallicRoughness"];
      floor["metallicRoughnessTexture"] = { { "index", 1 } };
      floor["baseColorTexture"] = { { "index", 2 } };
      floor["metallicFactor"] = 0.8;
      floor["roughnessFactor"] = 1.0;
    },
    true);
}
}
