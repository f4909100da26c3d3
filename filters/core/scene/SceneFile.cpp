#include "SceneFile.h"

#include <nlohmann/json.hpp>

#include "EnvironmentMap.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <memory>
#include <sstream>

namespace shadelab
{
namespace
{
using Json = nlohmann::json;

/// A problem at a JSON pointer; turned into a SceneFileError once the file name is known.
struct JsonError
{
  std::string path;
  std::string message;
};

std::string describe(const Json& value)
{
  std::string text = value.dump();
  return text.size() > 40 ? text.substr(0, 37) + "..." : text;
}

/// A value in the document together with its JSON pointer, so every error can say where.
class Node
{
public:
  Node(const Json& value, std::string path)
    : value_(value)
    , path_(std::move(path))
  {
  }

  const std::string& path() const { return path_; }

  [[noreturn]] void fail(const std::string& message) const { throw JsonError{ path_, message }; }

  /// Requires an object whose keys are all in allowed (a misspelt key is an error, not a
  /// silently ignored setting).
  void expectObject(std::initializer_list<const char*> allowed) const
  {
    if (!value_.is_object())
    {
      fail("must be an object, got " + describe(value_));
    }
    for (const auto& item : value_.items())
    {
      const bool known = std::any_of(allowed.begin(), allowed.end(),
        [&](const char* key) { return item.key() == key; });
      if (!known)
      {
        std::string list;
        for (const char* key : allowed)
        {
          list += (list.empty() ? "" : ", ") + std::string(key);
        }
        Node(item.value(), path_ + "/" + item.key()).fail("unknown field; allowed here: " + list);
      }
    }
  }

  bool has(const char* key) const { return value_.contains(key); }

  Node at(const char* key) const
  {
    if (!has(key))
    {
      Node(value_, path_ + "/" + key).fail("missing");
    }
    return Node(value_.at(key), path_ + "/" + key);
  }

  double number() const
  {
    if (!value_.is_number())
    {
      fail("must be a number, got " + describe(value_));
    }
    return value_.get<double>();
  }

  int wholeNumber(int low, int high) const
  {
    const double x = number();
    if (!(x >= low && x <= high && x == std::floor(x)))
    {
      fail("must be a whole number from " + std::to_string(low) + " to " + std::to_string(high));
    }
    return static_cast<int>(x);
  }

  bool boolean() const
  {
    if (!value_.is_boolean())
    {
      fail("must be true or false, got " + describe(value_));
    }
    return value_.get<bool>();
  }

  std::string text() const
  {
    if (!value_.is_string())
    {
      fail("must be a string, got " + describe(value_));
    }
    return value_.get<std::string>();
  }

  /// One of the listed strings; returns the value paired with it.
  template <typename Value>
  Value choice(std::initializer_list<std::pair<const char*, Value>> options) const
  {
    const std::string given = text();
    std::string list;
    for (const auto& [name, value] : options)
    {
      if (given == name)
      {
        return value;
      }
      list += (list.empty() ? "\"" : ", \"") + std::string(name) + "\"";
    }
    fail("\"" + given + "\" is not one of " + list);
  }

  glm::dvec3 vector3(const char* expected = "an array of 3 numbers") const
  {
    if (!value_.is_array() || value_.size() != 3 ||
      !std::all_of(value_.begin(), value_.end(), [](const Json& x) { return x.is_number(); }))
    {
      fail(std::string("must be ") + expected + ", got " + describe(value_));
    }
    return { value_[0].get<double>(), value_[1].get<double>(), value_[2].get<double>() };
  }

  /// An RGB colour: [r, g, b], or one number for grey.
  Rgb rgb() const
  {
    return value_.is_number() ? Rgb(value_.get<double>()) : vector3("[r, g, b] or one number");
  }

  std::size_t size() const { return value_.size(); }
  bool isArray() const { return value_.is_array(); }
  bool isString() const { return value_.is_string(); }
  Node element(std::size_t i) const { return Node(value_.at(i), path_ + "/" + std::to_string(i)); }

private:
  const Json& value_;
  std::string path_;
};

double numberOr(const Node& object, const char* key, double fallback)
{
  return object.has(key) ? object.at(key).number() : fallback;
}

Rgb rgbOr(const Node& object, const char* key, const Rgb& fallback)
{
  return object.has(key) ? object.at(key).rgb() : fallback;
}

Attenuation readAttenuation(const Node& light)
{
  Attenuation a;
  a.minDistance = numberOr(light, "min_distance", a.minDistance);
  if (!light.has("attenuation"))
  {
    return a;
  }
  const Node node = light.at("attenuation");
  const auto modelOf = [](const Node& name)
  {
    return name.choice<AttenuationModel>({ { "none", AttenuationModel::None },
      { "inverse", AttenuationModel::Inverse }, { "inverse_square", AttenuationModel::InverseSquare },
      { "vtk", AttenuationModel::ConstantLinearQuadratic }, { "gltf_range", AttenuationModel::GltfRange } });
  };
  if (node.isString())
  {
    a.model = modelOf(node);
    if (a.model == AttenuationModel::ConstantLinearQuadratic || a.model == AttenuationModel::GltfRange)
    {
      node.fail("this model has parameters: write it as an object, e.g. {\"model\": \"" +
        node.text() + "\", ...}");
    }
    return a;
  }
  node.expectObject({ "model", "constant", "linear", "quadratic", "range" });
  a.model = modelOf(node.at("model"));
  // Now that the model is known, its parameters are the only fields allowed.
  switch (a.model)
  {
    case AttenuationModel::ConstantLinearQuadratic:
      node.expectObject({ "model", "constant", "linear", "quadratic" });
      a.constant = numberOr(node, "constant", 1.0);
      a.linear = numberOr(node, "linear", 0.0);
      a.quadratic = numberOr(node, "quadratic", 0.0);
      break;
    case AttenuationModel::GltfRange:
      node.expectObject({ "model", "range" });
      a.range = node.at("range").number();
      break;
    default:
      node.expectObject({ "model" });
  }
  return a;
}

SpotCone readCone(const Node& light)
{
  SpotCone cone;
  if (!light.has("cone"))
  {
    return cone;
  }
  const Node node = light.at("cone");
  node.expectObject({ "model", "angle", "exponent", "inner_angle", "outer_angle" });
  cone.model = node.at("model").choice<ConeModel>({ { "vtk", ConeModel::Vtk }, { "gltf", ConeModel::Gltf } });
  if (cone.model == ConeModel::Vtk)
  {
    node.expectObject({ "model", "angle", "exponent" });
    cone.halfAngleDegrees = numberOr(node, "angle", cone.halfAngleDegrees);
    cone.exponent = numberOr(node, "exponent", cone.exponent);
  }
  else
  {
    node.expectObject({ "model", "inner_angle", "outer_angle" });
    cone.innerAngleDegrees = numberOr(node, "inner_angle", cone.innerAngleDegrees);
    cone.outerAngleDegrees = numberOr(node, "outer_angle", cone.outerAngleDegrees);
  }
  return cone;
}

template <typename Light>
void readStrength(const Node& node, Light& light)
{
  light.color = rgbOr(node, "color", light.color);
  light.intensity = numberOr(node, "intensity", light.intensity);
}

/// A light described by its colour and intensity alone.
template <typename Light>
Light readColourOnlyLight(const Node& node)
{
  node.expectObject({ "name", "type", "color", "intensity" });
  Light light;
  readStrength(node, light);
  return light;
}

enum class LightType
{
  Distant,
  Headlight,
  Point,
  Spot,
  Ambient,
  Polygon,
  Rectangle,
  Disk,
  Sphere,
  Environment,
};

Sampling readSampling(const Node& node)
{
  Sampling sampling;
  if (node.has("samples"))
  {
    sampling.samples = node.at("samples").wholeNumber(2, maxSamplesPerVertex);
  }
  if (node.has("stratified"))
  {
    sampling.stratified = node.at("stratified").boolean();
  }
  return sampling;
}

/// The fields every area light has besides its shape.
AreaLight readAreaLight(const Node& node, EmitterShape shape)
{
  AreaLight light;
  light.shape = std::move(shape);
  readStrength(node, light);
  if (node.has("two_sided"))
  {
    light.twoSided = node.at("two_sided").boolean();
  }
  if (node.has("estimator"))
  {
    light.estimator = node.at("estimator").choice<AreaEstimator>({ { "exact", AreaEstimator::Exact },
      { "monte_carlo", AreaEstimator::MonteCarlo }, { "point", AreaEstimator::Point } });
  }
  light.sampling = readSampling(node);
  return light;
}

/// A path in a scene file is relative to the scene file's folder.
std::string resolvePath(const std::string& path, const std::string& sceneFile)
{
  const std::filesystem::path given(path);
  if (given.is_absolute())
  {
    return path;
  }
  return (std::filesystem::path(sceneFile).parent_path() / given).lexically_normal().string();
}

EnvironmentLight readEnvironmentLight(const Node& node, const std::string& sceneFile)
{
  node.expectObject({ "name", "type", "file", "rotation", "color", "intensity", "estimator", "directions",
    "samples", "stratified", "brute_force_width" });
  EnvironmentLight light;
  readStrength(node, light);
  light.file = resolvePath(node.at("file").text(), sceneFile);
  if (node.has("rotation"))
  {
    light.rotationDegrees = node.at("rotation").number();
  }
  if (node.has("estimator"))
  {
    light.estimator = node.at("estimator").choice<EnvironmentEstimator>(
      { { "sh", EnvironmentEstimator::SphericalHarmonics }, { "monte_carlo", EnvironmentEstimator::MonteCarlo },
        { "brute_force", EnvironmentEstimator::BruteForce } });
  }
  if (node.has("directions"))
  {
    light.directions = node.at("directions").choice<EnvironmentDirections>(
      { { "luminance", EnvironmentDirections::Luminance }, { "cosine", EnvironmentDirections::Cosine } });
  }
  light.sampling = readSampling(node);
  if (node.has("brute_force_width"))
  {
    light.bruteForceWidth = node.at("brute_force_width").wholeNumber(2, 1 << 20);
  }
  try
  {
    light.map = std::make_shared<const EnvironmentMap>(readEnvironmentMap(light.file));
  }
  catch (const std::runtime_error& error)
  {
    node.at("file").fail(error.what());
  }
  return light;
}

NamedLight readLight(const Node& node, std::size_t index, const std::string& sceneFile)
{
  // First every field any light may have (so that a non-object or a misspelt field is caught
  // before the type is read), then, below, only those of this light's type.
  node.expectObject({ "name", "type", "color", "intensity", "direction", "intensity_from_length",
    "position", "attenuation", "min_distance", "cone", "vertices", "center", "edge_u", "edge_v", "normal",
    "radius", "two_sided", "estimator", "samples", "stratified", "file", "rotation", "directions",
    "brute_force_width" });
  const LightType type = node.at("type").choice<LightType>({ { "distant", LightType::Distant },
    { "headlight", LightType::Headlight }, { "point", LightType::Point }, { "spot", LightType::Spot },
    { "ambient", LightType::Ambient }, { "polygon", LightType::Polygon }, { "rectangle", LightType::Rectangle },
    { "disk", LightType::Disk }, { "sphere", LightType::Sphere }, { "environment", LightType::Environment } });
  NamedLight light;
  switch (type)
  {
    case LightType::Distant:
    {
      node.expectObject({ "name", "type", "color", "intensity", "direction", "intensity_from_length" });
      DistantLight distant;
      readStrength(node, distant);
      distant.direction = node.at("direction").vector3();
      if (node.has("intensity_from_length"))
      {
        distant.intensityFromLength = node.at("intensity_from_length").boolean();
      }
      light.source = distant;
      break;
    }
    case LightType::Headlight:
      light.source = readColourOnlyLight<Headlight>(node);
      break;
    case LightType::Point:
    {
      node.expectObject({ "name", "type", "color", "intensity", "position", "attenuation", "min_distance" });
      PointLight point;
      readStrength(node, point);
      point.position = node.at("position").vector3();
      point.attenuation = readAttenuation(node);
      light.source = point;
      break;
    }
    case LightType::Spot:
    {
      node.expectObject({ "name", "type", "color", "intensity", "position", "direction",
        "attenuation", "min_distance", "cone" });
      SpotLight spot;
      readStrength(node, spot);
      spot.position = node.at("position").vector3();
      spot.axis = node.at("direction").vector3();
      spot.attenuation = readAttenuation(node);
      spot.cone = readCone(node);
      light.source = spot;
      break;
    }
    case LightType::Ambient:
      light.source = readColourOnlyLight<AmbientLight>(node);
      break;
    case LightType::Polygon:
    {
      node.expectObject({ "name", "type", "color", "intensity", "vertices", "two_sided", "estimator", "samples",
        "stratified" });
      const Node vertices = node.at("vertices");
      if (!vertices.isArray())
      {
        vertices.fail("must be an array of [x, y, z] points");
      }
      PolygonEmitter polygon;
      for (std::size_t i = 0; i < vertices.size(); ++i)
      {
        polygon.vertices.push_back(vertices.element(i).vector3());
      }
      light.source = readAreaLight(node, polygon);
      break;
    }
    case LightType::Rectangle:
    {
      // Corners c - u/2 - v/2, c + u/2 - v/2, c + u/2 + v/2, c - u/2 + v/2: it emits toward u x v.
      node.expectObject({ "name", "type", "color", "intensity", "center", "edge_u", "edge_v", "two_sided",
        "estimator", "samples", "stratified" });
      const glm::dvec3 c = node.at("center").vector3();
      const glm::dvec3 u = 0.5 * node.at("edge_u").vector3();
      const glm::dvec3 v = 0.5 * node.at("edge_v").vector3();
      light.source = readAreaLight(node, PolygonEmitter{ { c - u - v, c + u - v, c + u + v, c - u + v } });
      break;
    }
    case LightType::Disk:
    {
      node.expectObject({ "name", "type", "color", "intensity", "center", "normal", "radius", "two_sided",
        "estimator", "samples", "stratified" });
      light.source = readAreaLight(
        node, DiskEmitter{ node.at("center").vector3(), node.at("normal").vector3(), node.at("radius").number() });
      break;
    }
    case LightType::Sphere:
    {
      node.expectObject({ "name", "type", "color", "intensity", "center", "radius", "estimator", "samples",
        "stratified" });
      light.source = readAreaLight(node, SphereEmitter{ node.at("center").vector3(), node.at("radius").number() });
      break;
    }
    case LightType::Environment:
      light.source = readEnvironmentLight(node, sceneFile);
      break;
  }
  light.name = node.has("name") ? node.at("name").text() : lightTypeName(light.source) + std::to_string(index);
  return light;
}

Material readMaterial(const Node& node, ShadingModel model)
{
  Material m;
  if (model == ShadingModel::VtkOpenGL2)
  {
    // vtkProperty's defaults: Ambient 0, Diffuse 1, Specular 0, SpecularPower 1, white colours.
    m.ka = Rgb(0.0);
    m.kd = Rgb(1.0);
    m.ks = Rgb(0.0);
    m.shininess = 1.0;
    node.expectObject({ "ka", "kd", "ks", "shininess" });
  }
  else
  {
    node.expectObject({ "ka", "kd", "ks", "shininess", "specular", "two_sided" });
  }
  m.kd = rgbOr(node, "kd", m.kd);
  // docs/formulas.md section 7: ambient RGB defaults to the diffuse RGB.
  m.ka = rgbOr(node, "ka", model == ShadingModel::Lecture ? m.kd : m.ka);
  m.ks = rgbOr(node, "ks", m.ks);
  m.shininess = numberOr(node, "shininess", m.shininess);
  if (node.has("specular"))
  {
    m.specular = node.at("specular").choice<SpecularModel>({ { "blinn-phong", SpecularModel::BlinnPhong },
      { "phong", SpecularModel::Phong }, { "none", SpecularModel::None } });
  }
  if (node.has("two_sided"))
  {
    m.twoSided = node.at("two_sided").boolean();
  }
  return m;
}

Viewer readViewer(const Node& node)
{
  node.expectObject({ "position", "focal_point", "direction" });
  Viewer viewer;
  if (node.has("position") == node.has("direction"))
  {
    node.fail("give either a position (a local viewer) or a direction (a viewer at infinity)");
  }
  if (node.has("position"))
  {
    viewer.position = node.at("position").vector3();
    if (node.has("focal_point"))
    {
      viewer.focalPoint = node.at("focal_point").vector3();
    }
  }
  else
  {
    if (node.has("focal_point"))
    {
      node.at("focal_point").fail("a viewer at infinity has no focal point: give a position instead of a direction");
    }
    viewer.viewDirection = node.at("direction").vector3();
  }
  return viewer;
}

Scene readScene(const Json& document, const std::string& sceneFile)
{
  const Node root(document, "");
  root.expectObject({ "model", "frame", "viewer", "material", "lights" });
  Scene scene;
  if (root.has("model"))
  {
    scene.model = root.at("model").choice<ShadingModel>(
      { { "lecture", ShadingModel::Lecture }, { "vtk", ShadingModel::VtkOpenGL2 } });
  }
  if (root.has("frame"))
  {
    scene.frame = root.at("frame").choice<SceneFrame>({ { "world", SceneFrame::World }, { "mesh", SceneFrame::Mesh } });
  }
  if (root.has("viewer"))
  {
    scene.viewer = readViewer(root.at("viewer"));
  }
  scene.material = readMaterial(root.has("material") ? root.at("material") : Node(Json::object(), "/material"), scene.model);
  const Node lights = root.at("lights");
  if (!lights.isArray())
  {
    lights.fail("must be an array of lights");
  }
  for (std::size_t i = 0; i < lights.size(); ++i)
  {
    scene.lights.push_back(readLight(lights.element(i), i, sceneFile));
  }
  if (scene.model == ShadingModel::VtkOpenGL2)
  {
    // Like vtkRenderer with AutomaticLightCreation: no light means one white headlight.
    if (scene.lights.empty())
    {
      scene.lights.push_back({ "headlight", Headlight{} });
    }
    scene.vtkLoneHeadlight =
      scene.lights.size() == 1 && std::holds_alternative<Headlight>(scene.lights[0].source);
  }
  const std::vector<SceneProblem> problems = sceneProblems(scene);
  if (!problems.empty())
  {
    throw JsonError{ problems.front().path, problems.front().message };
  }
  return scene;
}
}

namespace
{
constexpr int maxSceneDepth = 32;
}

Scene parseScene(const std::string& text, const std::string& sourceName)
{
  Json document;
  try
  {
    // No scene nests deeper than a few levels; refusing deeper ones as they are parsed keeps
    // every later walk over the document (and its description in messages) shallow.
    const Json::parser_callback_t depthLimit = [&](int depth, Json::parse_event_t, Json&)
    {
      if (depth > maxSceneDepth)
      {
        throw SceneFileError(sourceName + ": nested more than " + std::to_string(maxSceneDepth) +
          " levels deep: a scene file has a few levels (lights, a light, its fields)");
      }
      return true;
    };
    document = Json::parse(text, depthLimit);
  }
  catch (const Json::exception& error)
  {
    // nlohmann prefixes "[json.exception.parse_error.101] "; the rest says what and where
    // (a syntax error's line and column, or a number too large such as 1e400).
    std::string message = error.what();
    const std::size_t end = message.find("] ");
    message = end == std::string::npos ? message : message.substr(end + 2);
    // The message quotes what it last read, which in a binary file is any byte.
    std::replace_if(message.begin(), message.end(), [](char c) { return c < 0x20 || c >= 0x7f; }, '?');
    throw SceneFileError(sourceName + ": not valid JSON: " + message);
  }
  try
  {
    return readScene(document, sourceName);
  }
  catch (const JsonError& error)
  {
    throw SceneFileError(sourceName + ": " + (error.path.empty() ? "/" : error.path) + ": " + error.message);
  }
}

Scene readSceneFile(const std::string& fileName)
{
  std::error_code error;
  if (std::filesystem::is_directory(fileName, error))
  {
    throw SceneFileError(fileName + ": is a folder, not a scene file");
  }
  std::ifstream file(fileName);
  if (!file)
  {
    throw SceneFileError(fileName + ": cannot open the scene file (does it exist, and is it readable?)");
  }
  std::ostringstream text;
  text << file.rdbuf();
  return parseScene(text.str(), fileName);
}
}
