#pragma once
// The cone of a spotlight: the factor by which a spot dims light leaving at an angle to its
// axis. cosToAxis = dot(-s, axis), s the unit vector from the vertex to the light.
#include <algorithm>
#include <cmath>

namespace shadelab
{
enum class ConeModel
{
  Vtk,  // hard cut-off at a half-angle, cos^exponent inside (vtkLight)
  Gltf, // smooth fall-off between an inner and an outer angle (KHR_lights_punctual)
};

struct SpotCone
{
  ConeModel model = ConeModel::Vtk;
  double halfAngleDegrees = 30.0;  // Vtk: vtkLight::ConeAngle (default 30); >= 90 means no cone
  double exponent = 1.0;           // Vtk: vtkLight::Exponent (default 1, VTK clamps to [0, 128])
  double innerAngleDegrees = 0.0;  // Gltf: innerConeAngle (default 0)
  double outerAngleDegrees = 45.0; // Gltf: outerConeAngle (default pi/4)
};

class JsonNode;
class LightChecks;

/// A spotlight's "cone" field (docs/guide/scene-files.md).
SpotCone readCone(const JsonNode& light);

/// Its values' problems, at the light's "/cone".
void checkCone(const SpotCone& cone, LightChecks& checks);

// VTK 9.1 vtkOpenGLPolyDataMapper, positional lights with ConeAngle < 90:
// inside (coneDot >= cos(angle)) the factor is coneDot^exponent, outside it is 0. A coneDot
// that rounding puts above 1 is taken as 1, so that the factor never exceeds 1.
template<typename T>
T vtkConeFactor(T cosToAxis, T cosHalfAngle, T exponent)
{
  return cosToAxis >= cosHalfAngle ? std::pow(std::min(cosToAxis, T(1)), exponent) : T(0);
}

// KHR_lights_punctual, "Inner and Outer Cone Angles":
// scale = 1/max(0.001, cos(inner) - cos(outer)), offset = -cos(outer) scale,
// a = clamp(cosToAxis scale + offset, 0, 1), factor = a^2.
template<typename T>
T gltfConeFactor(T cosToAxis, T scale, T offset)
{
  const T a = std::clamp(cosToAxis * scale + offset, T(0), T(1));
  return a * a;
}

/// Constants of a cone, computed once per light rather than once per vertex.
template<typename T>
struct PreparedCone
{
  ConeModel model = ConeModel::Vtk;
  bool hasCutoff = false; // Vtk only: VTK applies the cone only when ConeAngle < 90
  T cosHalfAngle = 0, exponent = 1;
  T scale = 1, offset = 0;

  explicit PreparedCone(const SpotCone& cone)
    : model(cone.model)
  {
    constexpr double degree = 3.14159265358979323846 / 180.0;
    if (model == ConeModel::Vtk)
    {
      hasCutoff = cone.halfAngleDegrees < 90.0;
      cosHalfAngle = T(std::cos(cone.halfAngleDegrees * degree));
      exponent = T(cone.exponent);
    }
    else
    {
      const double cosInner = std::cos(cone.innerAngleDegrees * degree);
      const double cosOuter = std::cos(cone.outerAngleDegrees * degree);
      const double s = 1.0 / std::max(0.001, cosInner - cosOuter);
      scale = T(s);
      offset = T(-cosOuter * s);
    }
  }

  T factor(T cosToAxis) const
  {
    if (model == ConeModel::Gltf)
    {
      return gltfConeFactor(cosToAxis, scale, offset);
    }
    return hasCutoff ? vtkConeFactor(cosToAxis, cosHalfAngle, exponent) : T(1);
  }
};
}
