#include "AreaLight.h"

#include "AreaLightEstimator.h"
#include "LightFields.h"
#include "Overloaded.h"
#include "PolygonIrradiance.h"

#include <algorithm>

namespace shadelab
{
namespace
{
EmitterShape readPolygon(const JsonNode& node)
{
  const JsonNode vertices = node.at("vertices");
  if (!vertices.isArray())
  {
    vertices.fail("must be an array of [x, y, z] points");
  }
  PolygonEmitter polygon;
  for (std::size_t i = 0; i < vertices.size(); ++i)
  {
    polygon.vertices.push_back(vertices.element(i).vector3());
  }
  return polygon;
}

EmitterShape readRectangle(const JsonNode& node)
{
  // Corners c - u/2 - v/2, c + u/2 - v/2, c + u/2 + v/2, c - u/2 + v/2: it emits toward u x v.
  const glm::dvec3 c = node.at("center").vector3();
  const glm::dvec3 u = 0.5 * node.at("edge_u").vector3();
  const glm::dvec3 v = 0.5 * node.at("edge_v").vector3();
  return PolygonEmitter{ { c - u - v, c + u - v, c + u + v, c - u + v } };
}

EmitterShape readDisk(const JsonNode& node)
{
  return DiskEmitter{ node.at("center").vector3(), node.at("normal").vector3(), node.at("radius").number() };
}

EmitterShape readSphere(const JsonNode& node)
{
  return SphereEmitter{ node.at("center").vector3(), node.at("radius").number() };
}

/// An emitter's "type" name and fields in a scene file, and the function that reads its shape.
struct ShapeFileType
{
  SceneFileType fileType;
  EmitterShape (*readShape)(const JsonNode& node);
};

const std::vector<ShapeFileType>& shapeFileTypes()
{
  static const std::vector<ShapeFileType> types = {
    { { "polygon", { "vertices", "two_sided", "estimator", "samples", "max_samples", "stratified" } }, &readPolygon },
    { { "rectangle",
        { "center", "edge_u", "edge_v", "two_sided", "estimator", "samples", "max_samples", "stratified" } },
      &readRectangle },
    { { "disk", { "center", "normal", "radius", "two_sided", "estimator", "samples", "max_samples", "stratified" } },
      &readDisk },
    { { "sphere", { "center", "radius", "estimator", "samples", "max_samples", "stratified" } }, &readSphere },
  };
  return types;
}

void checkPolygon(const PolygonEmitter& polygon, LightChecks& checks)
{
  const auto& v = polygon.vertices;
  checks.require(v.size() >= 3, "/vertices", "a polygon needs at least 3 vertices");
  bool inRange = true;
  for (const glm::dvec3& vertex : v)
  {
    inRange = inRange && isWithin(vertex, coordinateLimit(checks.precision));
  }
  checks.require(inRange, "/vertices", outOfRange(checks.precision));
  if (v.size() < 3 || !inRange)
  {
    return;
  }
  const glm::dvec3 normal = polygonNormal(v);
  const double area = polygonArea(v);
  checks.require(area > 0 && normal != glm::dvec3(0.0), "/vertices", "the polygon has no area");
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
  checks.require(planar, "/vertices", "the polygon's vertices must lie in one plane");
  checks.require(!planar || convex, "/vertices",
    "the polygon must be convex, its vertices in order around it: split a concave emitter into convex lights");
}

/// A disk's or sphere's centre and radius.
void checkRound(const glm::dvec3& centre, double radius, LightChecks& checks)
{
  checks.point(centre, "/center");
  checks.require(std::isfinite(radius) && radius > 0 && radius <= coordinateLimit(checks.precision), "/radius",
    "must be a number > 0");
}
}

const std::vector<SceneFileType>& AreaLight::sceneFileTypes()
{
  static const std::vector<SceneFileType> types = []
  {
    std::vector<SceneFileType> fileTypes;
    for (const ShapeFileType& shape : shapeFileTypes())
    {
      fileTypes.push_back(shape.fileType);
    }
    return fileTypes;
  }();
  return types;
}

AreaLight AreaLight::read(const JsonNode& node, const SceneFileType& type, const std::string&)
{
  const auto& shapes = shapeFileTypes();
  const auto shape = std::find_if(shapes.begin(), shapes.end(),
    [&](const ShapeFileType& candidate) { return std::string(candidate.fileType.name) == type.name; });
  AreaLight light;
  light.shape = shape->readShape(node);
  readStrength(node, light);
  if (node.has("two_sided"))
  {
    light.twoSided = node.at("two_sided").boolean();
  }
  if (node.has("estimator"))
  {
    light.estimator = node.at("estimator")
                        .choice<AreaEstimator>({ { "exact", AreaEstimator::Exact },
                          { "monte_carlo", AreaEstimator::MonteCarlo }, { "point", AreaEstimator::Point } });
  }
  light.sampling = readSampling(node);
  return light;
}

std::string AreaLight::typeName() const
{
  // A rectangle is read as the polygon of its corners.
  return std::visit(Overloaded{ [](const PolygonEmitter&) { return "polygon"; },
                      [](const DiskEmitter&) { return "disk"; }, [](const SphereEmitter&) { return "sphere"; } },
    shape);
}

Rgb AreaLight::emitted() const
{
  return color * intensity;
}

void AreaLight::check(LightChecks& checks) const
{
  checks.strength(color, intensity);
  checks.distributed(sampling);
  std::visit(Overloaded{ [&](const PolygonEmitter& polygon) { checkPolygon(polygon, checks); },
               [&](const DiskEmitter& disk)
               {
                 checkRound(disk.centre, disk.radius, checks);
                 checks.direction(disk.normal, "/normal");
               },
               [&](const SphereEmitter& sphere) { checkRound(sphere.centre, sphere.radius, checks); } },
    shape);
}

double AreaLight::peakContribution(const Material& m) const
{
  return largestComponent(emitted()) * distributedPeakFactor * largestReflectance(m);
}

bool AreaLight::hasTerm(LightTerm term) const
{
  // The point approximation estimates S by the point light, not by sampling.
  return distributedLightHasTerm(term, estimator == AreaEstimator::MonteCarlo, estimator != AreaEstimator::Point);
}

void AreaLight::placeOn(const MeshPlacement& placement)
{
  // The radiance stays: the irradiance an emitter gives depends only on the solid angle it
  // fills, which scaling the emitter with the distances keeps.
  std::visit(Overloaded{ [&](PolygonEmitter& polygon)
               {
                 for (glm::dvec3& vertex : polygon.vertices)
                 {
                   vertex = placement.point(vertex);
                 }
               },
               [&](DiskEmitter& disk)
               {
                 disk.centre = placement.point(disk.centre);
                 disk.radius *= placement.radius;
               },
               [&](SphereEmitter& sphere)
               {
                 sphere.centre = placement.point(sphere.centre);
                 sphere.radius *= placement.radius;
               } },
    shape);
}

LightEvaluation AreaLight::prepare(const EvaluationContext& context) const
{
  const auto estimator =
    std::make_shared<const AreaLightEstimator>(*this, context.lightIndex, context.lobe, context.targets);
  return DistributedEvaluation{ estimator, std::nullopt, estimator };
}

ToleranceBounds AreaLight::toleranceBounds(const Material&, bool) const
{
  ToleranceBounds bounds;
  bounds.sampledIrradiance = estimator == AreaEstimator::MonteCarlo;
  bounds.autoSamples = "\"samples\": \"auto\"";
  if (estimator == AreaEstimator::Point)
  {
    bounds.unbounded = "its \"point\" estimator has no error bound: use \"exact\" or \"monte_carlo\"";
  }
  return bounds;
}
}
