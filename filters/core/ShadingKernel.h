#pragma once
// Per-vertex evaluation of the local reflectance model: every light's intermediate terms and
// their sums, written straight into the caller's arrays. VTK-free: the VTK filter hands in
// raw pointers and calls shadeVertex from a vtkSMPTools loop.
#include "ArrayCatalog.h"
#include "Scene.h"
#include "ShadingFlags.h"
#include "SpotCone.h"

#include <array>
#include <cstddef>
#include <vector>

namespace shadelab
{
/// Where results go: one pointer per requested array, nullptr for the rest. 3-component
/// arrays are interleaved per vertex (x y z, or r g b), as VTK stores them.
template <typename T>
struct ShadingOutputs
{
  std::vector<std::array<T*, LightTermCount>> lights; // follows scene.lights
  std::array<T*, TotalTermCount> totals{};
  ShadingFlags* flags = nullptr;
};

/// Evaluates a scene in arithmetic of type T (float or double). Work that no requested
/// array needs is skipped: no specular lobe without a specular output, no r without r, r.v
/// or Phong, no h without h, n.h or Blinn-Phong.
template <typename T>
class ShadingKernel
{
public:
  /// scene must have no sceneProblems(); outputs.lights must have one entry per scene light.
  ShadingKernel(const Scene& scene, ShadingOutputs<T> outputs);

  /// Shades vertex i. The normal need not be unit length. Concurrent calls for different i
  /// are safe.
  void shadeVertex(std::size_t i, const Vec3<T>& position, const Vec3<T>& normal) const;

private:
  enum class Kind
  {
    Distant,
    Point,
    Spot,
  };

  struct PreparedLight
  {
    Kind kind = Kind::Distant;
    Vec3<T> toLight{ 0 }; // distant lights: the constant s
    Vec3<T> position{ 0 };
    Vec3<T> axis{ 0 };
    Attenuation attenuation;
    PreparedCone<T> cone{ SpotCone{} };
    Vec3<T> diffuseColor{ 0 };  // Ld kd
    Vec3<T> specularColor{ 0 }; // Ls ks
    bool needsSpecular = false;
    bool needsReflection = false;
    bool needsHalfVector = false;
    std::array<T*, LightTermCount> out{};
  };

  struct LightSample
  {
    Vec3<T> toLight;
    T distance;
    T attenuation;
    T spotFactor;
    bool atMinimumDistance;
  };

  LightSample sample(const PreparedLight& light, const Vec3<T>& position, const Vec3<T>& normal) const;
  Vec3<T> toViewer(const Vec3<T>& position, const Vec3<T>& normal) const;
  void writeZeros(std::size_t i) const;

  std::vector<PreparedLight> lights_;
  ShadingOutputs<T> outputs_;
  Vec3<T> ambient_{ 0 }; // ka La, the same at every vertex
  SpecularModel specularModel_ = SpecularModel::None;
  T shininess_ = 0;
  bool twoSided_ = false;
  bool localViewer_ = false;
  bool needsViewer_ = true;
  Vec3<T> viewerPosition_{ 0 };
  Vec3<T> towardViewer_{ 0 }; // viewer at infinity: the constant v
  /// VTK's lone headlight: the specular viewer is the light itself, so h = s and n.h = n.s.
  bool specularViewerIsLight_ = false;
};

extern template class ShadingKernel<float>;
extern template class ShadingKernel<double>;
}
