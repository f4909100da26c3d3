#pragma once
// How one light is evaluated, as a tolerance's plan (MethodChoice.h) decides and the kernel
// (ShadingKernel.h) carries out.
#include "SequentialSampling.h"
#include "SpecularPower.h"

#include <glm/vec3.hpp>

#include <optional>

namespace shadelab
{
/// How one light is evaluated: exactly (the default), or by cheaper approximations that a
/// tolerance chose (MethodChoice.h).
struct LightMethod
{
  /// Point lights only: evaluate the light as a distant one, with the direction and
  /// attenuation it has at this point (the mesh's centre) used at every vertex.
  std::optional<glm::dvec3> distantFrom;
  PowMethod pow = PowMethod::Exact;
  /// Area lights and maps: their samples drawn to the plan's share ("samples": "auto").
  SampleTargets targets;

  bool operator==(const LightMethod& other) const
  {
    return distantFrom == other.distantFrom && pow == other.pow && targets == other.targets;
  }
};
}
