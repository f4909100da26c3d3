#pragma once
// Which triangles hide a light from a vertex on its own surface (docs/formulas.md section 20).
#include <array>
#include <utility>

namespace shadelab
{
/// What hides a light from a vertex of a faceted mesh whose normals describe a smooth surface
/// (docs/formulas.md section 20, the shadow terminator).
enum class SelfShadowing
{
  /// The smooth surface: the facets around the vertex (its own, and a copy's within 30 degrees
  /// of its normal) do not hide a light its normal faces (OccluderMesh::hiddenPastOwnFacets);
  /// every other triangle does.
  SmoothSurface,
  /// The facets as given: every triangle hides what it blocks.
  Facets,
};

/// The names of a scene file's "self_shadowing" (and shadelab shade's --self-shadowing).
inline constexpr std::array<std::pair<const char*, SelfShadowing>, 2> selfShadowingNames{ {
  { "smooth", SelfShadowing::SmoothSurface },
  { "facets", SelfShadowing::Facets },
} };
}
