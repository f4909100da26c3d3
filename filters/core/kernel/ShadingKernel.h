#pragma once
// Evaluation of the local reflectance model over blocks of vertices: every light's
// intermediate terms and their sums, written straight into the caller's arrays. VTK-free: the
// VTK filter hands in raw pointers and calls shadeRange from a vtkSMPTools loop.
//
// A block holds up to 128 vertices as separate x, y, z arrays, and each step of the model
// (normalise, direction to the light, attenuation, cosine, lobe, ...) is one loop over the
// block with the light's branches taken outside it, so the compiler turns it into SIMD
// instructions. A vertex-at-a-time version with the same formulas ran 3 to 5 times slower.
#include "ArrayCatalog.h"
#include "LightEvaluation.h"
#include "LightMethod.h"
#include "Scene.h"
#include "ShadingFlags.h"
#include "SpectralColors.h"
#include "SpecularPower.h"
#include "SpotCone.h"

#include <algorithm>
#include <array>
#include <cstddef>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace shadelab
{
/// Where results go: one pointer per requested array, nullptr for the rest. 3-component
/// arrays are interleaved per vertex (x y z, or r g b), as VTK stores them.
template<typename T>
struct ShadingOutputs
{
  std::vector<std::array<T*, LightTermCount>> lights; // follows scene.lights
  std::array<T*, TotalTermCount> totals{};
  ShadingFlags* flags = nullptr;
  /// Follows scene.lights: for an area light or map drawn to a target, 1 at each vertex that
  /// stopped at the maximum short of it, else 0; nullptr (or empty): not marked.
  std::vector<std::uint8_t*> shortOfTarget;
  /// Per vertex, a standard error at least that which sampling leaves in the totals and in E's
  /// and the occlusion's own arrays (its largest channel): over the area lights and maps,
  /// max(1, kd) sigma_E + ks sigma_S, plus max(1, ka La) sigma_AO, added as if they erred
  /// together; nullptr: not computed.
  double* sampledStandardError = nullptr;
  /// Per vertex, the samples that its area lights' and maps' estimates drew, added to what it
  /// holds (what a run costs, for a tolerance's forecast); nullptr: not counted.
  std::uint32_t* samplesDrawn = nullptr;
};

/// What the mesh hides, computed before shading (visibility/Visibility.h), one value per
/// vertex: each shadowed light's visibility multiplies its diffuse and specular terms, and the
/// ambient occlusion the ambient term.
struct ShadingInputs
{
  std::vector<const float*> lightVisibility; // follows scene.lights; nullptr (or empty): not shadowed
  /// Follows scene.lights: for an area light or map with shadows, the bits of its samples that
  /// the mesh hides (HiddenSamples), hiddenSampleWords(shadowRayCount()) words per vertex;
  /// nullptr: none.
  std::vector<const std::uint64_t*> lightHiddenSamples;
  /// Follows scene.lights: for an area light or map with shadows drawn to a target, the
  /// visibility step's estimates (packTerms' rows, packedTermsSize per vertex), used as they
  /// are; nullptr: none.
  std::vector<const double*> lightShadowedTerms;
  const float* ambientOcclusion = nullptr;         // nullptr: the open sky, 1
  const float* ambientOcclusionStdError = nullptr; // with ambientOcclusion
  const ShadingFlags* flags = nullptr;             // flags the rays found (FlagHiddenByOwnTriangle)
  /// Each vertex's id in the whole mesh, which seeds its samples, where the arrays hold some
  /// of its vertices (a piece of a mesh split over processes); nullptr: the vertex's index.
  const long long* sampleIds = nullptr;
  /// The vertices' own coefficients where the scene's material comes from arrays, in the
  /// kernel's precision (VertexMaterial::of); nullptr: the scene's material gives them all.
  const VertexMaterial* material = nullptr;
  /// The colours each local light's terms and the ambient term are multiplied by, instead of
  /// the products of the scene's RGB values: the spectral mode's (SpectralColors.h); nullptr:
  /// the RGB model's.
  const LightColors* lightColors = nullptr;
};

/// Up to `capacity` vertices in structure-of-arrays form; first is the index of the block's
/// first vertex in the output arrays.
template<typename T>
struct VertexBlock
{
  static constexpr std::size_t capacity = 128;
  std::size_t first = 0;
  std::size_t count = 0;
  std::array<T, capacity> px, py, pz, nx, ny, nz;

  /// Puts a vertex in slot k, converted to T.
  template<typename U>
  void set(std::size_t k, const Vec3<U>& position, const Vec3<U>& normal)
  {
    px[k] = T(position.x);
    py[k] = T(position.y);
    pz[k] = T(position.z);
    nx[k] = T(normal.x);
    ny[k] = T(normal.y);
    nz[k] = T(normal.z);
  }
};

/// Evaluates a scene in arithmetic of type T (float or double). Work that no requested
/// array needs is skipped: no specular lobe without a specular output, no r without r, r.v
/// or Phong, no h without h, n.h, Blinn-Phong or the flags, no v unless a term or the flags
/// need it.
template<typename T>
class ShadingKernel
{
public:
  /// scene must have no sceneProblems(); outputs.lights must have one entry per scene light,
  /// and methods one per scene light or none (every light exact). inputs must have the
  /// visibility of every light with shadows, and the occlusion if the scene has it.
  ShadingKernel(const Scene& scene, ShadingOutputs<T> outputs, const std::vector<LightMethod>& methods = {},
    ShadingInputs inputs = {});

  /// Shades the block's vertices. Normals need not be unit length. Concurrent calls for
  /// different vertices are safe.
  void shadeBlock(const VertexBlock<T>& block) const;

  /// Whether the scene has area lights or environment maps, whose estimators make every
  /// vertex far slower than the local lights do.
  bool hasDistributedLights() const { return !distributedLights_.empty(); }

private:
  struct PreparedLight
  {
    LocalEvaluation::Geometry geometry = LocalEvaluation::Geometry::Distant;
    Vec3<T> toLight{ 0 }; // distant lights: the constant s
    T distance = 0;       // distant lights: the constant distance (0, or the approximated one)
    T attenuation = 1;    // distant lights: the constant attenuation
    Vec3<T> position{ 0 };
    Vec3<T> axis{ 0 };
    Attenuation attenuationModel;
    PreparedCone<T> cone{ SpotCone{} };
    Vec3<T> diffuseColor{ 0 };  // Ld kd
    Vec3<T> specularColor{ 0 }; // Ls ks
    PowMethod pow = PowMethod::Exact;
    bool needsSpecular = false;
    bool needsReflection = false;
    bool needsHalfVector = false;
    const float* visibility = nullptr; // per vertex, for a light with shadows
    std::array<T*, LightTermCount> out{};
  };

  /// E(n) = sum of coefficient x monomial over the monomials xx, yy, zz, xy, xz, yz, x, y, z,
  /// 1 of the normal: an environment map's SH irradiance, evaluated in a vectorised loop.
  struct PreparedPolynomial
  {
    std::array<Vec3<T>, 10> coefficients;
  };

  /// An area light or environment map: its estimator, run vertex by vertex in float64, and
  /// for SH irradiance the polynomial that replaces it for E. With shadows, the shadowed
  /// estimator gives E and S instead, from the hidden samples, or the visibility step gave them
  /// (shadowedTerms).
  struct DistributedLightSlot
  {
    bool runsEstimator() const { return estimator || hiddenSamples || shadowedTerms; }

    std::shared_ptr<const DistributedLightEstimator> estimator;
    std::optional<PreparedPolynomial> irradiance;
    std::shared_ptr<const ShadowedLightEstimator> shadowed; // with hiddenSamples: the light's shadows
    const std::uint64_t* hiddenSamples = nullptr;
    int hiddenWords = 0;                   // per vertex
    const double* shadowedTerms = nullptr; // packedTermsSize per vertex
    Rgb kd{ 0.0 }, ks{ 0.0 };
    bool needsSpecular = false;
    std::array<T*, LightTermCount> out{};
    int transferComponents = 0;            // precomputed transfer: its coefficients per vertex
    std::uint8_t* shortOfTarget = nullptr; // ShadingOutputs::shortOfTarget's
  };

  struct Workspace;

  PreparedLight prepareLocal(const LocalEvaluation& evaluation, const std::array<T*, LightTermCount>& out,
    const Material& m, bool needsSpecular, PowMethod pow) const;
  DistributedLightSlot prepareDistributed(const DistributedEvaluation& evaluation,
    const std::array<T*, LightTermCount>& out, const Material& m, bool needsSpecular,
    const std::uint64_t* hiddenSamples, const double* shadowedTerms) const;

  /// The vtk_pbr model's material, roughness, F0 and F90 (docs/vtk-renderer.md section 11.1).
  void prepareMicrofacet(const Scene& scene);
  void prepareNormals(const VertexBlock<T>& block, Workspace& w) const;
  void loadMaterial(const VertexBlock<T>& block, Workspace& w) const;
  bool perVertex(MaterialCoefficient c) const { return vertexMaterial_[int(c)] != nullptr; }
  /// Whether each vertex has its own F0 and F90: its base colour or metallic factor is its own.
  bool perVertexFresnel() const
  {
    return perVertex(MaterialCoefficient::Diffuse) || perVertex(MaterialCoefficient::Metallic);
  }
  void prepareViewer(const VertexBlock<T>& block, Workspace& w) const;
  void sampleLight(const PreparedLight& light, const VertexBlock<T>& block, Workspace& w) const;
  void addLight(const PreparedLight& light, const VertexBlock<T>& block, Workspace& w) const;
  void addLectureTerms(const PreparedLight& light, const VertexBlock<T>& block, Workspace& w) const;
  void addMicrofacetTerms(const PreparedLight& light, const VertexBlock<T>& block, Workspace& w) const;
  void specularLobes(const PreparedLight& light, std::size_t count, Workspace& w) const;
  void storeLight(const PreparedLight& light, const VertexBlock<T>& block, const Workspace& w) const;
  void addDistributedLight(const DistributedLightSlot& light, const VertexBlock<T>& block, Workspace& w) const;
  void estimateDistributedLight(const DistributedLightSlot& light, const VertexBlock<T>& block, Workspace& w) const;
  void storeTotals(const VertexBlock<T>& block, Workspace& w) const;

  std::vector<PreparedLight> lights_;
  std::vector<DistributedLightSlot> distributedLights_;
  std::vector<std::array<int, LightTermCount>> termComponents_; // follows scene.lights: lightTermComponents
  ShadingOutputs<T> outputs_;
  ShadingInputs inputs_;
  std::array<const T*, MaterialCoefficientCount> vertexMaterial_{}; // inputs_.material's, or nullptr
  Vec3<T> ambient_{ 0 }; // ka La (La where ka is per vertex), times the occlusion where there is one
  SpecularModel specularModel_ = SpecularModel::None;
  T shininess_ = 0;
  bool twoSided_ = false;
  ShadedSide shadedSide_ = ShadedSide::Seen;
  bool localViewer_ = false;
  bool needsViewer_ = true;
  Vec3<T> viewerPosition_{ 0 };
  Vec3<T> towardViewer_{ 0 }; // viewer at infinity: the constant v
  /// VTK's lone headlight: the specular viewer is the light itself, so h = s and n.h = n.s.
  bool specularViewerIsLight_ = false;
  /// The vtk_pbr model (Microfacet.h): its material, its roughness, and F0 and F90 per channel
  /// (a vertex's own where its base colour or metallic factor is per vertex).
  bool microfacet_ = false;
  MicrofacetMaterial microfacetMaterial_{};
  double dielectricReflectance_ = 0; // the dielectric's F0, for a base colour per vertex
  T roughness_ = 0;
  std::array<T, 3> normalFresnel_{}, grazingFresnel_{};
};

/// Shades vertices [begin, end) block by block. vertex(i, block, k) copies vertex i's
/// position and normal into slot k of the block.
template<typename T, typename CopyVertex>
void shadeRange(const ShadingKernel<T>& kernel, std::size_t begin, std::size_t end, CopyVertex&& vertex)
{
  VertexBlock<T> block;
  for (std::size_t first = begin; first < end; first += VertexBlock<T>::capacity)
  {
    block.first = first;
    block.count = std::min(VertexBlock<T>::capacity, end - first);
    for (std::size_t k = 0; k < block.count; ++k)
    {
      vertex(first + k, block, k);
    }
    kernel.shadeBlock(block);
  }
}

extern template class ShadingKernel<float>;
extern template class ShadingKernel<double>;
}
