// Scenes in the mesh frame: parsing "frame", placing a scene on a mesh (every light type's
// geometry and fall-off), studio_mesh.json against studio.json on the bunny, and the default
// light kit.
#include "DefaultLightKit.h"
#include "EnvironmentMap.h"
#include "KernelHarness.h"
#include "SceneFile.h"
#include "SceneFileErrors.h"
#include "SceneFrame.h"
#include "TestPaths.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <limits>
#include <memory>
#include <sstream>
#include <type_traits>
#include <variant>

namespace
{
using namespace shadelab;
using shadelab::testing::KernelHarness;

std::string errorOf(const std::string& text)
{
  return shadelab::testing::sceneFileErrorOf(text);
}

/// |actual - expected| <= rel |expected|: rel 0 asks for equality.
void expectNear(double actual, double expected, double rel, const std::string& what)
{
  EXPECT_LE(std::abs(actual - expected), rel * std::abs(expected)) << what << ": " << actual << " vs " << expected;
}

void expectNear(const glm::dvec3& actual, const glm::dvec3& expected, double rel, const std::string& what)
{
  EXPECT_LE(vectorLength(actual - expected), rel * vectorLength(expected))
    << what << ": (" << actual.x << ", " << actual.y << ", " << actual.z << ") vs (" << expected.x << ", " << expected.y
    << ", " << expected.z << ")";
}

void expectSameAttenuation(const Attenuation& actual, const Attenuation& expected, double rel, const std::string& at)
{
  EXPECT_EQ(actual.model, expected.model) << at;
  expectNear(actual.constant, expected.constant, rel, at + " constant");
  expectNear(actual.linear, expected.linear, rel, at + " linear");
  expectNear(actual.quadratic, expected.quadratic, rel, at + " quadratic");
  expectNear(actual.range, expected.range, rel, at + " range");
  expectNear(actual.minDistance, expected.minDistance, rel, at + " min_distance");
}

void expectSameShape(const EmitterShape& actual, const EmitterShape& expected, double rel, const std::string& at)
{
  ASSERT_EQ(actual.index(), expected.index()) << at;
  if (const auto* polygon = std::get_if<PolygonEmitter>(&expected))
  {
    const auto& vertices = std::get<PolygonEmitter>(actual).vertices;
    ASSERT_EQ(vertices.size(), polygon->vertices.size()) << at;
    for (std::size_t i = 0; i < vertices.size(); ++i)
    {
      expectNear(vertices[i], polygon->vertices[i], rel, at + " vertex " + std::to_string(i));
    }
  }
  if (const auto* disk = std::get_if<DiskEmitter>(&expected))
  {
    expectNear(std::get<DiskEmitter>(actual).centre, disk->centre, rel, at + " centre");
    expectNear(std::get<DiskEmitter>(actual).normal, disk->normal, rel, at + " normal");
    expectNear(std::get<DiskEmitter>(actual).radius, disk->radius, rel, at + " radius");
  }
  if (const auto* sphere = std::get_if<SphereEmitter>(&expected))
  {
    expectNear(std::get<SphereEmitter>(actual).centre, sphere->centre, rel, at + " centre");
    expectNear(std::get<SphereEmitter>(actual).radius, sphere->radius, rel, at + " radius");
  }
}

/// Every field of the two scenes agrees: numbers within rel (relative), the rest exactly.
void expectSameScene(const Scene& actual, const Scene& expected, double rel)
{
  EXPECT_EQ(actual.model, expected.model);
  EXPECT_EQ(actual.frame, expected.frame);
  EXPECT_EQ(actual.vtkLoneHeadlight, expected.vtkLoneHeadlight);
  EXPECT_EQ(actual.material.ka, expected.material.ka);
  EXPECT_EQ(actual.material.kd, expected.material.kd);
  EXPECT_EQ(actual.material.ks, expected.material.ks);
  EXPECT_EQ(actual.material.shininess, expected.material.shininess);
  EXPECT_EQ(actual.material.specular, expected.material.specular);
  EXPECT_EQ(actual.material.twoSided, expected.material.twoSided);
  ASSERT_EQ(actual.viewer.position.has_value(), expected.viewer.position.has_value());
  ASSERT_EQ(actual.viewer.focalPoint.has_value(), expected.viewer.focalPoint.has_value());
  if (expected.viewer.position)
  {
    expectNear(*actual.viewer.position, *expected.viewer.position, rel, "viewer position");
  }
  if (expected.viewer.focalPoint)
  {
    expectNear(*actual.viewer.focalPoint, *expected.viewer.focalPoint, rel, "viewer focal point");
  }
  expectNear(actual.viewer.viewDirection, expected.viewer.viewDirection, rel, "viewer direction");

  ASSERT_EQ(actual.lights.size(), expected.lights.size());
  for (std::size_t i = 0; i < expected.lights.size(); ++i)
  {
    const std::string at = expected.lights[i].name;
    EXPECT_EQ(actual.lights[i].name, at);
    ASSERT_EQ(actual.lights[i].source.index(), expected.lights[i].source.index()) << at;
    std::visit(
      [&](const auto& want)
      {
        using Type = std::decay_t<decltype(want)>;
        const Type& got = std::get<Type>(actual.lights[i].source);
        EXPECT_EQ(got.color, want.color) << at;
        expectNear(got.intensity, want.intensity, rel, at + " intensity");
        if constexpr (std::is_same_v<Type, DistantLight>)
        {
          expectNear(got.direction, want.direction, rel, at + " direction");
          EXPECT_EQ(got.intensityFromLength, want.intensityFromLength) << at;
        }
        if constexpr (std::is_same_v<Type, PointLight> || std::is_same_v<Type, SpotLight>)
        {
          expectNear(got.position, want.position, rel, at + " position");
          expectSameAttenuation(got.attenuation, want.attenuation, rel, at);
        }
        if constexpr (std::is_same_v<Type, SpotLight>)
        {
          expectNear(got.axis, want.axis, rel, at + " axis");
          EXPECT_EQ(got.cone.model, want.cone.model) << at;
          EXPECT_EQ(got.cone.halfAngleDegrees, want.cone.halfAngleDegrees) << at;
          EXPECT_EQ(got.cone.exponent, want.cone.exponent) << at;
          EXPECT_EQ(got.cone.innerAngleDegrees, want.cone.innerAngleDegrees) << at;
          EXPECT_EQ(got.cone.outerAngleDegrees, want.cone.outerAngleDegrees) << at;
        }
        if constexpr (std::is_same_v<Type, AreaLight>)
        {
          expectSameShape(got.shape, want.shape, rel, at);
          EXPECT_EQ(got.twoSided, want.twoSided) << at;
          EXPECT_EQ(got.estimator, want.estimator) << at;
          EXPECT_EQ(got.sampling.samples, want.sampling.samples) << at;
          EXPECT_EQ(got.sampling.stratified, want.sampling.stratified) << at;
        }
        if constexpr (std::is_same_v<Type, EnvironmentLight>)
        {
          EXPECT_EQ(got.map, want.map) << at;
          EXPECT_EQ(got.file, want.file) << at;
          EXPECT_EQ(got.rotationDegrees, want.rotationDegrees) << at;
          EXPECT_EQ(got.estimator, want.estimator) << at;
          EXPECT_EQ(got.directions, want.directions) << at;
          EXPECT_EQ(got.sampling.samples, want.sampling.samples) << at;
          EXPECT_EQ(got.bruteForceWidth, want.bruteForceWidth) << at;
        }
      },
      expected.lights[i].source);
  }
}

MeshExtent extentOf(const glm::dvec3& centre, double radius)
{
  MeshExtent extent;
  extent.centre = centre;
  extent.radius = radius;
  return extent;
}

/// One light of every type, every attenuation model and both cones, in the mesh frame.
Scene everyLightInTheMeshFrame()
{
  Scene scene = parseScene(R"({
    "frame": "mesh",
    "viewer": { "position": [0.3, 0.5, 4], "focal_point": [0, 0.1, 0] },
    "material": { "kd": 0.7, "ks": 0.3, "shininess": 20 },
    "lights": [
      { "name": "sun", "type": "distant", "direction": [-0.3, -1, -0.4] },
      { "name": "head", "type": "headlight", "intensity": 0.2 },
      { "name": "bulb", "type": "point", "position": [2, 1.5, 1], "intensity": 3 },
      { "name": "soft", "type": "point", "position": [-1.5, 0.5, 2], "intensity": 2, "attenuation": "inverse",
        "min_distance": 0.05 },
      { "name": "flat", "type": "point", "position": [0, 3, 0], "intensity": 0.3, "attenuation": "none" },
      { "name": "vtk", "type": "point", "position": [1, -2, 1.5],
        "attenuation": { "model": "vtk", "constant": 0.5, "linear": 0.3, "quadratic": 0.2 } },
      { "name": "gltf", "type": "spot", "position": [0, 2.5, 1], "direction": [0, -1, -0.3], "intensity": 4,
        "attenuation": { "model": "gltf_range", "range": 6 },
        "cone": { "model": "gltf", "inner_angle": 10, "outer_angle": 40 } },
      { "name": "cone", "type": "spot", "position": [-2, 2, -1], "direction": [1, -1, 0.5], "intensity": 5,
        "cone": { "model": "vtk", "angle": 35, "exponent": 2 } },
      { "name": "panel", "type": "rectangle", "center": [0, 2, 1.5], "edge_u": [1, 0, 0], "edge_v": [0, -0.6, 0.8],
        "intensity": 0.5 },
      { "name": "tri", "type": "polygon", "vertices": [[2, 0, -1], [2, 1, 0], [2, 0, 1]], "intensity": 0.4,
        "two_sided": true },
      { "name": "disk", "type": "disk", "center": [-2, 0, 0], "normal": [1, 0, 0], "radius": 0.4, "intensity": 0.6 },
      { "name": "ball", "type": "sphere", "center": [0, -2.5, 0], "radius": 0.3, "intensity": 1.5 },
      { "name": "room", "type": "ambient", "intensity": 0.05 }
    ]
  })",
    "mesh_frame.json");
  // A constant map (made here rather than read, to keep the test small): E = pi L everywhere.
  auto map = std::make_shared<EnvironmentMap>();
  map->width = 4;
  map->height = 2;
  map->radiance.assign(8, Rgb(0.5));
  EnvironmentLight sky;
  sky.map = map;
  sky.intensity = 0.1;
  scene.lights.push_back({ "sky", sky });
  return scene;
}

const MeshExtent meshes[] = {
  extentOf({ 0, 0, 0 }, 1),
  extentOf({ 1e4, -2e4, 3e4 }, 1e3),
  extentOf({ 2e-3, -1e-3, 5e-4 }, 1e-3),
};

TEST(SceneFrame, ParsesTheFrame)
{
  EXPECT_EQ(parseScene(R"({ "lights": [] })", "scene.json").frame, SceneFrame::World);
  EXPECT_EQ(parseScene(R"({ "frame": "world", "lights": [] })", "scene.json").frame, SceneFrame::World);
  EXPECT_EQ(parseScene(R"({ "frame": "mesh", "lights": [] })", "scene.json").frame, SceneFrame::Mesh);
  EXPECT_EQ(errorOf(R"({ "frame": "bunny", "lights": [] })"),
    "scene.json: /frame: \"bunny\" is not one of \"world\", \"mesh\"");
  EXPECT_EQ(
    errorOf(R"({ "frame": "Mesh", "lights": [] })"), "scene.json: /frame: \"Mesh\" is not one of \"world\", \"mesh\"");
  EXPECT_EQ(errorOf(R"({ "frame": 1, "lights": [] })"), "scene.json: /frame: must be a string, got 1");
  EXPECT_EQ(errorOf(R"({ "frame": { "mesh": true }, "lights": [] })"),
    "scene.json: /frame: must be a string, got {\"mesh\":true}");
}

TEST(SceneFrame, AWorldSceneIsPlacedAsItIs)
{
  Scene scene = everyLightInTheMeshFrame();
  scene.frame = SceneFrame::World;
  for (const MeshExtent& mesh : meshes)
  {
    expectSameScene(placedOnMesh(scene, mesh), scene, 0);
  }
}

TEST(SceneFrame, OnTheUnitSphereAtTheOriginTheMeshFrameIsTheWorld)
{
  const Scene scene = everyLightInTheMeshFrame();
  Scene world = scene;
  world.frame = SceneFrame::World;
  expectSameScene(placedOnMesh(scene, meshes[0]), world, 0);
}

TEST(SceneFrame, PositionsAndLengthsScaleWithTheMesh)
{
  const Scene scene = everyLightInTheMeshFrame();
  for (const MeshExtent& mesh : meshes)
  {
    SCOPED_TRACE("radius " + std::to_string(mesh.radius));
    const Scene placed = placedOnMesh(scene, mesh);
    EXPECT_EQ(placed.frame, SceneFrame::World);
    EXPECT_TRUE(sceneProblems(placed).empty());
    const double R = mesh.radius;
    const auto at = [&](const glm::dvec3& p) { return mesh.centre + R * p; };
    const double exact = 1e-15;
    expectNear(*placed.viewer.position, at(*scene.viewer.position), exact, "viewer position");
    expectNear(*placed.viewer.focalPoint, at(*scene.viewer.focalPoint), exact, "viewer focal point");
    for (std::size_t i = 0; i < scene.lights.size(); ++i)
    {
      const LightSource& source = scene.lights[i].source;
      const LightSource& world = placed.lights[i].source;
      const std::string name = scene.lights[i].name;
      if (const glm::dvec3* position = positionOf(source))
      {
        expectNear(*positionOf(world), at(*position), exact, name + " position");
        expectNear(attenuationOf(world)->minDistance, R * attenuationOf(source)->minDistance, exact, name);
      }
      if (const auto* spot = std::get_if<SpotLight>(&source))
      {
        EXPECT_EQ(std::get<SpotLight>(world).axis, spot->axis) << name;
      }
      if (const auto* distant = std::get_if<DistantLight>(&source))
      {
        EXPECT_EQ(std::get<DistantLight>(world).direction, distant->direction) << name;
      }
      if (const auto* area = std::get_if<AreaLight>(&source))
      {
        // Radiance stays: the solid angle an emitter fills does not change with scale.
        const auto& placedArea = std::get<AreaLight>(world);
        EXPECT_EQ(placedArea.intensity, area->intensity) << name;
        AreaLight expected = *area;
        if (auto* polygon = std::get_if<PolygonEmitter>(&expected.shape))
        {
          for (glm::dvec3& vertex : polygon->vertices)
          {
            vertex = at(vertex);
          }
        }
        if (auto* disk = std::get_if<DiskEmitter>(&expected.shape))
        {
          *disk = { at(disk->centre), disk->normal, R * disk->radius };
        }
        if (auto* sphere = std::get_if<SphereEmitter>(&expected.shape))
        {
          *sphere = { at(sphere->centre), R * sphere->radius };
        }
        expectSameShape(placedArea.shape, expected.shape, exact, name);
      }
      if (!isPositional(source) && !std::holds_alternative<AreaLight>(source))
      {
        EXPECT_EQ(emittedColor(world), emittedColor(source)) << name;
      }
    }
  }
}

/// Intensity x fall-off at world distance R d equals the mesh frame's at d, for every
/// attenuation model, inside min_distance as well as beyond the glTF range.
TEST(SceneFrame, PositionalLightsGiveTheSameIrradianceAtTheSameRelativeDistance)
{
  const Scene scene = everyLightInTheMeshFrame();
  for (const MeshExtent& mesh : meshes)
  {
    const Scene placed = placedOnMesh(scene, mesh);
    for (std::size_t i = 0; i < scene.lights.size(); ++i)
    {
      const Attenuation* relative = attenuationOf(scene.lights[i].source);
      if (!relative)
      {
        continue;
      }
      const Attenuation* world = attenuationOf(placed.lights[i].source);
      const double relativeIntensity = largestComponent(emittedColor(scene.lights[i].source));
      const double worldIntensity = largestComponent(emittedColor(placed.lights[i].source));
      for (const double d : { 1e-3, 0.03, 0.5, 1.0, 2.0, 4.0, 10.0, 100.0 })
      {
        const double expected = relativeIntensity * attenuationAt(*relative, d);
        expectNear(worldIntensity * attenuationAt(*world, mesh.radius * d), expected, 1e-12,
          scene.lights[i].name + " at " + std::to_string(d) + " radii, radius " + std::to_string(mesh.radius));
      }
    }
  }
}

/// Vertices at the same place relative to the mesh, with the same normals, get the same shading
/// whatever the mesh's size and place: every term of every light type, through the kernel.
TEST(SceneFrame, TheShadingDoesNotDependOnWhereTheMeshIsOrHowBigItIs)
{
  const Scene scene = everyLightInTheMeshFrame();
  const std::vector<glm::dvec3> relative = { { 0, 0, 1 }, { 0.9, 0, 0 }, { 0, 0.5, 0 }, { -0.6, 0.3, -0.7 },
    { 0.2, -0.9, 0.1 }, { 2.001, 1.5, 1 } }; // the last within min_distance of bulb
  std::vector<glm::dvec3> normals;
  for (const glm::dvec3& p : relative)
  {
    normals.push_back(unitVector(p));
  }
  const KernelHarness<double> reference(placedOnMesh(scene, meshes[0]), relative, normals, { "totals" });
  for (const MeshExtent& mesh : meshes)
  {
    SCOPED_TRACE("radius " + std::to_string(mesh.radius));
    std::vector<glm::dvec3> positions;
    for (const glm::dvec3& p : relative)
    {
      positions.push_back(mesh.centre + mesh.radius * p);
    }
    const KernelHarness<double> run(placedOnMesh(scene, mesh), positions, normals, { "totals" });
    for (const auto& [name, values] : reference.arrays)
    {
      for (std::size_t i = 0; i < values.size(); ++i)
      {
        EXPECT_NEAR(run.arrays.at(name)[i], values[i], 1e-9 * std::max(1.0, std::abs(values[i]))) << name << " " << i;
      }
    }
  }
}

TEST(SceneFrame, AMeshOfRadiusZeroIsMeasuredInWorldUnits)
{
  const Scene scene = everyLightInTheMeshFrame();
  const MeshExtent point = extentOf({ 5, 6, 7 }, 0);
  const Scene placed = placedOnMesh(scene, point);
  Scene shifted = placedOnMesh(scene, extentOf(point.centre, 1));
  expectSameScene(placed, shifted, 0);
}

/// The bounding box of data/meshes/bunny_zipper.ply's points, read as float32 as VTK's PLY
/// reader does, as the filter measures a mesh.
MeshExtent bunnyExtent()
{
  std::ifstream file(shadelab::testing::sourcePath("data/meshes/bunny_zipper.ply"));
  std::string line;
  std::size_t count = 0;
  while (std::getline(file, line) && line != "end_header")
  {
    if (line.rfind("element vertex ", 0) == 0)
    {
      count = std::stoul(line.substr(15));
    }
  }
  const double inf = std::numeric_limits<double>::infinity();
  glm::dvec3 low(inf), high(-inf);
  for (std::size_t i = 0; i < count && std::getline(file, line); ++i)
  {
    std::istringstream fields(line);
    double x, y, z;
    fields >> x >> y >> z;
    const glm::dvec3 p{ float(x), float(y), float(z) };
    low = glm::min(low, p);
    high = glm::max(high, p);
  }
  EXPECT_EQ(count, 35947u);
  return extentOf(0.5 * (low + high), 0.5 * vectorLength(high - low));
}

TEST(SceneFrame, StudioMeshIsStudioOnTheBunny)
{
  const MeshExtent bunny = bunnyExtent();
  // data/scenes/studio_mesh.json holds studio.json's numbers converted with these (as
  // docs/guide/scene-files.md states them), to 12 significant digits.
  EXPECT_NEAR(bunny.centre.x, -0.0168404, 1e-7);
  EXPECT_NEAR(bunny.centre.y, 0.1101542, 1e-7);
  EXPECT_NEAR(bunny.centre.z, -0.0015370, 1e-7);
  EXPECT_NEAR(bunny.radius, 0.1251230, 1e-7);
  const Scene studio = readSceneFile(shadelab::testing::sourcePath("data/scenes/studio.json"));
  const Scene placed =
    placedOnMesh(readSceneFile(shadelab::testing::sourcePath("data/scenes/studio_mesh.json")), bunny);
  expectSameScene(placed, studio, 1e-9);

  // The same totals on a few of the bunny's points (bounding-box corners and its centre).
  const std::vector<glm::dvec3> points = { bunny.centre, bunny.centre + glm::dvec3(0.07, 0.07, 0.05),
    bunny.centre + glm::dvec3(-0.07, 0.07, -0.05), bunny.centre + glm::dvec3(0.05, -0.07, 0.06) };
  const std::vector<glm::dvec3> normals = { { 0, 0, 1 }, unitVector({ 1, 1, 1 }), unitVector({ -1, 1, -1 }),
    unitVector({ 1, -1, 1 }) };
  const KernelHarness<double> expected(studio, points, normals, { "totals" });
  const KernelHarness<double> run(placed, points, normals, { "totals" });
  for (const auto& [name, values] : expected.arrays)
  {
    for (std::size_t i = 0; i < values.size(); ++i)
    {
      EXPECT_NEAR(run.arrays.at(name)[i], values[i], 1e-9 * std::max(1.0, std::abs(values[i]))) << name << " " << i;
    }
  }
}

TEST(DefaultLightKit, IsVtkLightKitInTheMeshFrame)
{
  const Scene kit = defaultLightKit();
  EXPECT_TRUE(sceneProblems(kit).empty());
  EXPECT_TRUE(sceneProblems(kit, Precision::Float32).empty());
  EXPECT_EQ(kit.frame, SceneFrame::Mesh);
  EXPECT_EQ(kit.model, ShadingModel::Lecture);
  ASSERT_EQ(kit.lights.size(), 5u);

  // Elevation e and azimuth a (degrees) as vtkLight::SetDirectionAngle places a light, in
  // camera coordinates: the light travels from there toward the focal point.
  const auto fromAngles = [](double e, double a)
  {
    const double rad = std::acos(-1.0) / 180;
    return -glm::dvec3(std::cos(e * rad) * std::sin(a * rad), std::sin(e * rad), std::cos(e * rad) * std::cos(a * rad));
  };
  struct Expected
  {
    const char* name;
    glm::dvec3 direction;
    double intensity;
  };
  const double key = 0.75;
  const Expected distant[] = { { "key", fromAngles(50, 10), key }, { "fill", fromAngles(-75, -10), key / 3 },
    { "back_left", fromAngles(0, -110), key / 3.5 }, { "back_right", fromAngles(0, 110), key / 3.5 } };
  for (std::size_t i = 0; i < 4; ++i)
  {
    SCOPED_TRACE(distant[i].name);
    EXPECT_EQ(kit.lights[i].name, distant[i].name);
    const auto& light = std::get<DistantLight>(kit.lights[i].source);
    EXPECT_LE(vectorLength(light.direction - distant[i].direction), 1e-6);
    EXPECT_NEAR(light.intensity, distant[i].intensity, 1e-6);
  }
  const auto& keyLight = std::get<DistantLight>(kit.lights[0].source);
  const auto& fillLight = std::get<DistantLight>(kit.lights[1].source);
  EXPECT_GT(keyLight.color.r, keyLight.color.b);   // warm
  EXPECT_LT(fillLight.color.r, fillLight.color.b); // cool
  EXPECT_EQ(kit.lights[4].name, "ambient");
  EXPECT_NEAR(std::get<AmbientLight>(kit.lights[4].source).intensity, 0.1, 1e-12);

  // The bounding sphere fills a 30-degree view: sin(15 degrees) = R / distance.
  EXPECT_EQ(*kit.viewer.focalPoint, glm::dvec3(0));
  EXPECT_EQ(kit.viewer.position->x, 0);
  EXPECT_EQ(kit.viewer.position->y, 0);
  EXPECT_NEAR(kit.viewer.position->z, 1 / std::sin(std::acos(-1.0) / 12), 1e-12);
}

TEST(DefaultLightKit, LightsAPartAnywhereFromTheSameDirections)
{
  // The CAD part of the problem that the mesh frame solves: x 0..4.8, y 12.6..17.9.
  const glm::dvec3 low(0, 12.6, -1), high(4.8, 17.9, 1);
  const MeshExtent part = extentOf(0.5 * (low + high), 0.5 * vectorLength(high - low));
  const Scene placed = placedOnMesh(defaultLightKit(), part);
  EXPECT_TRUE(sceneProblems(placed).empty());
  EXPECT_NEAR(vectorLength(*placed.viewer.position - part.centre) * std::sin(std::acos(-1.0) / 12), part.radius, 1e-9);
  EXPECT_EQ(*placed.viewer.focalPoint, part.centre);
}

TEST(DefaultLightKit, TheGuideShowsIt)
{
  std::ifstream file(shadelab::testing::sourcePath("docs/guide/scene-files.md"));
  std::ostringstream text;
  text << file.rdbuf();
  EXPECT_NE(text.str().find("```json\n" + defaultLightKitText() + "```\n"), std::string::npos);
}
}
