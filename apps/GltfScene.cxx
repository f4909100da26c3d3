#include "GltfScene.h"

#include "IsolatedWork.h"
#include "MeshFiles.h"
#include "VtkErrorCapture.h"

#include "JsonNode.h"
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

#include <algorithm>
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

/// The most JSON text read from a glTF file: the JSON of a glTF scene, without its buffers,
/// is rarely more than a few megabytes.
constexpr std::uint32_t largestJson = 256u << 20;

/// The file's JSON: a .gltf is JSON text; a .glb a 12-byte header and then chunks, the first of
/// them the JSON (glTF 2.0, "Binary glTF Layout"), of which only the JSON is read. Null where
/// it is not a regular file, or cannot be read as either.
Json gltfJson(const std::string& fileName)
{
  std::error_code error;
  if (!std::filesystem::is_regular_file(fileName, error))
  {
    return nullptr;
  }
  std::ifstream file(fileName, std::ios::binary);
  char header[20] = {};
  file.read(header, sizeof header);
  auto word = [&](std::size_t at)
  {
    std::uint32_t value = 0;
    for (int b = 3; b >= 0; --b)
    {
      value = (value << 8) | static_cast<unsigned char>(header[at + std::size_t(b)]);
    }
    return value;
  };
  const bool binary = file.gcount() == sizeof header && std::string(header, 4) == "glTF";
  std::uint32_t length =
    std::uint32_t(std::min<std::uintmax_t>(std::filesystem::file_size(fileName, error), largestJson));
  if (binary)
  {
    length = word(12);
    if (word(16) != 0x4E4F534A || length > largestJson) // the chunk's type, "JSON"
    {
      return nullptr;
    }
  }
  else
  {
    file.clear();
    file.seekg(0);
  }
  std::string text(length, '\0');
  file.read(text.data(), length);
  text.resize(std::size_t(file.gcount()));
  if (!binary && file.peek() != std::char_traits<char>::eof())
  {
    return nullptr; // longer than largestJson
  }
  return Json::parse(text, nullptr, false);
}

/// The member `key` of a JSON object, or null where the node is not an object or has none.
const Json* member(const Json* node, const char* key)
{
  if (!node || !node->is_object())
  {
    return nullptr;
  }
  const auto found = node->find(key);
  return found == node->end() ? nullptr : &*found;
}

/// An index the file gives (a node's, a light's), or -1 where it is not one.
long long indexAt(const Json* node)
{
  return node && node->is_number_unsigned() ? static_cast<long long>(node->get<std::uint64_t>()) : -1;
}

/// The element `index` of a JSON array, or null.
const Json* element(const Json* array, long long index)
{
  return array && array->is_array() && index >= 0 && std::size_t(index) < array->size() ? &(*array)[std::size_t(index)]
                                                                                        : nullptr;
}

/// The nodes vtkGLTFImporter 9.1 visits, in its order, for its actors and its lights alike. It
/// puts the scene's nodes on a stack and pops them one at a time, making the node's actors (one
/// per mesh primitive, in order) and light and pushing its children, so the last node comes
/// first (measured: nodes [A, B] with B's children [C, D] give D, C, A; the lamps' ball before
/// their floor). A file whose nodes form a cycle is cut after as many pops as it has nodes.
std::vector<const Json*> nodesInImporterOrder(const Json& gltf)
{
  const Json* nodes = member(&gltf, "nodes");
  const long long sceneIndex = member(&gltf, "scene") ? indexAt(member(&gltf, "scene")) : 0;
  const Json* roots = member(element(member(&gltf, "scenes"), sceneIndex), "nodes");
  std::vector<long long> stack;
  for (std::size_t r = 0; roots && roots->is_array() && r < roots->size(); ++r)
  {
    stack.push_back(indexAt(&(*roots)[r]));
  }
  std::vector<const Json*> visited;
  for (std::size_t pops = 0; !stack.empty() && nodes && nodes->is_array() && pops < nodes->size(); ++pops)
  {
    const Json* node = element(nodes, stack.back());
    stack.pop_back();
    visited.push_back(node);
    const Json* children = member(node, "children");
    for (std::size_t c = 0; children && children->is_array() && c < children->size(); ++c)
    {
      stack.push_back(indexAt(&(*children)[c]));
    }
  }
  return visited;
}

/// The KHR_lights_punctual definition of each light vtkGLTFImporter 9.1 makes, in its order
/// (null where a node's light index names none).
std::vector<const Json*> lightsInImporterOrder(const Json& gltf)
{
  const Json* definitions = member(member(member(&gltf, "extensions"), "KHR_lights_punctual"), "lights");
  std::vector<const Json*> lights;
  for (const Json* node : nodesInImporterOrder(gltf))
  {
    if (const Json* light = member(member(member(node, "extensions"), "KHR_lights_punctual"), "light"))
    {
      lights.push_back(element(definitions, indexAt(light)));
    }
  }
  return lights;
}

/// A number of the definition's, or its default.
double numberOr(const Json* node, const char* key, double fallback)
{
  const Json* value = member(node, key);
  return value && value->is_number() ? value->get<double>() : fallback;
}

/// A text of the definition's, or "".
std::string textOr(const Json* node, const char* key)
{
  const Json* value = member(node, key);
  return value && value->is_string() ? value->get<std::string>() : "";
}

/// A name for each part vtkGLTFImporter 9.1 makes (one per mesh primitive, in its order): the
/// primitive's material's name, as an OBJ's parts are named by their materials, or else its
/// mesh's, or else "" (the caller then numbers it).
std::vector<std::string> partNamesInImporterOrder(const Json& gltf)
{
  const Json* meshes = member(&gltf, "meshes");
  const Json* materials = member(&gltf, "materials");
  std::vector<std::string> names;
  for (const Json* node : nodesInImporterOrder(gltf))
  {
    const Json* mesh = member(node, "mesh") ? element(meshes, indexAt(member(node, "mesh"))) : nullptr;
    const Json* primitives = member(mesh, "primitives");
    for (std::size_t p = 0; primitives && primitives->is_array() && p < primitives->size(); ++p)
    {
      const std::string material = textOr(element(materials, indexAt(member(&(*primitives)[p], "material"))), "name");
      names.push_back(!material.empty() ? material : textOr(mesh, "name"));
    }
  }
  return names;
}

/// `name`, or where it is taken, name_2, name_3, ...
std::string uniqueName(const std::string& name, std::vector<std::string>& taken)
{
  std::string unique = name;
  for (int copy = 2; std::find(taken.begin(), taken.end(), unique) != taken.end(); ++copy)
  {
    unique = name + "_" + std::to_string(copy);
  }
  taken.push_back(unique);
  return unique;
}

/// The light's glTF type: its definition's, or where it has none, as vtkGLTFImporter 9.1 makes
/// the light (positional off for a directional light, a cone under 90 degrees for a spot).
std::string gltfType(vtkLight* light, const Json* definition)
{
  const std::string type = textOr(definition, "type");
  if (type == "point" || type == "spot" || type == "directional")
  {
    return type;
  }
  return !light->GetPositional() ? "directional" : light->GetConeAngle() < 90 ? "spot" : "point";
}

/// A light's name from its definition where it is one ShadeLab takes (letters, digits and _,
/// starting with a letter), else its type and index; made unique among `taken` with _2, _3, ...
std::string lightName(
  const Json* definition, const std::string& type, std::size_t index, std::vector<std::string>& taken)
{
  std::string name = textOr(definition, "name");
  const bool usable = !name.empty() && name.size() <= 48 && std::isalpha(static_cast<unsigned char>(name[0])) &&
    name.find_first_not_of("abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789_") == std::string::npos;
  return uniqueName(usable ? name : type + std::to_string(index), taken);
}

/// The importer's light as a ShadeLab light (KHR_lights_punctual's conventions, docs/guide/
/// scene-files.md "glTF files"): placed at its node's origin, pointing down its node's -z. A
/// point or spot light of I candela is a light of intensity I under the inverse-square law (with
/// glTF's window where it has a range), a directional light of E lux a distant one of
/// intensity E. The importer keeps neither a point light's range nor a spot's inner cone,
/// which only the definition has.
Json shadeLabLight(vtkLight* light, const Json* definition, const std::string& name)
{
  vtkMatrix4x4* node = light->GetTransformMatrix();
  const double origin[4] = { 0, 0, 0, 1 }, down[4] = { 0, 0, -1, 0 };
  double position[4] = { 0, 0, 0, 1 }, axis[4] = { 0, 0, -1, 0 };
  if (node)
  {
    node->MultiplyPoint(origin, position);
    node->MultiplyPoint(down, axis);
  }
  const std::string type = gltfType(light, definition);
  const double* color = light->GetDiffuseColor();
  Json out = { { "name", name }, { "type", type == "directional" ? "distant" : type },
    { "color", { color[0], color[1], color[2] } }, { "intensity", light->GetIntensity() } };
  if (type == "directional")
  {
    out["direction"] = { axis[0], axis[1], axis[2] };
    return out;
  }
  out["position"] = { position[0], position[1], position[2] };
  const double range = numberOr(definition, "range", 0);
  out["attenuation"] = range > 0 ? Json{ { "model", "gltf_range" }, { "range", range } } : Json("inverse_square");
  if (type == "spot")
  {
    const Json* spot = member(definition, "spot");
    out["direction"] = { axis[0], axis[1], axis[2] };
    out["cone"] = { { "model", "gltf" }, { "inner_angle", numberOr(spot, "innerConeAngle", 0) * 180 / M_PI },
      { "outer_angle", numberOr(spot, "outerConeAngle", M_PI / 4) * 180 / M_PI } };
  }
  return out;
}

/// The renderer's lights as a ShadeLab scene's JSON text, or "" for none.
std::string lightsScene(vtkRenderer* renderer, const Json& gltf, std::vector<std::string>& notes)
{
  const std::vector<const Json*> definitions = lightsInImporterOrder(gltf);
  vtkLightCollection* collection = renderer->GetLights();
  if (definitions.size() != std::size_t(collection->GetNumberOfItems()))
  {
    notes.push_back("VTK's importer made " + std::to_string(collection->GetNumberOfItems()) +
      " lights where the file's nodes name " + std::to_string(definitions.size()) +
      ": their ranges and inner cones are glTF's defaults");
  }
  Json lights = Json::array();
  std::vector<std::string> names;
  collection->InitTraversal();
  for (int i = 0; i < collection->GetNumberOfItems(); ++i)
  {
    vtkLight* light = collection->GetNextItem();
    const Json* definition =
      definitions.size() == std::size_t(collection->GetNumberOfItems()) ? definitions[i] : nullptr;
    lights.push_back(shadeLabLight(light, definition, lightName(definition, gltfType(light, definition), i, names)));
  }
  return lights.empty() ? "" : Json{ { "lights", lights } }.dump(2);
}

/// The extensions the file uses that ShadeLab does not read, those it requires first: each may
/// change how the file looks (a texture's transform, a clear coat, an emission), so each is said.
void noteUnreadExtensions(const Json& gltf, std::vector<std::string>& notes)
{
  const Json* required = member(&gltf, "extensionsRequired");
  const Json* used = member(&gltf, "extensionsUsed");
  for (const Json* list : { required, used })
  {
    for (std::size_t e = 0; list && list->is_array() && e < list->size(); ++e)
    {
      const std::string name = (*list)[e].is_string() ? (*list)[e].get<std::string>() : "";
      const bool alsoRequired = list == used && required && required->is_array() &&
        std::find(required->begin(), required->end(), (*list)[e]) != required->end();
      if (!name.empty() && name != "KHR_lights_punctual" && !alsoRequired)
      {
        notes.push_back(std::string(list == required ? "requires" : "uses") + " the extension " + name +
          ", which ShadeLab does not read: what it changes is not shaded");
      }
    }
  }
}

/// A material's doubleSided that is not a boolean ("yes", 1): VTK's loader takes it for false,
/// glTF's default, and culls the part's back faces. Said, since the file meant something else.
void noteDoubleSidedNotBoolean(const Json& gltf, std::vector<std::string>& notes)
{
  const Json* materials = member(&gltf, "materials");
  for (std::size_t m = 0; materials && materials->is_array() && m < materials->size(); ++m)
  {
    const Json* flag = member(&(*materials)[m], "doubleSided");
    if (flag && !flag->is_boolean())
    {
      std::string name = textOr(&(*materials)[m], "name");
      name = name.size() > 60 ? name.substr(0, 57) + "..." : name;
      notes.push_back("material " + (name.empty() ? std::to_string(m) : "'" + name + "'") + " gives doubleSided as " +
        printableText(shortJsonText(*flag)) +
        ", not true or false: VTK's importer reads it as false, so its parts are one-sided");
    }
  }
}

/// What the vtk_pbr model cannot take from a material, said where the file is read: a roughness
/// of 0, which VTK's GGX distribution divides by (0/0 in the mirror direction), and the textures
/// other than the base colour's and the metallic-roughness one, which ShadeLab does not read.
void noteMaterialsShadedOtherwise(const Json& gltf, std::vector<std::string>& notes)
{
  const Json* materials = member(&gltf, "materials");
  for (std::size_t m = 0; materials && materials->is_array() && m < materials->size(); ++m)
  {
    const Json* material = &(*materials)[m];
    std::string name = textOr(material, "name");
    name = name.size() > 60 ? name.substr(0, 57) + "..." : name;
    const std::string named = "material " + (name.empty() ? std::to_string(m) : "'" + name + "'");
    const Json* pbr = member(material, "pbrMetallicRoughness");
    // VTK's property clamps a negative roughness to 0.
    if (numberOr(pbr, "roughnessFactor", 1) <= 0)
    {
      notes.push_back(named +
        " has roughnessFactor 0, which the vtk_pbr model would refuse (VTK's GGX distribution is 0/0 in the mirror "
        "direction): a vtk_pbr scene needs a material of its own for this file");
    }
    // VTK 9.1's importer applies it beside a base colour texture only, and ShadeLab shades what
    // it applies.
    if (member(pbr, "metallicRoughnessTexture") && !member(pbr, "baseColorTexture"))
    {
      notes.push_back(named +
        " has a metallicRoughnessTexture but no baseColorTexture, without which VTK's importer does not apply it: "
        "shaded with its metallic and roughness factors alone");
    }
    std::vector<std::string> unread;
    for (const char* key : { "normalTexture", "occlusionTexture", "emissiveTexture" })
    {
      if (member(material, key))
      {
        unread.push_back(key);
      }
    }
    std::string list;
    for (std::size_t t = 0; t < unread.size(); ++t)
    {
      list += (t == 0 ? "" : t + 1 == unread.size() ? " and " : ", ") + unread[t];
    }
    if (!unread.empty())
    {
      notes.push_back(named + " has " + list + ", which ShadeLab does not read: shaded without " +
        (unread.size() == 1 ? "it" : "them"));
    }
  }
}

/// The part's material from its PBR property (glTF's pbrMetallicRoughness): as VTK's PBR
/// shader reads it, and in the lecture's coefficients; and its sides: vtkGLTFImporter culls the
/// back faces of a material that is not doubleSided. A primitive without a material keeps
/// vtkProperty's defaults (no culling, nor the PBR interpolation that the importer gives every
/// material it applies), and glTF's default material is one-sided.
PartMaterial materialOf(vtkProperty* property)
{
  const double* base = property->GetColor();
  PartMaterial material;
  material.microfacet = MicrofacetMaterial{};
  material.microfacet->baseColor = Rgb(base[0], base[1], base[2]);
  material.microfacet->metallic = property->GetMetallic();
  material.microfacet->roughness = property->GetRoughness();
  const LectureCoefficients c =
    lectureCoefficients(material.microfacet->baseColor, material.microfacet->metallic, material.microfacet->roughness);
  material.ka = material.kd = c.kd;
  material.ks = c.ks;
  material.shininess = c.shininess;
  material.twoSided = property->GetInterpolation() == VTK_PBR && !property->GetBackfaceCulling();
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
  const Json gltf = gltfJson(fileName);
  std::vector<ImportedPart> parts;
  vtkActorCollection* actors = renderer->GetActors();
  // Named from the file where its primitives are the importer's actors one for one.
  const std::vector<std::string> fileNames = partNamesInImporterOrder(gltf);
  const bool named = fileNames.size() == std::size_t(actors->GetNumberOfItems());
  std::vector<std::string> taken;
  actors->InitTraversal();
  for (int i = 0; i < actors->GetNumberOfItems(); ++i)
  {
    vtkActor* actor = actors->GetNextActor();
    vtkProperty* property = actor->GetProperty();
    const std::string name = named && !fileNames[i].empty() ? fileNames[i] : "part" + std::to_string(i);
    parts.push_back({ actor, uniqueName(name, taken), materialOf(property), property->GetTexture("albedoTex"), "",
      property->GetTexture("materialTex") });
  }
  std::vector<std::string> skipped;
  vtkSmartPointer<vtkPolyData> mesh = meshOfParts(parts, skipped);
  notes.insert(notes.end(), skipped.begin(), skipped.end());
  if (mesh->GetNumberOfCells() == 0)
  {
    throw UserError(fileName + ": the glTF file has no geometry that VTK's importer reads (no mesh primitives)");
  }
  noteUnreadExtensions(gltf, notes);
  noteDoubleSidedNotBoolean(gltf, notes);
  noteMaterialsShadedOtherwise(gltf, notes);
  const std::string lights = lightsScene(renderer, gltf, notes);
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
  const std::string extension = lowerExtension(fileName);
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
    const Json* resources = member(&gltf, kind);
    for (std::size_t r = 0; resources && resources->is_array() && r < resources->size(); ++r)
    {
      const std::string uri = textOr(&(*resources)[r], "uri");
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
