#pragma once
// docs/formulas.md section 11: distributed sources. An emitter of uniform radiance
// L = colour x intensity over its surface (a Lambertian emitter), seen from each vertex as a
// solid angle; its estimators are in AreaLightEstimator.
#include "LightType.h"
#include "SampleSequence.h"

#include <variant>
#include <vector>

namespace shadelab
{
/// A planar convex polygon; it emits on the side its vertices wind anticlockwise around (the
/// right-hand normal), or on both sides when the light is two-sided.
struct PolygonEmitter
{
  std::vector<glm::dvec3> vertices;
};

/// A disk, emitting on the side its normal points to (or both when two-sided).
struct DiskEmitter
{
  glm::dvec3 centre{ 0, 0, 0 };
  glm::dvec3 normal{ 0, 0, -1 };
  double radius = 1.0;
};

/// A sphere, emitting outward everywhere on its surface.
struct SphereEmitter
{
  glm::dvec3 centre{ 0, 0, 0 };
  double radius = 1.0;
};

using EmitterShape = std::variant<PolygonEmitter, DiskEmitter, SphereEmitter>;

/// How the irradiance from an area light is estimated. The specular term is estimated by
/// Monte Carlo for Exact and MonteCarlo, and by the point light for Point.
enum class AreaEstimator
{
  Exact,      // Lambert's polygon formula clipped to the horizon; the sphere's and disk's exact forms
  MonteCarlo, // `samples` points on the emitter, with a standard error per vertex
  Point,      // a point light at the emitter's centre ("five-times rule", docs/formulas.md section 11.5)
};

struct AreaLight
{
  EmitterShape shape;
  Rgb color{ 1, 1, 1 };
  double intensity = 1.0; // L = color x intensity, radiance
  bool twoSided = false;
  AreaEstimator estimator = AreaEstimator::Exact;
  Sampling sampling;

  SHADELAB_LIGHT_TYPE(AreaLight, Distributed, false, true);
  ToleranceBounds toleranceBounds(const Material& m, bool shadowed) const;
};
}
