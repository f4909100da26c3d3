#pragma once
// Distance attenuation of positional lights (point and spot).
#include <algorithm>

namespace shadelab
{
enum class AttenuationModel
{
  None,                    // f = 1
  Inverse,                 // f = 1/d            (docs/formulas.md section 9.1, softer)
  InverseSquare,           // f = 1/d^2          (docs/formulas.md section 9.1, physical)
  ConstantLinearQuadratic, // f = 1/(k0+k1 d+k2 d^2)  (vtkLight::AttenuationValues)
  GltfRange,               // f = window(d)/d^2  (KHR_lights_punctual)
};

/// How a positional light fades with distance. Every model is evaluated at
/// max(d, minDistance), so a light at (or very near) a vertex gives a large but finite value
/// instead of Inf. Filament, Frostbite and Unity clamp the same way at 1 cm
/// (docs/formulas.md section 9.2).
struct Attenuation
{
  AttenuationModel model = AttenuationModel::InverseSquare;
  double constant = 1.0;  // k0, ConstantLinearQuadratic only
  double linear = 0.0;    // k1
  double quadratic = 0.0; // k2
  double range = 0.0;     // GltfRange only: the distance where the light reaches zero
  double minDistance = 0.01;
};

// docs/formulas.md section 9.1: f = 1/d^2, the inverse-square law.
template<typename T>
T inverseSquareFalloff(T d)
{
  return T(1) / (d * d);
}

// docs/formulas.md section 9.1: f = 1/d.
template<typename T>
T inverseFalloff(T d)
{
  return T(1) / d;
}

// VTK 9.1 vtkOpenGLPolyDataMapper, positional lights: 1/(k0 + k1 d + k2 d^2).
template<typename T>
T constantLinearQuadraticFalloff(T k0, T k1, T k2, T d)
{
  return T(1) / (k0 + k1 * d + k2 * d * d);
}

// KHR_lights_punctual, "Range Property": clamp(1 - (d/range)^4, 0, 1) / d^2.
template<typename T>
T gltfRangeFalloff(T range, T d)
{
  const T ratio = d / range;
  const T ratio2 = ratio * ratio;
  const T window = std::clamp(T(1) - ratio2 * ratio2, T(0), T(1));
  return window / (d * d);
}

template<typename T>
T attenuationAt(const Attenuation& a, T distance)
{
  const T d = std::max(distance, T(a.minDistance));
  switch (a.model)
  {
    case AttenuationModel::None: return T(1);
    case AttenuationModel::Inverse: return inverseFalloff(d);
    case AttenuationModel::InverseSquare: return inverseSquareFalloff(d);
    case AttenuationModel::ConstantLinearQuadratic:
      return constantLinearQuadraticFalloff(T(a.constant), T(a.linear), T(a.quadratic), d);
    case AttenuationModel::GltfRange: return gltfRangeFalloff(T(a.range), d);
  }
  return T(1);
}

class JsonNode;
class LightChecks;

/// A light's "attenuation" and "min_distance" fields (docs/guide/scene-files.md).
Attenuation readAttenuation(const JsonNode& light);

/// Its values' problems, at the light's "/attenuation" and "/min_distance".
void checkAttenuation(const Attenuation& a, LightChecks& checks);

/// A positional light's intensity and attenuation for world distances R d, given them for
/// mesh-frame distances d (scene/SceneFrame.h): intensity x falloff(R d) equals the mesh
/// frame's at d.
void placeFalloff(double& intensity, Attenuation& a, double R);

/// True when the model grows without bound as d -> 0, so a minimum distance of 0 would
/// let a light at a vertex produce Inf.
inline bool divergesAtZero(const Attenuation& a)
{
  switch (a.model)
  {
    case AttenuationModel::None: return false;
    case AttenuationModel::ConstantLinearQuadratic: return a.constant <= 0.0;
    default: return true;
  }
}
}
