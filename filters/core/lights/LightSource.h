#pragma once
// The light types ShadeLab knows, registered in one line, and what the rest of ShadeLab asks
// of a light, whatever its type. Each type's parameters, scene-file fields, checks and
// evaluation are in its own file pair (LightType.h lists what each provides).
#include "AmbientLight.h"
#include "AreaLight.h"
#include "DistantLight.h"
#include "EnvironmentLight.h"
#include "Headlight.h"
#include "PointLight.h"
#include "Spectrum.h"
#include "SpotLight.h"

#include <optional>
#include <string>
#include <variant>

namespace shadelab
{
/// The registration: every light type, in the order a scene file's "type" names are listed
/// in messages.
using LightSource =
  std::variant<DistantLight, Headlight, PointLight, SpotLight, AmbientLight, AreaLight, EnvironmentLight>;

struct NamedLight
{
  std::string name;
  LightSource source;
  /// Whether the mesh casts this light's shadows (local lights only; visibility/).
  bool shadows = false;
  /// The light's emission where the scene gives it as a spectrum (its colour is then the
  /// spectrum's RGB, its luminance scaled to 1: SpectrumFields.h).
  std::optional<SampledSpectrum> spectrum{};
};

/// The light's "type" name, for messages and default light names: the shape it was read as
/// ("polygon" for a "rectangle").
std::string lightTypeName(const LightSource& source);

/// Colour x intensity (x |direction| for a distant light with intensityFromLength): the RGB
/// the light delivers before attenuation, cone and material.
Rgb emittedColor(const LightSource& source);

LightRole roleOf(const LightSource& source);

inline bool isAmbient(const LightSource& source)
{
  return roleOf(source) == LightRole::Ambient;
}

/// Area lights and environment maps: lights integrated over a solid angle per vertex.
inline bool isDistributed(const LightSource& source)
{
  return roleOf(source) == LightRole::Distributed;
}

/// How a light integrated over a solid angle (area, environment) places its samples, or nullptr.
const Sampling* samplingOf(const LightSource& source);

/// The position of a light that has one (point, spot), or nullptr.
const glm::dvec3* positionOf(const LightSource& source);

/// The distance attenuation of a light that has a position, or nullptr.
const Attenuation* attenuationOf(const LightSource& source);

/// True for lights that sit at a position, so that distance means something.
inline bool isPositional(const LightSource& source)
{
  return positionOf(source) != nullptr;
}

/// Whether the light has this per-light term (LightTerms.h).
bool lightHasTerm(const LightSource& source, LightTerm term);
/// Whether the light has the term's array: its type's terms, and its visibility when it casts
/// shadows.
bool lightHasTerm(const NamedLight& light, LightTerm term);

/// The largest RGB value the light can add at a vertex of this material.
double peakContribution(const LightSource& source, const Material& m);

/// Every problem of the light's values.
void checkLightSource(const LightSource& source, LightChecks& checks);

/// The light moved from the mesh's frame to the world.
void placeOnMesh(LightSource& source, const MeshPlacement& placement);

/// The light's form for the kernel.
LightEvaluation prepareEvaluation(const LightSource& source, const EvaluationContext& context);

/// Whether "shadows" is allowed on the light (its type's castsShadows).
bool castsShadows(const LightSource& source);

/// The scene-file "type" names of the registered types that cast shadows, as a phrase for
/// messages: "distant, headlight, point, spot, polygon, rectangle, disk, sphere and environment".
std::string shadowCastingTypeNames();

/// A light from its JSON object in a scene file: the fields any light may have, its "type",
/// then only that type's fields. Throws JsonError (JsonNode.h).
LightSource readLightSource(const JsonNode& node, const std::string& sceneFile);
}
