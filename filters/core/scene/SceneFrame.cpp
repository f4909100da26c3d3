#include "SceneFrame.h"

namespace shadelab
{
namespace
{
/// A positional light's intensity and attenuation for world distances R d, given them for
/// mesh-frame distances d: intensity x falloff(R d) must equal the mesh frame's at d.
void placeFalloff(double& intensity, Attenuation& a, double R)
{
  a.minDistance *= R;
  switch (a.model)
  {
    case AttenuationModel::None:
      break;
    case AttenuationModel::Inverse:
      intensity *= R;
      break;
    case AttenuationModel::InverseSquare:
      intensity *= R * R;
      break;
    case AttenuationModel::ConstantLinearQuadratic:
      // 1/(k0 + k1 d + k2 d^2) is dimensionless: k1 and k2 carry 1/length and 1/length^2.
      a.linear /= R;
      a.quadratic /= R * R;
      break;
    case AttenuationModel::GltfRange:
      a.range *= R;
      intensity *= R * R;
      break;
  }
}

struct Placement
{
  glm::dvec3 c;
  double R;

  glm::dvec3 point(const glm::dvec3& p) const { return c + R * p; }

  void operator()(PointLight& light) const
  {
    light.position = point(light.position);
    placeFalloff(light.intensity, light.attenuation, R);
  }
  void operator()(SpotLight& light) const
  {
    light.position = point(light.position);
    placeFalloff(light.intensity, light.attenuation, R);
  }
  // An emitter's radiance stays: the irradiance it gives depends only on the solid angle it
  // fills, which scaling the emitter with the distances keeps.
  void operator()(AreaLight& light) const
  {
    std::visit([this](auto& shape) { place(shape); }, light.shape);
  }
  // Directions only, or no geometry at all. Listed rather than a catch-all template, so that a
  // new light type does not compile until it is placed.
  void operator()(DistantLight&) const {}
  void operator()(Headlight&) const {}
  void operator()(AmbientLight&) const {}
  void operator()(EnvironmentLight&) const {}

  void place(PolygonEmitter& polygon) const
  {
    for (glm::dvec3& vertex : polygon.vertices)
    {
      vertex = point(vertex);
    }
  }
  void place(DiskEmitter& disk) const
  {
    disk.centre = point(disk.centre);
    disk.radius *= R;
  }
  void place(SphereEmitter& sphere) const
  {
    sphere.centre = point(sphere.centre);
    sphere.radius *= R;
  }
};
}

Scene placedOnMesh(const Scene& scene, const MeshExtent& extent)
{
  Scene placed = scene;
  if (scene.frame == SceneFrame::World)
  {
    return placed;
  }
  const Placement placement{ extent.centre, extent.radius > 0 ? extent.radius : 1.0 };
  Viewer& viewer = placed.viewer;
  if (viewer.position)
  {
    viewer.position = placement.point(*viewer.position);
  }
  if (viewer.focalPoint)
  {
    viewer.focalPoint = placement.point(*viewer.focalPoint);
  }
  for (NamedLight& light : placed.lights)
  {
    std::visit(placement, light.source);
  }
  placed.frame = SceneFrame::World;
  return placed;
}
}
