#include "AreaLightEstimator.h"

#include "DiskIrradiance.h"
#include "Overloaded.h"
#include "PolygonIrradiance.h"
#include "SampleWarps.h"
#include "SampledTerms.h"
#include "SphereIrradiance.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace shadelab
{
namespace
{
double triangleArea(const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c)
{
  return 0.5 * vectorLength(glm::cross(b - a, c - a));
}

/// From a receiver to a point on an emitter: the unit direction and the distance, and the
/// distance's square (all 0 where the two points are one).
struct Reach
{
  glm::dvec3 direction{ 0.0 };
  double distance = 0;
  double distanceSquared = 0;
};

Reach reachOf(const glm::dvec3& onEmitter, const glm::dvec3& receiver)
{
  // Selects rather than a branch, so that the loop of a vertex's shadow rays vectorizes.
  const glm::dvec3 offset = onEmitter - receiver;
  const double d2 = glm::dot(offset, offset);
  const bool apart = d2 > 0;
  const double d = std::sqrt(d2);
  const double inverse = 1 / d;
  return { apart ? offset * inverse : glm::dvec3(0.0), apart ? d : 0.0, apart ? d2 : 0.0 };
}
}

AreaLightEstimator::AreaLightEstimator(
  const AreaLight& light, std::uint64_t lightIndex, const LobeModel& lobe, const SampleTargets& targets)
  : light_(light)
  , radiance_(light.color * light.intensity)
  , lightIndex_(lightIndex)
  , lobe_(lobe)
  , targets_(targets)
  , backFace_(light.twoSided ? 1.0 : 0.0)
{
  std::visit(Overloaded{ [&](const PolygonEmitter& polygon) { measurePolygon(polygon); },
               [&](const DiskEmitter& disk)
               {
                 normal_ = unitVector(disk.normal);
                 orthonormalBasis(normal_, tangent_, bitangent_);
                 centre_ = disk.centre;
                 area_ = samplePi * disk.radius * disk.radius;
               },
               [&](const SphereEmitter& sphere)
               {
                 centre_ = sphere.centre;
                 area_ = 4 * samplePi * sphere.radius * sphere.radius;
               } },
    light.shape);
}

void AreaLightEstimator::measurePolygon(const PolygonEmitter& polygon)
{
  const auto& v = polygon.vertices;
  normal_ = polygonNormal(v);
  // A convex polygon is the fan of triangles (v0, v_k-1, v_k).
  glm::dvec3 weightedCentre(0.0);
  for (std::size_t k = 2; k < v.size(); ++k)
  {
    const double area = triangleArea(v[0], v[k - 1], v[k]);
    area_ += area;
    weightedCentre += area * (v[0] + v[k - 1] + v[k]) / 3.0;
    fanAreaFraction_.push_back(area_);
  }
  for (double& fraction : fanAreaFraction_)
  {
    fraction /= area_;
  }
  centre_ = weightedCentre / area_;
}

bool AreaLightEstimator::isPlanar() const
{
  return std::visit(Overloaded{ [](const PolygonEmitter&) { return true; }, [](const DiskEmitter&) { return true; },
                      [](const SphereEmitter&) { return false; } },
    light_.shape);
}

double AreaLightEstimator::emittedCosine(const glm::dvec3& towardEmitter) const
{
  const double cosEmitter = -glm::dot(normal_, towardEmitter); // > 0: the receiver is in front
  // |cos| for a two-sided emitter, max(cos, 0) for a one-sided one: a product with backFace_
  // rather than a select on twoSided, which stops GCC's vectorizer in the loop of shadow rays.
  return std::max(cosEmitter, -cosEmitter * backFace_);
}

bool AreaLightEstimator::sendsLightTo(const glm::dvec3& position) const
{
  if (!isPlanar())
  {
    return true;
  }
  const double side = glm::dot(normal_, position - centre_);
  return light_.twoSided ? side != 0 : side > 0;
}

double AreaLightEstimator::exactProjectedSolidAngle(const SurfacePoint& point) const
{
  if (!sendsLightTo(point.position))
  {
    return 0;
  }
  return std::visit(
    Overloaded{ [&](const PolygonEmitter& polygon)
      { return polygonProjectedSolidAngle(polygon.vertices, point.position, point.normal); },
      [&](const DiskEmitter& disk)
      { return diskProjectedSolidAngle(disk.centre, normal_, disk.radius, point.position, point.normal); },
      [&](const SphereEmitter& sphere)
      { return sphereProjectedSolidAngle(sphere.centre, sphere.radius, point.position, point.normal); } },
    light_.shape);
}

WeightedDirection AreaLightEstimator::sample(const glm::dvec2& u, const SurfacePoint& point) const
{
  return sampleEmitter(u, point).toward;
}

bool AreaLightEstimator::risesAbovePlaneOf(const SurfacePoint& point) const
{
  // A polygon is above the plane where one of its corners is (it is convex); a disk where its
  // highest point is; a sphere where its centre is less than a radius below.
  auto height = [&](const glm::dvec3& p) { return glm::dot(point.normal, p - point.position); };
  return std::visit(Overloaded{ [&](const PolygonEmitter& polygon)
                      {
                        return std::any_of(polygon.vertices.begin(), polygon.vertices.end(),
                          [&](const glm::dvec3& corner) { return height(corner) > 0; });
                      },
                      [&](const DiskEmitter& disk)
                      {
                        const double tilt = glm::dot(point.normal, normal_);
                        return height(disk.centre) + disk.radius * std::sqrt(std::max(0.0, 1 - tilt * tilt)) > 0;
                      },
                      [&](const SphereEmitter& sphere) { return height(sphere.centre) + sphere.radius > 0; } },
    light_.shape);
}

AreaLightEstimator::EmitterSample AreaLightEstimator::sampleEmitter(
  const glm::dvec2& u, const SurfacePoint& point) const
{
  return std::visit(
    Overloaded{ [&](const PolygonEmitter& polygon) { return towardPoint(pointOnPolygon(polygon, u), point.position); },
      [&](const DiskEmitter& disk) { return towardPoint(pointOnDisk(disk, u), point.position); },
      [&](const SphereEmitter& sphere) { return towardSphere(sphere, u, point); } },
    light_.shape);
}

glm::dvec3 AreaLightEstimator::pointOnPolygon(const PolygonEmitter& polygon, const glm::dvec2& u) const
{
  // u.x picks a fan triangle by area and, stretched back to [0, 1), places the point in it:
  // the first whose cumulative fraction is above u.x, the last at most. Counted without a
  // branch on u.x, which a binary search takes the wrong way half the time.
  const auto& v = polygon.vertices;
  std::size_t k = 0;
  for (std::size_t i = 0; i + 1 < fanAreaFraction_.size(); ++i)
  {
    k += fanAreaFraction_[i] <= u.x ? 1 : 0;
  }
  const double low = k == 0 ? 0.0 : fanAreaFraction_[k - 1];
  const double stretched = std::clamp((u.x - low) / (fanAreaFraction_[k] - low), 0.0, 1.0);
  return pointOnTriangle(v[0], v[k + 1], v[k + 2], { stretched, u.y });
}

glm::dvec3 AreaLightEstimator::pointOnDisk(const DiskEmitter& disk, const glm::dvec2& u) const
{
  const glm::dvec2 q = disk.radius * concentricDisk(u);
  return disk.centre + q.x * tangent_ + q.y * bitangent_;
}

AreaLightEstimator::EmitterSample AreaLightEstimator::towardPoint(
  const glm::dvec3& onEmitter, const glm::dvec3& receiver) const
{
  // Area sampling, pdf 1/A, in solid angle d^2 / (A cos_e) (pbrt-v4, section 4.2.3).
  const Reach reach = reachOf(onEmitter, receiver);
  if (!(reach.distanceSquared > 0))
  {
    return {};
  }
  return { { reach.direction, area_ * emittedCosine(reach.direction) / reach.distanceSquared }, reach.distance };
}

AreaLightEstimator::EmitterSample AreaLightEstimator::towardSphere(
  const SphereEmitter& sphere, const glm::dvec2& u, const SurfacePoint& point) const
{
  const glm::dvec3 offset = sphere.centre - point.position;
  const double d = vectorLength(offset);
  const bool inside = d <= sphere.radius;
  // Inside the emitter every direction sees it: cosine-weighted, which makes E exactly pi L.
  // Outside, the cone of half-angle asin(r/d), where every direction hits the sphere;
  // 1 - cos theta_max = (r/d)^2 / (1 + cos theta_max) keeps its digits for a small, far sphere.
  const double sinMax2 = inside ? 1.0 : (sphere.radius / d) * (sphere.radius / d);
  const WeightedDirection toward = inside ? cosineWeightedDirection(point.normal, u)
                                          : uniformConeDirection(offset / d, sinMax2 / (1 + std::sqrt(1 - sinMax2)), u);
  // The ray meets the sphere where |p + t w - c| = r: t = b -+ sqrt(b^2 - (d^2 - r^2)), b = w.(c - p),
  // the nearer root from outside and the farther from inside. Written as (d^2 - r^2) / (b + root)
  // from outside, so that a far sphere's distance keeps its digits.
  const double b = glm::dot(toward.direction, offset);
  const double c = (d - sphere.radius) * (d + sphere.radius);
  const double root = std::sqrt(std::max(0.0, b * b - c));
  return { toward, inside ? b + root : c / std::max(b + root, std::numeric_limits<double>::min()) };
}

DistributedTerms AreaLightEstimator::monteCarlo(
  const SurfacePoint& point, bool irradiance, const SampleTargets& targets, const SampleShadowing& shadowing) const
{
  return sampledTerms(
    lightIndex_, point.index, light_.sampling, targets, irradiance, lobe_, point.normal, point.toViewer, shadowing.on(),
    [&](const SampleSequence& round)
    { return shadowing.of(round, [&](const SampleSequence& s, ShadowRay* rays) { shadowRaysOf(point, s, rays); }); },
    pointByPoint(
      [&](const glm::dvec2& u)
      {
        const WeightedDirection sample = this->sample(u, point);
        return RadianceSample{ sample.direction, radiance_ * sample.weight, std::nullopt };
      }));
}

DistributedTerms AreaLightEstimator::pointApproximation(const SurfacePoint& point) const
{
  // A Lambertian emitter of area A seen from direction -s has intensity I = L A cos_e (a
  // sphere, L pi r^2 from every side); the point light's E = I max(0, n.s) / d^2, evaluated at
  // the point lights' default minimum distance so that a vertex at the centre stays finite.
  DistributedTerms terms;
  const glm::dvec3 offset = centre_ - point.position;
  const double d = vectorLength(offset);
  const glm::dvec3 s = d > 0 ? offset / d : point.normal;
  const double projectedArea = isPlanar() ? area_ * emittedCosine(s) : area_ / 4; // a sphere: pi r^2
  const Rgb intensity = radiance_ * projectedArea * attenuationAt(Attenuation{}, d);
  terms.irradiance = intensity * std::max(0.0, glm::dot(point.normal, s));
  if (lobe_.wanted())
  {
    terms.specular = intensity * lobe_(point.normal, s, point.toViewer);
  }
  return terms;
}

DistributedTerms AreaLightEstimator::estimate(const SurfacePoint& point) const
{
  return estimateWith(point, {});
}

DistributedTerms AreaLightEstimator::estimate(const SurfacePoint& point, const HiddenSamples& hidden) const
{
  return estimateWith(point, { &hidden, nullptr });
}

DistributedTerms AreaLightEstimator::estimate(const SurfacePoint& point, RoundShadows& shadows) const
{
  return estimateWith(point, { nullptr, &shadows });
}

DistributedTerms AreaLightEstimator::estimateWith(const SurfacePoint& point, const SampleShadowing& shadowing) const
{
  switch (light_.estimator)
  {
    case AreaEstimator::Point:
    {
      // Its one ray, found by the visibility step or traced now.
      DistributedTerms terms = pointApproximation(point);
      ShadowRay ray;
      if (shadowing.rounds)
      {
        shadowRays(point, &ray);
      }
      const bool hidden =
        shadowing.fixed ? shadowing.fixed->hidden(0) : shadowing.rounds && shadowing.rounds->trace(&ray, 1).hidden(0);
      if (hidden)
      {
        terms = {};
        terms.visibility = 0;
      }
      return terms;
    }
    case AreaEstimator::MonteCarlo: return monteCarlo(point, true, targets_, shadowing);
    case AreaEstimator::Exact: break;
  }
  // Exact E; S has no closed form for a Phong lobe over a polygon, so it is sampled. With
  // shadows, the samples also give the visible fraction of E, drawn to E's target over the
  // exact E where there is one.
  const Rgb unshadowed = radiance_ * exactProjectedSolidAngle(point);
  DistributedTerms terms = lobe_.wanted() || shadowing.on()
    ? monteCarlo(point, false, shadowing.on() ? withVisibilityTarget(targets_, unshadowed) : targets_, shadowing)
    : DistributedTerms{};
  terms.irradiance = unshadowed * terms.visibility;
  terms.irradianceStdError = unshadowed * terms.visibilityStdError;
  return terms;
}

int AreaLightEstimator::shadowRayCount() const
{
  return light_.estimator == AreaEstimator::Point ? 1 : light_.sampling.samples;
}

namespace
{
/// A sample's shadow ray, cast only where the sample carries light to the point's lit side: the
/// others count as visible and add nothing.
ShadowRay shadowRayOf(const SurfacePoint& point, const glm::dvec3& direction, double weight, double distance)
{
  return ShadowRay{ direction, distance, weight > 0 && glm::dot(point.normal, direction) > 0 };
}
}

void AreaLightEstimator::shadowRays(const SurfacePoint& point, ShadowRay* rays) const
{
  if (light_.estimator == AreaEstimator::Point)
  {
    const glm::dvec3 offset = centre_ - point.position;
    const double d = vectorLength(offset);
    rays[0] = d > 0 ? shadowRayOf(point, offset / d, 1.0, d) : ShadowRay{};
    return;
  }
  shadowRaysOf(point, SampleSequence(lightIndex_, point.index, light_.sampling), rays);
}

void AreaLightEstimator::shadowRaysOf(const SurfacePoint& point, const SampleSequence& sequence, ShadowRay* rays) const
{
  auto ray = [&](const glm::dvec3& direction, double weight, double distance)
  { return shadowRayOf(point, direction, weight, distance); };
  if (!sendsLightTo(point.position) || !risesAbovePlaneOf(point))
  {
    std::fill_n(rays, sequence.count(), ShadowRay{}); // no sample would cast one
    return;
  }
  // A planar emitter's rays a block of samples at a time: their points on the emitter, then the
  // rays toward them in arrays of coordinates, a loop that vectorizes.
  auto fillToward = [&](auto emitterPoint)
  {
    constexpr int block = 16;
    for (int first = 0; first < sequence.count(); first += block)
    {
      const int count = std::min(block, sequence.count() - first);
      double x[block], y[block], z[block], distance[block], weight[block];
      warpedPoints(sequence, first, count, emitterPoint, x, y, z);
      for (int j = 0; j < count; ++j)
      {
        const Reach reach = reachOf({ x[j], y[j], z[j] }, point.position);
        x[j] = reach.direction.x;
        y[j] = reach.direction.y;
        z[j] = reach.direction.z;
        distance[j] = reach.distance;
        weight[j] = emittedCosine(reach.direction); // its sign: the division by d^2 is saved
      }
      for (int j = 0; j < count; ++j)
      {
        rays[first + j] = ray({ x[j], y[j], z[j] }, weight[j], distance[j]);
      }
    }
  };
  std::visit(Overloaded{ [&](const PolygonEmitter& polygon)
               { fillToward([&](const glm::dvec2& u) { return pointOnPolygon(polygon, u); }); },
               [&](const DiskEmitter& disk) { fillToward([&](const glm::dvec2& u) { return pointOnDisk(disk, u); }); },
               [&](const SphereEmitter& sphere)
               {
                 for (int j = 0; j < sequence.count(); ++j)
                 {
                   const EmitterSample sample = towardSphere(sphere, sequence.point(j), point);
                   rays[j] = ray(sample.toward.direction, sample.toward.weight, sample.distance);
                 }
               } },
    light_.shape);
}
}
