#pragma once
// Scenes written relative to the mesh (SceneFrame::Mesh), so that one scene file lights a
// mesh of any size anywhere: positions in units of the mesh's bounding-sphere radius about
// its centre, and intensities that give the same irradiance at the same relative distance.
#include "MeshExtent.h"
#include "Scene.h"

namespace shadelab
{
/// The scene in world coordinates (frame World) for a mesh of this extent: a World scene as
/// it is; a Mesh scene with every position p moved to c + R p and every length times R
/// (emitter radii and vertices, min_distance, glTF range), directions kept, and intensities
/// and attenuation constants rescaled so that intensity x attenuation at distance R d equals
/// the mesh frame's at d (inverse_square intensity x R^2, inverse x R, vtk k1 / R and k2 / R^2,
/// gltf_range intensity x R^2; area lights' radiance and distant, ambient, headlight and
/// environment lights need nothing). A mesh of radius 0 (a single point) has no size to
/// measure by: R = 1 there. The result is not checked: run sceneProblems on it, since
/// placing can take a valid scene beyond the precision's limits.
Scene placedOnMesh(const Scene& scene, const MeshExtent& extent);
}
