#include "Scene.h"

#include "EnvironmentMap.h"
#include "NumberText.h"
#include "PolygonIrradiance.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <set>
#include <sstream>

namespace shadelab
{
std::string lightTypeName(const LightSource& source)
{
  struct Namer
  {
    std::string operator()(const DistantLight&) const { return "distant"; }
    std::string operator()(const Headlight&) const { return "headlight"; }
    std::string operator()(const PointLight&) const { return "point"; }
    std::string operator()(const SpotLight&) const { return "spot"; }
    std::string operator()(const AmbientLight&) const { return "ambient"; }
    std::string operator()(const AreaLight& light) const
    {
      return std::visit(
        [](const auto& shape)
        {
          using Shape = std::decay_t<decltype(shape)>;
          return std::is_same_v<Shape, PolygonEmitter> ? "polygon" : std::is_same_v<Shape, DiskEmitter> ? "disk" : "sphere";
        },
        light.shape);
    }
    std::string operator()(const EnvironmentLight&) const { return "environment"; }
  };
  return std::visit(Namer{}, source);
}

Rgb emittedColor(const LightSource& source)
{
  return std::visit(
    [](const auto& light)
    {
      Rgb color = light.color * light.intensity;
      if constexpr (std::is_same_v<std::decay_t<decltype(light)>, DistantLight>)
      {
        color *= light.intensityFromLength ? vectorLength(light.direction) : 1.0;
      }
      return color;
    },
    source);
}

SpecularModel evaluatedSpecularModel(const Scene& scene)
{
  if (scene.model == ShadingModel::VtkOpenGL2)
  {
    return scene.vtkLoneHeadlight ? SpecularModel::BlinnPhong : SpecularModel::Phong;
  }
  return scene.material.specular;
}

namespace
{
/// Two significant digits: enough to say how far out of range a value is.
std::string scientific(double x)
{
  return withDigits(x, 2);
}

const char* precisionName(Precision precision)
{
  return precision == Precision::Float32 ? "float32" : "float64";
}

double largestFinite(Precision precision)
{
  return precision == Precision::Float32 ? std::numeric_limits<float>::max()
                                         : std::numeric_limits<double>::max();
}
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

double coordinateLimit(Precision precision)
{
  // |a - b|^2 <= (2 limit)^2 = largest / 16: squared distances keep a margin for rounding.
  return std::sqrt(largestFinite(precision)) / 8;
}

std::string meshCoordinateProblem(double reach, Precision precision)
{
  if (reach <= coordinateLimit(precision))
  {
    return "";
  }
  return "the mesh's coordinates reach " + scientific(reach) + ", beyond +-" +
    scientific(coordinateLimit(precision)) + " where squared distances overflow " + precisionName(precision) +
    (precision == Precision::Float32 ? ": use double precision (shadelab shade --precision float64)" : "");
}

namespace
{
bool isNonNegative(const glm::dvec3& v)
{
  return isFinite(v) && v.x >= 0 && v.y >= 0 && v.z >= 0;
}

bool isNonNegative(double x)
{
  return std::isfinite(x) && x >= 0;
}

bool isNonZero(const glm::dvec3& v)
{
  return isFinite(v) && largestComponent(v) > 0;
}

/// The largest RGB value a light can add at a vertex: colour x intensity x the larger of kd
/// and ks, at full attenuation (a positional light at its minimum distance).
double peakContribution(const LightSource& source, const Material& m)
{
  const double k = std::max(largestComponent(m.kd), largestComponent(m.ks));
  const double peak = largestComponent(emittedColor(source));
  if (isAmbient(source))
  {
    return peak * largestComponent(m.ka);
  }
  if (const Attenuation* attenuation = attenuationOf(source))
  {
    return peak * attenuationAt(*attenuation, 0.0) * k;
  }
  // E is at most pi L, S at most 2 pi L (a lobe of 1 over the hemisphere).
  const double twoPi = 6.283185307179586;
  if (const auto* environment = std::get_if<EnvironmentLight>(&source))
  {
    double brightest = 0;
    for (const Rgb& texel : environment->map->radiance)
    {
      brightest = std::max(brightest, largestComponent(texel));
    }
    return peak * brightest * twoPi * k;
  }
  if (isDistributed(source))
  {
    return peak * twoPi * k;
  }
  return peak * k;
}

class ProblemList
{
public:
  void check(bool ok, const std::string& path, const std::string& message)
  {
    if (!ok)
    {
      problems.push_back({ path, message });
    }
  }
  std::vector<SceneProblem> problems;
};

void checkAttenuation(const Attenuation& a, const std::string& at, ShadingModel model, ProblemList& list)
{
  const bool vtkCanExpress =
    a.model == AttenuationModel::None || a.model == AttenuationModel::ConstantLinearQuadratic;
  list.check(model != ShadingModel::VtkOpenGL2 || vtkCanExpress, at + "/attenuation",
    "the vtk model has only vtkLight's constant-linear-quadratic attenuation (or none)");
  list.check(isNonNegative(a.minDistance), at + "/min_distance", "must be a number >= 0");
  list.check(!divergesAtZero(a) || a.minDistance > 0, at + "/min_distance",
    "must be > 0: this attenuation is infinite at distance 0");
  if (a.model == AttenuationModel::ConstantLinearQuadratic)
  {
    const bool allNonNegative =
      isNonNegative(a.constant) && isNonNegative(a.linear) && isNonNegative(a.quadratic);
    list.check(allNonNegative, at + "/attenuation", "constant, linear and quadratic must be >= 0");
    list.check(a.constant + a.linear + a.quadratic > 0, at + "/attenuation",
      "constant, linear and quadratic must not all be 0");
  }
  if (a.model == AttenuationModel::GltfRange)
  {
    list.check(std::isfinite(a.range) && a.range > 0, at + "/attenuation/range", "must be > 0");
  }
}

void checkCone(const SpotCone& cone, const std::string& at, ShadingModel model, ProblemList& list)
{
  if (cone.model == ConeModel::Vtk)
  {
    list.check(std::isfinite(cone.halfAngleDegrees) && cone.halfAngleDegrees >= 0 &&
        cone.halfAngleDegrees <= 180,
      at + "/cone/angle", "must be a half-angle in degrees, in [0, 180]");
    list.check(std::isfinite(cone.exponent) && cone.exponent >= 0 && cone.exponent <= 128,
      at + "/cone/exponent", "must be in [0, 128], the range vtkLight allows");
    return;
  }
  list.check(model != ShadingModel::VtkOpenGL2, at + "/cone/model",
    "the vtk model has only vtkLight's cone (model \"vtk\")");
  list.check(std::isfinite(cone.outerAngleDegrees) && cone.outerAngleDegrees > 0 &&
      cone.outerAngleDegrees <= 90,
    at + "/cone/outer_angle", "must be in (0, 90] degrees");
  list.check(std::isfinite(cone.innerAngleDegrees) && cone.innerAngleDegrees >= 0 &&
      cone.innerAngleDegrees < cone.outerAngleDegrees,
    at + "/cone/inner_angle", "must be >= 0 and less than outer_angle");
}

template <typename Light>
void checkStrength(const Light& light, const std::string& at, ProblemList& list)
{
  list.check(isNonNegative(light.color), at + "/color", "components must be numbers >= 0");
  list.check(isNonNegative(light.intensity), at + "/intensity", "must be a number >= 0");
}

bool isWithin(const glm::dvec3& point, double limit)
{
  return isFinite(point) && largestComponent(point) <= limit;
}

std::string outOfRange(Precision precision)
{
  return std::string("must be a finite point with coordinates within +-") +
    scientific(coordinateLimit(precision)) + " for " + precisionName(precision) + " arithmetic";
}

void checkPolygon(const PolygonEmitter& polygon, const std::string& at, Precision precision, ProblemList& list)
{
  const auto& v = polygon.vertices;
  list.check(v.size() >= 3, at + "/vertices", "a polygon needs at least 3 vertices");
  bool inRange = true;
  for (const glm::dvec3& vertex : v)
  {
    inRange = inRange && isWithin(vertex, coordinateLimit(precision));
  }
  list.check(inRange, at + "/vertices", outOfRange(precision));
  if (v.size() < 3 || !inRange)
  {
    return;
  }
  const glm::dvec3 normal = polygonNormal(v);
  const double area = polygonArea(v);
  list.check(area > 0 && normal != glm::dvec3(0.0), at + "/vertices", "the polygon has no area");
  if (!(area > 0))
  {
    return;
  }
  // Planar within a millionth of its size, and convex: every corner turns the same way.
  const double size = std::sqrt(area);
  bool planar = true, convex = true;
  for (std::size_t i = 0; i < v.size(); ++i)
  {
    const glm::dvec3& a = v[i];
    const glm::dvec3& b = v[(i + 1) % v.size()];
    const glm::dvec3& c = v[(i + 2) % v.size()];
    planar = planar && std::abs(glm::dot(a - v[0], normal)) <= 1e-6 * size;
    convex = convex && glm::dot(glm::cross(b - a, c - b), normal) >= 0;
  }
  list.check(planar, at + "/vertices", "the polygon's vertices must lie in one plane");
  list.check(!planar || convex, at + "/vertices",
    "the polygon must be convex, its vertices in order around it: split a concave emitter into convex lights");
}

void checkEmitter(const EmitterShape& shape, const std::string& at, Precision precision, ProblemList& list)
{
  if (const auto* polygon = std::get_if<PolygonEmitter>(&shape))
  {
    checkPolygon(*polygon, at, precision, list);
    return;
  }
  const auto* disk = std::get_if<DiskEmitter>(&shape);
  const auto* sphere = std::get_if<SphereEmitter>(&shape);
  const glm::dvec3& centre = disk ? disk->centre : sphere->centre;
  const double radius = disk ? disk->radius : sphere->radius;
  list.check(isWithin(centre, coordinateLimit(precision)), at + "/center", outOfRange(precision));
  list.check(std::isfinite(radius) && radius > 0 && radius <= coordinateLimit(precision), at + "/radius",
    "must be a number > 0");
  if (disk)
  {
    list.check(isNonZero(disk->normal), at + "/normal", "must be a non-zero vector");
  }
}

void checkEnvironment(const EnvironmentLight& light, const std::string& at, ProblemList& list)
{
  list.check(std::isfinite(light.rotationDegrees), at + "/rotation", "must be a finite angle in degrees");
  const EnvironmentMap* map = light.map.get();
  list.check(map != nullptr, at + "/file", "no environment map was loaded for this light");
  if (!map)
  {
    return;
  }
  // readEnvironmentMap ensures these; a map made in C++ may not.
  const bool shaped = map->height > 0 && map->width == 2 * map->height &&
    map->radiance.size() == std::size_t(map->width) * std::size_t(map->height);
  list.check(shaped, at + "/file", "the map must be twice as wide as high, with width x height texels");
  const bool radiant = std::all_of(map->radiance.begin(), map->radiance.end(), [](const Rgb& t) { return isNonNegative(t); });
  list.check(radiant, at + "/file", "every texel must be a finite non-negative radiance");
  const int width = light.bruteForceWidth;
  list.check(width >= map->width || (width >= 2 && width % 2 == 0 && map->width % width == 0),
    at + "/brute_force_width",
    "must be an even number that divides the map's width (" + std::to_string(map->width) + "), or at least that width");
}

/// Letters, digits and _, starting with a letter: a name that can stand in an array's name.
/// (A loop, not std::regex_match, whose recursion overflows the stack on long names.)
bool isLightName(const std::string& name)
{
  auto isAsciiLetter = [](char c) { return (c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z'); };
  return !name.empty() && isAsciiLetter(name[0]) &&
    std::all_of(name.begin(), name.end(),
      [&](char c) { return isAsciiLetter(c) || (c >= '0' && c <= '9') || c == '_'; });
}

void checkLight(const Scene& scene, const NamedLight& light, const std::string& at, Precision precision,
  ProblemList& list)
{
  if (light.name.size() > maxLightNameLength)
  {
    list.check(false, at + "/name",
      "a name of " + std::to_string(light.name.size()) + " characters is too long: use at most " +
        std::to_string(maxLightNameLength));
  }
  else
  {
    list.check(isLightName(light.name), at + "/name",
      "'" + light.name + "' is not a valid light name: use letters, digits and _, starting with a letter");
  }

  const bool vtk = scene.model == ShadingModel::VtkOpenGL2;
  std::visit(
    [&](const auto& source)
    {
      using Type = std::decay_t<decltype(source)>;
      checkStrength(source, at, list);
      if constexpr (std::is_same_v<Type, DistantLight>)
      {
        list.check(isNonZero(source.direction), at + "/direction", "must be a non-zero vector");
      }
      if constexpr (std::is_same_v<Type, Headlight>)
      {
        list.check(scene.viewer.lineOfSight().has_value(), at,
          "a headlight shines along the viewer's line of sight: give the viewer a focal_point");
      }
      if constexpr (std::is_same_v<Type, PointLight> || std::is_same_v<Type, SpotLight>)
      {
        list.check(isWithin(source.position, coordinateLimit(precision)), at + "/position", outOfRange(precision));
        checkAttenuation(source.attenuation, at, scene.model, list);
      }
      if constexpr (std::is_same_v<Type, SpotLight>)
      {
        list.check(isNonZero(source.axis), at + "/direction", "must be a non-zero vector");
        checkCone(source.cone, at, scene.model, list);
      }
      if constexpr (std::is_same_v<Type, AmbientLight>)
      {
        list.check(!vtk, at + "/type",
          "VTK's renderer has no ambient light: with the vtk model, put the ambient colour in material.ka");
      }
      if constexpr (std::is_same_v<Type, AreaLight> || std::is_same_v<Type, EnvironmentLight>)
      {
        list.check(!vtk, at + "/type",
          "VTK's renderer has no area lights or environment maps: use the lecture model");
        const int samples = source.sampling.samples;
        list.check(samples >= 2 && samples <= maxSamplesPerVertex, at + "/samples",
          "must be a whole number from 2 to " + std::to_string(maxSamplesPerVertex));
      }
      if constexpr (std::is_same_v<Type, AreaLight>)
      {
        checkEmitter(source.shape, at, precision, list);
      }
      if constexpr (std::is_same_v<Type, EnvironmentLight>)
      {
        checkEnvironment(source, at, list);
      }
    },
    light.source);
}
}

std::vector<SceneProblem> sceneProblems(const Scene& scene, Precision precision)
{
  ProblemList list;
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
  }
  else
  {
    list.check(isNonZero(viewer.viewDirection), "/viewer/direction", "must be a non-zero vector");
    list.check(scene.model != ShadingModel::VtkOpenGL2, "/viewer/position",
      "the vtk model needs a camera position (VTK's renderer always has a local viewer)");
  }

  const Material& m = scene.material;
  list.check(isNonNegative(m.ka), "/material/ka", "components must be numbers >= 0");
  list.check(isNonNegative(m.kd), "/material/kd", "components must be numbers >= 0");
  list.check(isNonNegative(m.ks), "/material/ks", "components must be numbers >= 0");
  list.check(isNonNegative(m.shininess), "/material/shininess", "must be a number >= 0");

  std::set<std::string> lightNames;
  for (std::size_t i = 0; i < scene.lights.size(); ++i)
  {
    const std::string at = "/lights/" + std::to_string(i);
    checkLight(scene, scene.lights[i], at, precision, list);
    list.check(lightNames.insert(scene.lights[i].name).second, at + "/name",
      "another light is already named '" + scene.lights[i].name + "'");
  }

  // Only a scene that is otherwise valid has meaningful peaks.
  if (list.problems.empty())
  {
    // The outputs are sums of the lights' contributions: keep them below a quarter of the
    // largest finite value, a margin for the rounding of the products that form them.
    double sum = 0;
    for (const NamedLight& light : scene.lights)
    {
      sum += peakContribution(light.source, m);
    }
    list.check(sum <= largestFinite(precision) / 4, "/lights",
      std::string("together the lights can reach ") + scientific(sum) +
        " at a vertex (colour x intensity x k x attenuation at min_distance), beyond what " +
        precisionName(precision) + " holds: use " +
        (precision == Precision::Float32 ? "float64 or " : "") + "smaller values");
  }
  return list.problems;
}
}
