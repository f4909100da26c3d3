#include "Scene.h"

#include "Microfacet.h"
#include "NumberText.h"
#include "SpectralColors.h"

#include <algorithm>
#include <cmath>
#include <set>

namespace shadelab
{
SpecularModel evaluatedSpecularModel(const Scene& scene)
{
  switch (scene.model)
  {
    case ShadingModel::Lecture: return scene.material.specular;
    case ShadingModel::VtkOpenGL2: return scene.vtkLoneHeadlight ? SpecularModel::BlinnPhong : SpecularModel::Phong;
    case ShadingModel::VtkPbr: return SpecularModel::None; // its microfacet term instead (Microfacet.h)
  }
  return SpecularModel::None;
}

bool hasSpecularTerm(const Scene& scene)
{
  if (scene.model == ShadingModel::VtkPbr)
  {
    return true;
  }
  return evaluatedSpecularModel(scene) != SpecularModel::None && scene.material.ks != Rgb(0.0);
}

glm::dvec3 Viewer::directionFrom(const glm::dvec3& p) const
{
  if (!position)
  {
    return -unitVector(viewDirection);
  }
  const double distance = vectorLength(*position - p);
  return distance > 0 ? (*position - p) / distance : glm::dvec3(0.0);
}

std::optional<glm::dvec3> Viewer::lineOfSight() const
{
  if (!position)
  {
    return unitVector(viewDirection);
  }
  if (!focalPoint || *focalPoint == *position)
  {
    return std::nullopt;
  }
  return unitVector(*focalPoint - *position);
}

std::string meshCoordinateProblem(double reach, Precision precision)
{
  if (reach <= coordinateLimit(precision))
  {
    return "";
  }
  return "the mesh's coordinates reach " + scientific(reach) + ", beyond +-" + scientific(coordinateLimit(precision)) +
    " where squared distances overflow " + precisionName(precision) +
    (precision == Precision::Float32 ? ": use double precision (shadelab shade --precision float64)" : "");
}

std::string roughnessPrecisionProblem(double roughness, Precision precision)
{
  // A percent of D at the highlight's peak: float32 cannot resolve 1 - n.h below that roughness.
  const double float32Error = float32DistributionError(roughness);
  if (precision != Precision::Float32 || float32Error <= 0.01)
  {
    return "";
  }
  return "at roughness " + withDigits(roughness, 3) + " float32 arithmetic errs by " +
    (float32Error >= 1 ? std::string("100% or more") : "up to " + withDigits(100 * float32Error, 2) + "%") +
    " at the highlight's peak (D needs 1 - n.h finer than float32 holds): use float64, or a roughness of at least "
    "0.07";
}

namespace
{
Material peakMaterial(const Scene& scene, Precision precision)
{
  if (scene.model != ShadingModel::VtkPbr)
  {
    return scene.material;
  }
  // The lecture's kd and ks that bound the microfacet model's diffuse and specular factors:
  // (1 - m)(1 - F) base / pi <= base / pi, and D V F (n.s) <= microfacetSpecularBound.
  const MicrofacetMaterial& microfacet = scene.material.microfacet;
  Material bound;
  bound.kd = microfacet.baseColor * vtkReciprocalPi;
  // A roughness from an array is bounded by the smallest one it may give (roughnessPrecisionProblem,
  // checked as the array is read).
  bound.ks = Rgb(microfacetSpecularBound(
    scene.material.arrays[MaterialCoefficient::Roughness] ? smallestArrayRoughness(precision) : microfacet.roughness));
  return bound;
}

/// A material read from the mesh's arrays (MaterialArrays.h): scales in their domain, and
/// what the array cannot give in this scene.
void checkMaterialArrays(const Scene& scene, ProblemList& list)
{
  const Material& m = scene.material;
  for (int c = 0; c < MaterialCoefficientCount; ++c)
  {
    const auto coefficient = MaterialCoefficient(c);
    if (const auto& source = m.arrays[coefficient])
    {
      list.check(std::isfinite(source->scale) && source->scale >= 0,
        std::string("/material/") + materialKey(coefficient, scene.model) + "/scale", "must be a number >= 0");
    }
  }
  // VTK's mapper colours the ambient term with the scalars' colour as well as the diffuse one.
  list.check(scene.model != ShadingModel::VtkOpenGL2 || !m.arrays[MaterialCoefficient::Diffuse] ||
      m.arrays[MaterialCoefficient::Ambient] || m.ka == Rgb(0.0),
    "/material/ka",
    "with kd from an array, VTK's mapper takes the ambient colour from the array too: give ka as {\"array\": \"" +
      (m.arrays[MaterialCoefficient::Diffuse] ? m.arrays[MaterialCoefficient::Diffuse]->array : std::string()) +
      "\", \"scale\": <the property's Ambient>}");
  list.check(scene.model == ShadingModel::VtkPbr ||
      (!m.arrays[MaterialCoefficient::Metallic] && !m.arrays[MaterialCoefficient::Roughness]),
    "/material", "only the vtk_pbr model has a metallic factor and a roughness");
  if (m.arrays[MaterialCoefficient::Shininess] && hasSpecularTerm(scene))
  {
    for (std::size_t i = 0; i < scene.lights.size(); ++i)
    {
      list.check(!isDistributed(scene.lights[i].source), "/material/shininess",
        "light '" + scene.lights[i].name + "' (" + lightTypeName(scene.lights[i].source) +
          ") samples one specular lobe for every vertex, so the shininess cannot vary per vertex: give a number, "
          "or make ks 0");
    }
  }
}

/// Letters, digits and _, starting with a letter: a name that can stand in an array's name.
/// (A loop, not std::regex_match, whose recursion overflows the stack on long names.)
bool isLightName(const std::string& name)
{
  auto isAsciiLetter = [](char c) { return (c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z'); };
  return !name.empty() && isAsciiLetter(name[0]) &&
    std::all_of(
      name.begin(), name.end(), [&](char c) { return isAsciiLetter(c) || (c >= '0' && c <= '9') || c == '_'; });
}

/// The vtk_pbr model's material, and what VTK's PBR shader (without image-based lighting) has
/// no counterpart for.
void checkMicrofacetModel(const Scene& scene, Precision precision, ProblemList& list)
{
  if (scene.model != ShadingModel::VtkPbr)
  {
    return;
  }
  const MicrofacetMaterial& m = scene.material.microfacet;
  auto isReflectance = [](const Rgb& c) { return isNonNegative(c) && largestComponent(c) <= 1; };
  const MaterialArrays& arrays = scene.material.arrays;
  // A coefficient from an array has its scale (the property's factor, which VTK clamps to 1)
  // checked here, and its values as they are read.
  if (arrays[MaterialCoefficient::Diffuse])
  {
    list.check(arrays[MaterialCoefficient::Diffuse]->scale <= 1, "/material/base_color/scale",
      "must be a number from 0 to 1 (the property's Diffuse)");
  }
  else
  {
    list.check(isReflectance(m.baseColor), "/material/base_color", "components must be numbers from 0 to 1");
  }
  list.check(m.metallic >= 0 && m.metallic <= 1,
    arrays[MaterialCoefficient::Metallic] ? "/material/metallic/scale" : "/material/metallic",
    "must be a number from 0 to 1");
  list.check(m.roughness > 0 && m.roughness <= 1,
    arrays[MaterialCoefficient::Roughness] ? "/material/roughness/scale" : "/material/roughness",
    "must be a number above 0 and at most 1 (at 0, VTK's GGX distribution is 0/0 in the mirror direction)");
  list.check(!arrays[MaterialCoefficient::Roughness] || !arrays[MaterialCoefficient::Roughness]->clamp,
    "/material/roughness/clamp",
    "a roughness cannot be clamped: (0, 1] has no value nearest to 0 or below; correct the array's values");
  list.check(std::isfinite(m.baseIor) && m.baseIor >= 1, "/material/base_ior", "must be a number >= 1");
  if (!arrays[MaterialCoefficient::Roughness] && m.roughness > 0)
  {
    const std::string problem = roughnessPrecisionProblem(m.roughness, precision);
    list.check(problem.empty(), "/material/roughness", problem);
  }
  list.check(isReflectance(m.edgeTint), "/material/edge_tint", "components must be numbers from 0 to 1");
  list.check(!arrays[MaterialCoefficient::Ambient] && !arrays[MaterialCoefficient::Specular] &&
      !arrays[MaterialCoefficient::Shininess],
    "/material",
    "the vtk_pbr model takes its base colour, metallic factor and roughness from arrays (VTK's scalar colouring, a "
    "glTF file's parts): it has no ka, ks or shininess");
  // VTK's PBR shader takes a light's direction from its position where any light is positional,
  // which a distant light in a scene file has not (headlights sit at the camera:
  // placeHeadlightsAtTheCamera).
  const bool positional = hasPositionalLight(scene);
  for (std::size_t i = 0; i < scene.lights.size() && positional; ++i)
  {
    list.check(!std::holds_alternative<DistantLight>(scene.lights[i].source), "/lights/" + std::to_string(i) + "/type",
      "beside a point or spot light, VTK's PBR shader makes a directional light shine from its position, which a "
      "distant light has not: give it as a point light with \"attenuation\": {\"model\": \"none\"}");
  }
  list.check(!scene.ambientOcclusion, "/ambient_occlusion",
    "VTK's PBR shader has no ambient term for the occlusion to darken: use the vtk or lecture model");
  list.check(!scene.interreflection, "/interreflection",
    "the vtk_pbr model does not compute interreflection: use the lecture model");
}

/// The viewer's position and focal point within the precision's range, or its direction.
void checkViewer(const Scene& scene, Precision precision, ProblemList& list)
{
  const Viewer& viewer = scene.viewer;
  const double limit = coordinateLimit(precision);
  if (viewer.position)
  {
    list.check(isWithin(*viewer.position, limit), "/viewer/position", outOfRange(precision));
    if (viewer.focalPoint)
    {
      list.check(isWithin(*viewer.focalPoint, limit), "/viewer/focal_point", outOfRange(precision));
      list.check(*viewer.focalPoint != *viewer.position, "/viewer/focal_point", "must differ from the position");
    }
    return;
  }
  list.check(isNonZero(viewer.viewDirection), "/viewer/direction", "must be a non-zero vector");
  list.check(!reproducesVtkRenderer(scene.model), "/viewer/position",
    std::string("the ") + modelName(scene.model) +
      " model needs a camera position (VTK's renderer always has a local viewer)");
}

/// What interreflection needs of the rest of the scene.
void checkInterreflection(const Scene& scene, ProblemList& list)
{
  if (scene.interreflection)
  {
    const int bounces = scene.interreflection->bounces, samples = scene.interreflection->sampling.samples;
    list.check(bounces >= 1 && bounces <= Interreflection::maxBounces, "/interreflection/bounces",
      "must be a whole number from 1 to " + std::to_string(Interreflection::maxBounces) +
        " (leave \"interreflection\" out for none)");
    list.check(samples >= 2 && samples <= maxSamplesPerVertex, "/interreflection/samples",
      "must be a whole number from 2 to " + std::to_string(maxSamplesPerVertex));
  }
  list.check(!scene.interreflection || largestComponent(scene.material.kd) <= 1, "/material/kd",
    "is the albedo each bounce of \"interreflection\" reflects, and above 1 it reflects more light than arrives: "
    "give components <= 1");
  list.check(!(scene.interreflection && scene.spectral), "/interreflection",
    "is computed in RGB (each bounce multiplies by the material's RGB kd), which \"spectral\" replaces by spectra: "
    "remove one of them");
}

void checkLightName(const std::string& name, const std::string& at, ProblemList& list)
{
  if (name.size() > maxLightNameLength)
  {
    list.check(false, at + "/name",
      "a name of " + std::to_string(name.size()) + " characters is too long: use at most " +
        std::to_string(maxLightNameLength));
    return;
  }
  list.check(isLightName(name), at + "/name",
    "'" + name + "' is not a valid light name: use letters, digits and _, starting with a letter");
}
}

bool Scene::needsVisibility() const
{
  return ambientOcclusion ||
    std::any_of(lights.begin(), lights.end(), [](const NamedLight& light) { return light.shadows; });
}

std::vector<SceneProblem> sceneProblems(const Scene& scene, Precision precision)
{
  ProblemList list;
  const Viewer& viewer = scene.viewer;
  checkViewer(scene, precision, list);
  const Material& m = scene.material;
  list.check(isNonNegative(m.ka), "/material/ka", "components must be numbers >= 0");
  list.check(isNonNegative(m.kd), "/material/kd", "components must be numbers >= 0");
  list.check(isNonNegative(m.ks), "/material/ks", "components must be numbers >= 0");
  list.check(isNonNegative(m.shininess), "/material/shininess", "must be a number >= 0");
  checkMaterialArrays(scene, list);
  checkMicrofacetModel(scene, precision, list);
  if (const std::optional<SceneProblem> spectral = spectralModeProblem(scene))
  {
    list.problems.push_back(*spectral);
  }

  std::set<std::string> lightNames;
  for (std::size_t i = 0; i < scene.lights.size(); ++i)
  {
    const std::string at = "/lights/" + std::to_string(i);
    const NamedLight& light = scene.lights[i];
    checkLightName(light.name, at, list);
    LightChecks checks(at, scene.model, viewer.lineOfSight(), precision, list);
    checkLightSource(light.source, checks);
    list.check(
      lightNames.insert(light.name).second, at + "/name", "another light is already named '" + light.name + "'");
    list.check(!light.shadows || castsShadows(light.source), at + "/shadows",
      "only " + shadowCastingTypeNames() +
        " lights cast shadows (an ambient light has no direction; "
        "the mesh's shadowing of it is ambient occlusion): remove \"shadows\" from this light");
  }
  if (scene.ambientOcclusion)
  {
    const double maxDistance = scene.ambientOcclusion->maxDistance;
    list.check((maxDistance > 0 && maxDistance <= coordinateLimit(precision)) ||
        maxDistance == std::numeric_limits<double>::infinity(),
      "/ambient_occlusion/max_distance", "must be a number > 0 (leave it out to count occluders at any distance)");
  }

  checkInterreflection(scene, list);

  // Only a scene that is otherwise valid has meaningful peaks.
  if (list.problems.empty())
  {
    // The outputs are sums of the lights' contributions: keep them below a quarter of the
    // largest finite value, a margin for the rounding of the products that form them.
    // A light that overflows alone is named by its intensity, the field to change.
    const double limit = largestFinite(precision) / 4;
    auto beyond = [&](double peak)
    {
      const std::string reach =
        std::isfinite(peak) ? scientific(peak) : "more than " + scientific(largestFinite(Precision::Float64));
      return reach + " at a vertex (colour x intensity x k x attenuation at min_distance), beyond what " +
        precisionName(precision) + " holds: use " + (precision == Precision::Float32 ? "float64 or " : "");
    };
    double sum = 0;
    const Material bounding = peakMaterial(scene, precision);
    for (std::size_t i = 0; i < scene.lights.size(); ++i)
    {
      const double peak = peakContribution(scene.lights[i].source, bounding);
      // The light of colour and intensity 1 reaches k x attenuation: where that is the larger
      // factor, a tiny min_distance is what overflows, not the light's strength.
      LightSource unit = scene.lights[i].source;
      std::visit([](auto& light) { light.color = Rgb(1.0), light.intensity = 1.0; }, unit);
      const double unitPeak = peakContribution(unit, bounding);
      const bool nearness = unitPeak > 1 && unitPeak * unitPeak > peak;
      list.check(peak <= limit, "/lights/" + std::to_string(i) + (nearness ? "/min_distance" : "/intensity"),
        "this light alone can reach " + beyond(peak) +
          (nearness ? "a larger min_distance" : "a smaller intensity or colour"));
      sum += peak;
    }
    list.check(list.problems.size() > 0 || sum <= limit, "/lights",
      "together the lights can reach " + beyond(sum) + "smaller intensities");
    // Each bounce adds at most the last one's light (kd <= 1, checked above); "auto" may take
    // up to the most bounces.
    const int bounces = !scene.interreflection      ? 0
      : scene.interreflection->bouncesFromTolerance ? Interreflection::maxBounces
                                                    : scene.interreflection->bounces;
    list.check(list.problems.size() > 0 || sum * (1 + bounces) <= limit, "/interreflection/bounces",
      "the lights and their " + std::to_string(bounces) + " bounces can reach " + beyond(sum * (1 + bounces)) +
        "fewer bounces or smaller intensities");
  }
  return list.problems;
}

bool hasPositionalLight(const Scene& scene)
{
  return std::any_of(
    scene.lights.begin(), scene.lights.end(), [](const NamedLight& light) { return isPositional(light.source); });
}

void placeHeadlightsAtTheCamera(Scene& scene, bool lightsFromPositions)
{
  if (!lightsFromPositions)
  {
    return;
  }
  for (NamedLight& light : scene.lights)
  {
    if (const auto* headlight = std::get_if<Headlight>(&light.source))
    {
      light.source =
        PointLight{ scene.viewer.position.value(), headlight->color, headlight->intensity, { AttenuationModel::None } };
    }
  }
}

bool shadesBothSides(const Scene& scene)
{
  return scene.material.twoSided || reproducesVtkRenderer(scene.model);
}

std::vector<SceneProblem> untargetedSamplingProblems(const Scene& scene, bool lightsPlanned)
{
  const std::string remedy = "give one (shadelab shade --tolerance, the filter's Tolerance), or a number of ";
  if (scene.ambientOcclusion && scene.ambientOcclusion->sampling.fromTolerance && !scene.ambientOcclusion->target)
  {
    return { { "/ambient_occlusion/rays", "\"auto\" takes its count of rays from a tolerance: " + remedy + "rays" } };
  }
  const std::optional<Interreflection>& interreflection = scene.interreflection;
  if (interreflection && (interreflection->bouncesFromTolerance || interreflection->sampling.fromTolerance) &&
    !lightsPlanned)
  {
    const bool bounces = interreflection->bouncesFromTolerance;
    return { { std::string("/interreflection/") + (bounces ? "bounces" : "samples"),
      std::string("\"auto\" takes interreflection's count of ") + (bounces ? "bounces" : "gather rays") +
        " from a tolerance: " + remedy + (bounces ? "bounces" : "samples") } };
  }
  for (std::size_t i = 0; i < scene.lights.size(); ++i)
  {
    const Sampling* sampling = samplingOf(scene.lights[i].source);
    if (sampling && sampling->fromTolerance && !lightsPlanned)
    {
      return { { "/lights/" + std::to_string(i) + "/samples",
        "\"auto\" takes the count of light '" + scene.lights[i].name + "' from a tolerance: " + remedy + "samples" } };
    }
  }
  return {};
}
}
