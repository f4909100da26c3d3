#include "GltfScene.h"

#include "IsolatedWork.h"
#include "MeshFiles.h"
#include "VtkErrorCapture.h"

#include "MetallicRoughness.h"
#include "ShadeLabImportedParts.h"

#include "vtkActor.h"
#include "vtkActorCollection.h"
#include "vtkFieldData.h"
#include "vtkGLTFImporter.h"
#include "vtkLight.h"
#include "vtkLightCollection.h"
#include "vtkMatrix4x4.h"
#include "vtkProperty.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"
#include "vtkRendererCollection.h"
#include "vtkStringArray.h"

#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iterator>

namespace shadelab::app
{
namespace
{
using Json = nlohmann::json;

/// The file's JSON: a .gltf is JSON text; a .glb a 12-byte header and then chunks, the first of
/// them the JSON (glTF 2.0, "Binary glTF Layout"). Null where it cannot be read as either.
Json gltfJson(const std::string& fileName)
{
  std::ifstream file(fileName, std::ios::binary);
  std::string bytes((std::istreambuf_iterator<char>(file)), std::istreambuf_iterator<char>());
  auto word = [&](std::size_t at)
  {
    std::uint32_t value = 0;
    for (int b = 3; b >= 0; --b)
    {
      value = (value << 8) | static_cast<unsigned char>(bytes[at + std::size_t(b)]);
    }
    return value;
  };
  if (bytes.size() >= 20 && bytes.compare(0, 4, "glTF") == 0)
  {
    const std::uint32_t length = word(12);
    if (word(16) != 0x4E4F534A || 20 + std::size_t(length) > bytes.size()) // "JSON"
    {
      return nullptr;
    }
    bytes = bytes.substr(20, length);
  }
  return Json::parse(bytes, nullptr, false);
}

/// The lights the file's KHR_lights_punctual extension defines, or none.
Json punctualLights(const Json& gltf)
{
  const Json* lights = nullptr;
  if (gltf.is_object() && gltf.contains("extensions") && gltf["extensions"].contains("KHR_lights_punctual"))
  {
    lights = &gltf["extensions"]["KHR_lights_punctual"]["lights"];
  }
  return lights && lights->is_array() ? *lights : Json::array();
}

/// A number of the light's, or its default.
double numberOr(const Json& node, const char* key, double fallback)
{
  return node.is_object() && node.contains(key) && node[key].is_number() ? node[key].get<double>() : fallback;
}

/// The glTF type of a light as vtkGLTFImporter 9.1 makes it: positional off for a directional
/// light, a cone under 90 degrees for a spot.
std::string gltfType(vtkLight* light)
{
  return !light->GetPositional() ? "directional" : light->GetConeAngle() < 90 ? "spot" : "point";
}

/// The definition in `lights` that the importer's light was made from: the one of its type,
/// colour and intensity (and outer cone, for a spot). The importer keeps neither a point
/// light's range nor a spot's inner cone, which only the definition has.
const Json* definitionOf(vtkLight* light, const Json& lights)
{
  const std::string type = gltfType(light);
  for (const Json& definition : lights)
  {
    const Json color = definition.value("color", Json::array({ 1.0, 1.0, 1.0 }));
    bool same = definition.value("type", "") == type && numberOr(definition, "intensity", 1) == light->GetIntensity();
    for (int c = 0; c < 3 && same && color.is_array() && color.size() == 3; ++c)
    {
      same = color[std::size_t(c)].is_number() && color[std::size_t(c)].get<double>() == light->GetDiffuseColor()[c];
    }
    if (same && type == "spot")
    {
      const double outer = numberOr(definition.value("spot", Json::object()), "outerConeAngle", M_PI / 4);
      same = std::abs(outer * 180 / M_PI - light->GetConeAngle()) < 1e-9;
    }
    if (same)
    {
      return &definition;
    }
  }
  return nullptr;
}

/// The importer's light as a ShadeLab light (KHR_lights_punctual's conventions, docs/guide/
/// scene-files.md "glTF files"): placed at its node's origin, pointing down its node's -z. A
/// point or spot light of I candela is a light of intensity I under the inverse-square law (with
/// glTF's window where it has a range), a directional light of E lux a distant one of
/// intensity E.
Json shadeLabLight(vtkLight* light, const Json* definition, std::size_t index)
{
  vtkMatrix4x4* node = light->GetTransformMatrix();
  const double origin[4] = { 0, 0, 0, 1 }, down[4] = { 0, 0, -1, 0 };
  double position[4] = { 0, 0, 0, 1 }, axis[4] = { 0, 0, -1, 0 };
  if (node)
  {
    node->MultiplyPoint(origin, position);
    node->MultiplyPoint(down, axis);
  }
  const std::string type = gltfType(light);
  const double* color = light->GetDiffuseColor();
  std::string name = definition && definition->contains("name") && (*definition)["name"].is_string()
    ? (*definition)["name"].get<std::string>()
    : "";
  const bool usable = !name.empty() && std::isalpha(static_cast<unsigned char>(name[0])) &&
    name.find_first_not_of("abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789_") == std::string::npos &&
    name.size() <= 64;
  Json out = { { "name", usable ? name : type + std::to_string(index) },
    { "type", type == "directional" ? "distant" : type }, { "color", { color[0], color[1], color[2] } },
    { "intensity", light->GetIntensity() } };
  if (type == "directional")
  {
    out["direction"] = { axis[0], axis[1], axis[2] };
    return out;
  }
  out["position"] = { position[0], position[1], position[2] };
  const double range = definition ? numberOr(*definition, "range", 0) : 0;
  out["attenuation"] = range > 0 ? Json{ { "model", "gltf_range" }, { "range", range } } : Json("inverse_square");
  if (type == "spot")
  {
    const Json spot = definition ? definition->value("spot", Json::object()) : Json::object();
    out["direction"] = { axis[0], axis[1], axis[2] };
    out["cone"] = { { "model", "gltf" }, { "inner_angle", numberOr(spot, "innerConeAngle", 0) * 180 / M_PI },
      { "outer_angle", numberOr(spot, "outerConeAngle", M_PI / 4) * 180 / M_PI } };
  }
  return out;
}

/// The renderer's lights as a ShadeLab scene's JSON text, or "" for none.
std::string lightsScene(vtkRenderer* renderer, const Json& gltf, std::vector<std::string>& notes)
{
  const Json definitions = punctualLights(gltf);
  Json lights = Json::array();
  vtkLightCollection* collection = renderer->GetLights();
  collection->InitTraversal();
  for (int i = 0; i < collection->GetNumberOfItems(); ++i)
  {
    vtkLight* light = collection->GetNextItem();
    const Json* definition = definitionOf(light, definitions);
    if (!definition)
    {
      notes.push_back("light " + std::to_string(i) + " (" + gltfType(light) +
        "): its KHR_lights_punctual definition was not found: its range and inner cone are glTF's defaults");
    }
    lights.push_back(shadeLabLight(light, definition, std::size_t(i)));
  }
  return lights.empty() ? "" : Json{ { "lights", lights } }.dump(2);
}

/// The part's material from its PBR property (glTF's pbrMetallicRoughness), in the lecture's
/// coefficients.
PartMaterial materialOf(vtkProperty* property)
{
  const double* base = property->GetColor();
  const LectureCoefficients c =
    lectureCoefficients(Rgb(base[0], base[1], base[2]), property->GetMetallic(), property->GetRoughness());
  PartMaterial material;
  material.ka = material.kd = c.kd;
  material.ks = c.ks;
  material.shininess = c.shininess;
  return material;
}
}

vtkSmartPointer<vtkPolyData> importGltfScene(const std::string& fileName, std::vector<std::string>& notes)
{
  vtkNew<vtkGLTFImporter> importer;
  importer->SetFileName(fileName.c_str());
  vtkNew<vtkRenderWindow> window; // the importer's renderer's; nothing is drawn
  importer->SetRenderWindow(window);
  vtkNew<VtkErrorCapture> errors;
  errors->watch(importer);
  importer->Update();
  vtkRenderer* renderer = window->GetRenderers()->GetFirstRenderer();
  if (errors->failed() || !renderer)
  {
    throw UserError(fileName + ": VTK's glTF importer could not read it: " +
      printableText(errors->failed() ? errors->message() : "it made no scene"));
  }
  std::vector<ImportedPart> parts;
  vtkActorCollection* actors = renderer->GetActors();
  actors->InitTraversal();
  for (int i = 0; i < actors->GetNumberOfItems(); ++i)
  {
    vtkActor* actor = actors->GetNextActor();
    vtkProperty* property = actor->GetProperty();
    parts.push_back({ actor, "part" + std::to_string(i), materialOf(property), property->GetTexture("albedoTex"), "" });
  }
  std::vector<std::string> skipped;
  vtkSmartPointer<vtkPolyData> mesh = meshOfParts(parts, skipped);
  notes.insert(notes.end(), skipped.begin(), skipped.end());
  if (mesh->GetNumberOfCells() == 0)
  {
    throw UserError(fileName + ": the glTF file has no geometry that VTK's importer reads (no mesh primitives)");
  }
  const std::string lights = lightsScene(renderer, gltfJson(fileName), notes);
  if (!lights.empty())
  {
    auto text = vtkSmartPointer<vtkStringArray>::New();
    text->SetName(fileLightsArrayName);
    text->InsertNextValue(lights);
    mesh->GetFieldData()->AddArray(text);
  }
  return mesh;
}

bool isGltfFile(const std::string& fileName)
{
  std::string extension = std::filesystem::path(fileName).extension().string();
  for (char& c : extension)
  {
    c = char(std::tolower(static_cast<unsigned char>(c)));
  }
  return extension == ".gltf" || extension == ".glb";
}

void importGltfAlone(const std::string& fileName)
{
  vtkNew<vtkGLTFImporter> importer;
  importer->SetFileName(fileName.c_str());
  vtkNew<vtkRenderWindow> window;
  importer->SetRenderWindow(window);
  importer->Update();
}

std::uintmax_t gltfBytes(const std::string& fileName)
{
  std::error_code error;
  std::uintmax_t bytes = std::filesystem::file_size(fileName, error);
  const Json gltf = gltfJson(fileName);
  const std::filesystem::path folder = std::filesystem::path(fileName).parent_path();
  for (const char* kind : { "buffers", "images" })
  {
    if (!gltf.is_object() || !gltf.contains(kind) || !gltf[kind].is_array())
    {
      continue;
    }
    for (const Json& resource : gltf[kind])
    {
      const std::string uri = resource.is_object() ? resource.value("uri", "") : "";
      if (!uri.empty() && uri.rfind("data:", 0) != 0)
      {
        const std::uintmax_t size = std::filesystem::file_size(folder / uri, error);
        bytes += error ? 0 : size;
      }
    }
  }
  return bytes;
}

std::string fileLightsOf(vtkPolyData* mesh)
{
  auto* text = vtkStringArray::SafeDownCast(mesh->GetFieldData()->GetAbstractArray(fileLightsArrayName));
  return text && text->GetNumberOfValues() == 1 ? text->GetValue(0) : "";
}
}
