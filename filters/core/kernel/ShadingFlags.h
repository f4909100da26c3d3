#pragma once
// Bits of the per-vertex diagnostics array. A vertex may carry several.
#include <cstdint>

namespace shadelab
{
using ShadingFlags = std::uint8_t;

enum ShadingFlag : ShadingFlags
{
  /// The vertex has no usable normal (missing, zero length): it was shaded with n = 0, so it
  /// gets ambient light only.
  FlagDegenerateNormal = 1u << 0,
  /// A positional light is at or inside its minimum distance: attenuation was evaluated at the
  /// minimum distance, and at d = 0 the light direction is taken as the normal.
  FlagLightAtMinimumDistance = 1u << 1,
  /// A light is at or below the vertex's horizon (n.s <= 0): it adds no diffuse or specular.
  FlagLightBelowHorizon = 1u << 2,
  /// s = -v for a light under Blinn-Phong: h is undefined; h = 0, n.h = 0, no specular.
  FlagHalfVectorUndefined = 1u << 3,
  /// The position or normal has a NaN or Inf component: every output of the vertex is 0.
  FlagNonFiniteInput = 1u << 4,
  /// Two-sided shading flipped the normal to face the viewer.
  FlagNormalFlipped = 1u << 5,
  /// The shadow ray to a light that the normal faces met first a triangle that has the vertex
  /// as a corner: a concave crease, or the shadow terminator of a coarse mesh, where the smooth
  /// normal faces a light that a neighbouring facet hides. Under SelfShadowing::SmoothSurface
  /// the light is hidden only by what lies beyond those facets (visibility/Visibility.h).
  FlagHiddenByOwnTriangle = 1u << 6,
  /// A shadowed light hidden from the vertex is enclosed by the mesh: every ray from inside it
  /// meets a triangle (a light inside a closed mesh), so no vertex outside gets its light
  /// (visibility/Visibility.h, enclosesPoint).
  FlagLightEnclosed = 1u << 7,
};

/// Each flag and what it means, in the words the command line prints.
struct FlagMeaning
{
  ShadingFlag flag;
  const char* meaning;
};
inline constexpr FlagMeaning flagMeanings[] = {
  { FlagDegenerateNormal, "degenerate normal" },
  { FlagLightAtMinimumDistance, "a light at its minimum distance" },
  { FlagLightBelowHorizon, "a light below the horizon" },
  { FlagHalfVectorUndefined, "half vector undefined" },
  { FlagNonFiniteInput, "non-finite position or normal" },
  { FlagNormalFlipped, "normal flipped to face the viewer" },
  { FlagHiddenByOwnTriangle, "a shadowed light's ray meeting its own triangles first" },
  { FlagLightEnclosed, "a shadowed light hidden inside the mesh" },
};
}
