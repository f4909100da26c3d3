#include "SceneFile.h"

#include "JsonNode.h"
#include "LightFields.h"
#include "SpectrumFields.h"

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
/// A light; shadowsByDefault is the scene's "shadows", which lights that can cast shadows take
/// unless they say otherwise.
NamedLight readLight(const JsonNode& node, std::size_t index, const std::string& sceneFile, bool shadowsByDefault)
{
  NamedLight light;
  light.source = readLightSource(node, sceneFile);
  if (node.has("spectrum"))
  {
    if (node.has("color"))
    {
      node.at("color").fail("give the light a colour or a spectrum, not both");
    }
    light.spectrum = readSpectrum(node.at("spectrum"));
    const Rgb rgb = withColorTables(node.at("spectrum"), [&] { return emitterRgb(*light.spectrum); });
    if (!isFinite(rgb))
    {
      node.at("spectrum").fail("emits no visible light (its luminance Y is 0)");
    }
    std::visit([&](auto& source) { source.color = rgb; }, light.source);
  }
  light.name = node.has("name") ? node.at("name").text() : lightTypeName(light.source) + std::to_string(index);
  light.shadows = node.has("shadows") ? node.at("shadows").boolean() : shadowsByDefault && castsShadows(light.source);
  return light;
}

AmbientOcclusion readAmbientOcclusion(const JsonNode& node)
{
  node.expectObject({ "rays", "max_rays", "stratified", "max_distance" });
  AmbientOcclusion occlusion;
  readSampleCount(node, "rays", "max_rays", occlusion.sampling);
  if (node.has("stratified"))
  {
    occlusion.sampling.stratified = node.at("stratified").boolean();
  }
  if (node.has("max_distance"))
  {
    occlusion.maxDistance = node.at("max_distance").number();
  }
  return occlusion;
}

}

void readBounces(const JsonNode& node, Interreflection& interreflection)
{
  interreflection.bouncesFromTolerance = node.isString();
  if (node.isString() && node.text() != "auto")
  {
    node.fail("must be a whole number of bounces, or \"auto\" (as many as a tolerance needs)");
  }
  interreflection.bounces = node.isString() ? 1 : node.wholeNumber(0, Interreflection::maxBounces);
}

namespace
{
Interreflection readInterreflection(const JsonNode& node)
{
  node.expectObject({ "bounces", "samples", "max_samples", "stratified" });
  Interreflection interreflection;
  if (node.has("bounces"))
  {
    readBounces(node.at("bounces"), interreflection);
  }
  readSampleCount(node, "samples", "max_samples", interreflection.sampling);
  if (node.has("stratified"))
  {
    interreflection.sampling.stratified = node.at("stratified").boolean();
  }
  return interreflection;
}

/// A coefficient read from a point-data array: {"array": "Colors", ...}.
ArrayCoefficient readArrayCoefficient(const JsonNode& node, MaterialCoefficient coefficient)
{
  // One number per vertex (a shininess, a metallic factor, a roughness) is read as it is.
  node.expectObject(isColorCoefficient(coefficient)
      ? std::vector<const char*>{ "array", "encoding", "scale", "colormap", "range", "clamp" }
      : std::vector<const char*>{ "array", "scale", "clamp" });
  ArrayCoefficient c;
  c.array = node.at("array").text();
  if (c.array.empty())
  {
    node.at("array").fail("must name a point-data array of the mesh");
  }
  if (node.has("encoding"))
  {
    c.encoding = node.at("encoding")
                   .choice<ArrayEncoding>({ { "srgb", ArrayEncoding::Srgb }, { "linear", ArrayEncoding::Linear } });
  }
  c.scale = numberOr(node, "scale", c.scale);
  if (node.has("colormap"))
  {
    const std::string name = node.at("colormap").text();
    if (!isColorMapName(name))
    {
      node.at("colormap").fail("\"" + name + "\" is not one of " + colorMapNameList());
    }
    c.colorMap = name;
  }
  if (node.has("range"))
  {
    if (c.colorMap.empty())
    {
      node.at("range").fail("a range is the colour map's: give \"colormap\" too, or leave the range out");
    }
    c.range = node.at("range").interval();
  }
  c.clamp = node.has("clamp") && node.at("clamp").boolean();
  return c;
}

/// A colour coefficient: RGB numbers, a reflectance spectrum ({"spectrum": ...}, whose RGB
/// under D65 it is in the RGB model), or an array ({"array": ...}) whose number in the material
/// becomes its bound (Material).
void readColorCoefficient(const JsonNode& material, MaterialCoefficient coefficient, Material& m, Rgb& value)
{
  const char* key = coefficientKey(coefficient);
  if (material.has(key) && material.at(key).isObject() && material.at(key).has("spectrum"))
  {
    const JsonNode node = material.at(key);
    node.expectObject({ "spectrum" });
    const SampledSpectrum reflectance = readSpectrum(node.at("spectrum"));
    value = withColorTables(node, [&] { return reflectorRgb(reflectance); });
    m.spectra[int(coefficient)] = reflectance;
  }
  else if (material.has(key) && material.at(key).isObject())
  {
    m.arrays[coefficient] = readArrayCoefficient(material.at(key), coefficient);
    value = Rgb(m.arrays[coefficient]->scale);
  }
  else
  {
    value = rgbOr(material, key, value);
  }
}

/// A coefficient that is one number, or an array's ({"array": ...}: the shininess, the metallic
/// factor, the roughness): the array's scale, which then stands as the material's number, or
/// the number given, or else `fallback`.
double readNumberCoefficient(const JsonNode& node, MaterialCoefficient coefficient, Material& material, double fallback)
{
  const char* key = coefficientKey(coefficient);
  if (node.has(key) && node.at(key).isObject())
  {
    material.arrays[coefficient] = readArrayCoefficient(node.at(key), coefficient);
    return material.arrays[coefficient]->scale;
  }
  return numberOr(node, key, fallback);
}

/// The vtk_pbr model's material: vtkProperty's PBR parameters, with its defaults. The base
/// colour, metallic factor and roughness may each come from an array ({"array": ...}; the base
/// colour's is VTK's scalar colouring, kd's array in Material), scaled by its "scale" (the
/// property's Diffuse, Metallic or Roughness), which then stands as the material's number.
void readMicrofacetMaterial(const JsonNode& node, Material& material)
{
  node.expectObject({ "base_color", "metallic", "roughness", "base_ior", "edge_tint" });
  MicrofacetMaterial& m = material.microfacet;
  if (node.has("base_color") && node.at("base_color").isObject())
  {
    material.arrays[MaterialCoefficient::Diffuse] =
      readArrayCoefficient(node.at("base_color"), MaterialCoefficient::Diffuse);
    m.baseColor = Rgb(material.arrays[MaterialCoefficient::Diffuse]->scale);
  }
  else
  {
    m.baseColor = rgbOr(node, "base_color", m.baseColor);
  }
  m.metallic = readNumberCoefficient(node, MaterialCoefficient::Metallic, material, m.metallic);
  m.roughness = readNumberCoefficient(node, MaterialCoefficient::Roughness, material, m.roughness);
  m.baseIor = numberOr(node, "base_ior", m.baseIor);
  m.edgeTint = rgbOr(node, "edge_tint", m.edgeTint);
}

Material readMaterial(const JsonNode& node, ShadingModel model)
{
  Material m;
  if (model == ShadingModel::VtkPbr)
  {
    m.ka = m.kd = m.ks = Rgb(0.0); // the lecture's coefficients, which the microfacet model has none of
    readMicrofacetMaterial(node, m);
    return m;
  }
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
  readColorCoefficient(node, MaterialCoefficient::Diffuse, m, m.kd);
  // docs/formulas.md section 7: ambient RGB defaults to the diffuse RGB (its array too).
  if (model == ShadingModel::Lecture && !node.has("ka"))
  {
    m.ka = m.kd;
    m.arrays[MaterialCoefficient::Ambient] = m.arrays[MaterialCoefficient::Diffuse];
    m.spectra[int(MaterialCoefficient::Ambient)] = m.spectra[int(MaterialCoefficient::Diffuse)];
  }
  else
  {
    readColorCoefficient(node, MaterialCoefficient::Ambient, m, m.ka);
  }
  readColorCoefficient(node, MaterialCoefficient::Specular, m, m.ks);
  m.shininess = readNumberCoefficient(node, MaterialCoefficient::Shininess, m, m.shininess);
  if (node.has("specular"))
  {
    m.specular = node.at("specular")
                   .choice<SpecularModel>({ { "blinn-phong", SpecularModel::BlinnPhong },
                     { "phong", SpecularModel::Phong }, { "none", SpecularModel::None } });
  }
  if (node.has("two_sided"))
  {
    m.twoSided = node.at("two_sided").boolean();
  }
  return m;
}

Viewer readViewer(const JsonNode& node)
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
  const JsonNode root(document, "");
  root.expectObject({ "model", "frame", "viewer", "material", "lights", "shadows", "self_shadowing",
    "ambient_occlusion", "interreflection", "spectral" });
  Scene scene;
  if (root.has("model"))
  {
    scene.model = root.at("model").choice<ShadingModel>({ { modelName(ShadingModel::Lecture), ShadingModel::Lecture },
      { modelName(ShadingModel::VtkOpenGL2), ShadingModel::VtkOpenGL2 },
      { modelName(ShadingModel::VtkPbr), ShadingModel::VtkPbr } });
  }
  if (root.has("frame"))
  {
    scene.frame = root.at("frame").choice<SceneFrame>({ { "world", SceneFrame::World }, { "mesh", SceneFrame::Mesh } });
  }
  if (root.has("viewer"))
  {
    scene.viewer = readViewer(root.at("viewer"));
  }
  scene.materialGiven = root.has("material");
  scene.material =
    readMaterial(root.has("material") ? root.at("material") : JsonNode(Json::object(), "/material"), scene.model);
  const JsonNode lights = root.at("lights");
  if (!lights.isArray())
  {
    lights.fail("must be an array of lights");
  }
  const bool shadowsByDefault = root.has("shadows") && root.at("shadows").boolean();
  for (std::size_t i = 0; i < lights.size(); ++i)
  {
    scene.lights.push_back(readLight(lights.element(i), i, sceneFile, shadowsByDefault));
  }
  if (root.has("self_shadowing"))
  {
    scene.selfShadowing = root.at("self_shadowing").choiceAmong(selfShadowingNames);
  }
  if (root.has("ambient_occlusion"))
  {
    scene.ambientOcclusion = readAmbientOcclusion(root.at("ambient_occlusion"));
  }
  if (root.has("interreflection"))
  {
    const Interreflection interreflection = readInterreflection(root.at("interreflection"));
    scene.interreflection = interreflection.bounces > 0 ? std::optional(interreflection) : std::nullopt;
  }
  if (root.has("spectral"))
  {
    const JsonNode spectral = root.at("spectral");
    spectral.expectObject({ "band_nm" });
    scene.spectral = SpectralMode{ numberOr(spectral, "band_nm", SpectralMode{}.bandNm) };
  }
  if (reproducesVtkRenderer(scene.model))
  {
    // Like vtkRenderer with AutomaticLightCreation: no light means one white headlight.
    if (scene.lights.empty())
    {
      scene.lights.push_back({ "headlight", Headlight{} });
    }
    scene.vtkLoneHeadlight = scene.lights.size() == 1 && std::holds_alternative<Headlight>(scene.lights[0].source);
  }
  // The lone headlight, or one beside a point or spot light (a distant light there is refused:
  // Scene.cpp).
  if (scene.model == ShadingModel::VtkPbr && scene.viewer.position)
  {
    placeHeadlightsAtTheCamera(scene, scene.vtkLoneHeadlight || hasPositionalLight(scene));
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
    std::replace_if(
      message.begin(), message.end(), [](char c) { return c < 0x20 || c >= 0x7f; }, '?');
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
