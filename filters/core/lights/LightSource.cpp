#include "LightSource.h"

#include "JsonNode.h"

#include <algorithm>
#include <type_traits>

namespace shadelab
{
std::string lightTypeName(const LightSource& source)
{
  return std::visit([](const auto& light) { return light.typeName(); }, source);
}

Rgb emittedColor(const LightSource& source)
{
  return std::visit([](const auto& light) { return light.emitted(); }, source);
}

LightRole roleOf(const LightSource& source)
{
  return std::visit([](const auto& light) { return std::decay_t<decltype(light)>::role; }, source);
}

const Sampling* samplingOf(const LightSource& source)
{
  return std::visit(
    [](const auto& light) -> const Sampling*
    {
      if constexpr (std::decay_t<decltype(light)>::role == LightRole::Distributed)
      {
        return &light.sampling;
      }
      return nullptr;
    },
    source);
}

const glm::dvec3* positionOf(const LightSource& source)
{
  return std::visit(
    [](const auto& light) -> const glm::dvec3*
    {
      if constexpr (std::decay_t<decltype(light)>::positional)
      {
        return &light.position;
      }
      return nullptr;
    },
    source);
}

const Attenuation* attenuationOf(const LightSource& source)
{
  return std::visit(
    [](const auto& light) -> const Attenuation*
    {
      if constexpr (std::decay_t<decltype(light)>::positional)
      {
        return &light.attenuation;
      }
      return nullptr;
    },
    source);
}

bool lightHasTerm(const LightSource& source, LightTerm term)
{
  return std::visit([term](const auto& light) { return light.hasTerm(term); }, source);
}

bool lightHasTerm(const NamedLight& light, LightTerm term)
{
  // A distributed light's shadows are sampled (ShadowedLightEstimator): its visibility has a
  // standard error, and so has its irradiance, whatever the estimator; a map's S is sampled
  // too, even by the brute-force sum.
  const bool softShadows = light.shadows && isDistributed(light.source);
  switch (term)
  {
    case LightTerm::Visibility: return light.shadows;
    case LightTerm::VisibilityStdError: return softShadows;
    case LightTerm::ShortOfTarget: return samplingOf(light.source) && samplingOf(light.source)->fromTolerance;
    case LightTerm::IrradianceStdError: return softShadows || lightHasTerm(light.source, term);
    case LightTerm::SpecularStdError:
      return (softShadows && std::holds_alternative<EnvironmentLight>(light.source)) ||
        lightHasTerm(light.source, term);
    case LightTerm::ShTransferStdError: return softShadows && lightHasTerm(light.source, LightTerm::ShTransfer);
    default: return lightHasTerm(light.source, term);
  }
}

double peakContribution(const LightSource& source, const Material& m)
{
  return std::visit([&m](const auto& light) { return light.peakContribution(m); }, source);
}

void checkLightSource(const LightSource& source, LightChecks& checks)
{
  std::visit([&checks](const auto& light) { light.check(checks); }, source);
}

void placeOnMesh(LightSource& source, const MeshPlacement& placement)
{
  std::visit([&placement](auto& light) { light.placeOn(placement); }, source);
}

LightEvaluation prepareEvaluation(const LightSource& source, const EvaluationContext& context)
{
  return std::visit([&context](const auto& light) { return light.prepare(context); }, source);
}

namespace
{
/// One "type" name of a registered light type, and how to read it.
struct FileTypeEntry
{
  const SceneFileType* type;
  bool castsShadows;
  LightSource (*read)(const JsonNode&, const SceneFileType&, const std::string&);
};

template<typename Light>
LightSource readAs(const JsonNode& node, const SceneFileType& type, const std::string& sceneFile)
{
  return Light::read(node, type, sceneFile);
}

template<std::size_t... Index>
std::vector<FileTypeEntry> collectFileTypes(std::index_sequence<Index...>)
{
  std::vector<FileTypeEntry> entries;
  auto add = [&entries](const std::vector<SceneFileType>& types, bool castsShadows, auto read)
  {
    for (const SceneFileType& type : types)
    {
      entries.push_back({ &type, castsShadows, read });
    }
  };
  (add(std::variant_alternative_t<Index, LightSource>::sceneFileTypes(),
     std::variant_alternative_t<Index, LightSource>::castsShadows,
     &readAs<std::variant_alternative_t<Index, LightSource>>),
    ...);
  return entries;
}

/// Every registered "type" name, in registration order.
const std::vector<FileTypeEntry>& fileTypes()
{
  static const std::vector<FileTypeEntry> entries =
    collectFileTypes(std::make_index_sequence<std::variant_size_v<LightSource>>{});
  return entries;
}

const std::vector<const char*> commonFields = { "name", "type", "color", "spectrum", "intensity", "shadows" };

std::vector<const char*> fieldsOf(const SceneFileType& type)
{
  std::vector<const char*> fields = commonFields;
  fields.insert(fields.end(), type.fields.begin(), type.fields.end());
  return fields;
}

/// The fields any light may have: the common ones, then each type's in registration order.
const std::vector<const char*>& anyLightFields()
{
  static const std::vector<const char*> fields = []
  {
    std::vector<const char*> all = commonFields;
    for (const FileTypeEntry& entry : fileTypes())
    {
      for (const char* field : entry.type->fields)
      {
        if (std::none_of(all.begin(), all.end(), [&](const char* known) { return std::string(known) == field; }))
        {
          all.push_back(field);
        }
      }
    }
    return all;
  }();
  return fields;
}

/// The registered type the node names; fails with the list of names otherwise.
const FileTypeEntry& fileTypeNamed(const JsonNode& node)
{
  static const std::vector<std::pair<const char*, const FileTypeEntry*>> byName = []
  {
    std::vector<std::pair<const char*, const FileTypeEntry*>> names;
    for (const FileTypeEntry& entry : fileTypes())
    {
      names.emplace_back(entry.type->name, &entry);
    }
    return names;
  }();
  return *node.choiceAmong(byName);
}
}

bool castsShadows(const LightSource& source)
{
  return std::visit([](const auto& light) { return std::decay_t<decltype(light)>::castsShadows; }, source);
}

std::string shadowCastingTypeNames()
{
  std::vector<const char*> names;
  for (const FileTypeEntry& entry : fileTypes())
  {
    if (entry.castsShadows)
    {
      names.push_back(entry.type->name);
    }
  }
  std::string phrase;
  for (std::size_t i = 0; i < names.size(); ++i)
  {
    phrase += (i == 0 ? "" : i + 1 == names.size() ? " and " : ", ") + std::string(names[i]);
  }
  return phrase;
}

LightSource readLightSource(const JsonNode& node, const std::string& sceneFile)
{
  // The fields of the light's type, so that a misspelt one is matched against those alone;
  // without a type, every field any light may have (the type is then reported missing).
  node.expectObject(
    node.isObject() && node.has("type") ? fieldsOf(*fileTypeNamed(node.at("type")).type) : anyLightFields());
  const FileTypeEntry& entry = fileTypeNamed(node.at("type"));
  return entry.read(node, *entry.type, sceneFile);
}
}
