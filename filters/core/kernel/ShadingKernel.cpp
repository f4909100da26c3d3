#include "ShadingKernel.h"

#include <stdexcept>

#include "KernelLanes.h"
#include "Microfacet.h"
#include "Overloaded.h"
#include "Reflectance.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace shadelab
{
namespace
{
template<typename T>
Vec3<T> toVec(const glm::dvec3& v)
{
  return Vec3<T>(v);
}

// A normal shorter than this is treated as missing: it comes from degenerate geometry
// (zero-area triangles, isolated points), not from a surface direction.
template<typename T>
constexpr T degenerateNormalLength2 = T(1e-12);
}
using namespace kernel_lanes;

/// The per-vertex quantities of one block, one array ("lane") each.
template<typename T>
struct ShadingKernel<T>::Workspace
{
  Lane<T> nx, ny, nz; // the unit normal, flipped to the viewer where two-sided
  Lane<T> vx, vy, vz; // to the viewer
  Lane<T> sx, sy, sz; // to the current light
  Lane<T> distance, attenuation, spotFactor, cosIncidence;
  Lane<T> diffuse, specular; // the light's factors of Ld kd and Ls ks
  Lane<T> rx, ry, rz, rDotV;
  Lane<T> hx, hy, hz, nDotH;
  Lane<T> incidenceAngle;
  Lane<T> diffuseR, diffuseG, diffuseB, specularR, specularG, specularB; // sums over lights
  Lane<T> irradianceR, irradianceG, irradianceB;                         // an area light's or map's E
  Lane<T> integralR, integralG, integralB;                               // and its S, before ks
  std::array<Rgb, VertexBlock<T>::capacity> sampledError; // ShadingOutputs::sampledStandardError's, per channel
  std::array<ShadingFlags, VertexBlock<T>::capacity> flags;
  // A material from arrays: the vertices' own coefficients, and the current light's diffuse and
  // specular factors times them (the light's colour holds the rest).
  std::array<Lane<T>, 3> ka, kd, ks, diffuseRgb, specularRgb;
  Lane<T> shininess, metallic, roughness;
  Lane<T> ggxDistribution, smithVisibility; // the microfacet model's D and V
  std::array<Lane<T>, 3> fresnel;           // and its F, channel by channel
  /// The microfacet model's F0 and F90 at each vertex, where its base colour or metallic factor
  /// is the vertex's own.
  std::array<Lane<T>, 3> normalFresnel, grazingFresnel;
  Lane<T> halfVectorDefined; // 1 or 0: a lane of T, so that its loops vectorise with the rest
  std::size_t nonFinite = 0;
};

/// Where unitVectorsFrom found no direction, the normal stands in for it.
template<typename T, typename Workspace>
void replaceZeroLengthByNormal(std::size_t undefined, std::size_t count, const Lane<T>& distance, Lane<T>& x,
  Lane<T>& y, Lane<T>& z, const Workspace& w)
{
  for (std::size_t k = 0; undefined > 0 && k < count; ++k)
  {
    if (distance[k] < std::numeric_limits<T>::min())
    {
      x[k] = w.nx[k];
      y[k] = w.ny[k];
      z[k] = w.nz[k];
      --undefined;
    }
  }
}

template<typename T>
typename ShadingKernel<T>::PreparedLight ShadingKernel<T>::prepareLocal(const LocalEvaluation& evaluation,
  const std::array<T*, LightTermCount>& out, const Material& m, bool needsSpecular, PowMethod pow) const
{
  PreparedLight light;
  light.geometry = evaluation.geometry;
  light.toLight = toVec<T>(evaluation.toLight);
  light.distance = T(evaluation.distance);
  light.attenuation = T(evaluation.attenuation);
  light.position = toVec<T>(evaluation.position);
  light.axis = toVec<T>(evaluation.axis);
  light.attenuationModel = evaluation.falloff;
  light.cone = PreparedCone<T>(evaluation.cone);
  // The microfacet model's diffuse colour is (1 - m) base / pi (its 1 - F per channel in the
  // lanes), its specular one 1 (D V F in the lanes).
  const MicrofacetMaterial& microfacet = m.microfacet;
  light.diffuseColor = toVec<T>(
    evaluation.color * (microfacet_ ? (1.0 - microfacet.metallic) * microfacet.baseColor * vtkReciprocalPi : m.kd));
  light.specularColor = toVec<T>(evaluation.color * (microfacet_ ? Rgb(1.0) : m.ks));
  light.pow = pow;
  light.out = out;
  light.needsSpecular = needsSpecular;
  light.needsReflection = out[int(LightTerm::Reflection)] || out[int(LightTerm::RDotV)] ||
    (needsSpecular && specularModel_ == SpecularModel::Phong);
  light.needsHalfVector = out[int(LightTerm::HalfVector)] || out[int(LightTerm::NDotH)] ||
    (needsSpecular && specularModel_ == SpecularModel::BlinnPhong) || outputs_.flags || microfacet_;
  return light;
}

template<typename T>
typename ShadingKernel<T>::DistributedLightSlot ShadingKernel<T>::prepareDistributed(
  const DistributedEvaluation& evaluation, const std::array<T*, LightTermCount>& out, const Material& m,
  bool needsSpecular, const std::uint64_t* hiddenSamples, const double* shadowedTerms) const
{
  DistributedLightSlot light;
  light.estimator = evaluation.estimator;
  if (hiddenSamples && evaluation.shadowed)
  {
    light.shadowed = evaluation.shadowed;
    light.hiddenSamples = hiddenSamples;
    light.hiddenWords = hiddenSampleWords(evaluation.shadowed->shadowRayCount());
  }
  light.shadowedTerms = shadowedTerms;
  const std::optional<IrradiancePolynomial>& e = evaluation.irradiance;
  if (e && !light.hiddenSamples && !light.shadowedTerms)
  {
    light.irradiance = PreparedPolynomial{ { toVec<T>(e->xx), toVec<T>(e->yy), toVec<T>(e->zz), toVec<T>(e->xy),
      toVec<T>(e->xz), toVec<T>(e->yz), toVec<T>(e->x), toVec<T>(e->y), toVec<T>(e->z), toVec<T>(e->constant) } };
  }
  light.kd = m.kd;
  light.ks = m.ks;
  light.needsSpecular = needsSpecular;
  light.out = out;
  return light;
}

template<typename T>
void ShadingKernel<T>::prepareMicrofacet(const Scene& scene)
{
  microfacet_ = scene.model == ShadingModel::VtkPbr;
  microfacetMaterial_ = scene.material.microfacet;
  dielectricReflectance_ = dielectricReflectance(microfacetMaterial_.baseIor);
  roughness_ = T(microfacetMaterial_.roughness);
  const Rgb f0 = reflectanceAtNormalIncidence(microfacetMaterial_);
  const Rgb f90 = reflectanceAtGrazingIncidence(microfacetMaterial_, f0);
  normalFresnel_ = { T(f0.x), T(f0.y), T(f0.z) };
  grazingFresnel_ = { T(f90.x), T(f90.y), T(f90.z) };
}

template<typename T>
ShadingKernel<T>::ShadingKernel(
  const Scene& scene, ShadingOutputs<T> outputs, const std::vector<LightMethod>& methods, ShadingInputs inputs)
  : outputs_(std::move(outputs))
  , inputs_(std::move(inputs))
{
  for (int c = 0; c < MaterialCoefficientCount && inputs_.material; ++c)
  {
    vertexMaterial_[c] = inputs_.material->of<T>(MaterialCoefficient(c));
  }
  // Where a coefficient is per vertex, the lights' colours take 1 for it and the vertex's own
  // multiplies each term (loadMaterial).
  Material m = scene.material;
  m.ka = perVertex(MaterialCoefficient::Ambient) ? Rgb(1.0) : m.ka;
  m.kd = perVertex(MaterialCoefficient::Diffuse) ? Rgb(1.0) : m.kd;
  m.ks = perVertex(MaterialCoefficient::Specular) ? Rgb(1.0) : m.ks;
  // The microfacet model's base colour from kd's array is VTK's scalar colouring under PBR; its
  // metallic factor from an array multiplies the diffuse part vertex by vertex (1 - m).
  m.microfacet.baseColor = perVertex(MaterialCoefficient::Diffuse) ? Rgb(1.0) : m.microfacet.baseColor;
  m.microfacet.metallic = perVertex(MaterialCoefficient::Metallic) ? 0.0 : m.microfacet.metallic;
  const bool vtk = scene.model == ShadingModel::VtkOpenGL2;
  // docs/vtk-renderer.md sections 1, 2 and 5: VTK's shader always flips back faces, and its
  // ambient term is Ka*Ca from the property alone. In its lone-headlight shader the specular
  // viewer is the light.
  specularModel_ = evaluatedSpecularModel(scene);
  specularViewerIsLight_ = vtk && scene.vtkLoneHeadlight;
  prepareMicrofacet(scene);
  twoSided_ = shadesBothSides(scene);
  shadedSide_ = scene.shadedSide;
  shininess_ = T(m.shininess);

  localViewer_ = scene.viewer.position.has_value();
  if (localViewer_)
  {
    viewerPosition_ = toVec<T>(*scene.viewer.position);
  }
  else
  {
    towardViewer_ = toVec<T>(-unitVector(scene.viewer.viewDirection));
  }

  const bool totalSpecular = outputs_.totals[int(TotalTerm::Specular)] || outputs_.totals[int(TotalTerm::Total)];
  Rgb ambientLight = vtk ? Rgb(1.0) : Rgb(0.0);
  for (std::size_t l = 0; l < scene.lights.size(); ++l)
  {
    const LightMethod method = methods.empty() ? LightMethod{} : methods.at(l);
    const std::array<T*, LightTermCount>& out = outputs_.lights[l];
    termComponents_.emplace_back();
    for (int t = 0; t < LightTermCount; ++t)
    {
      termComponents_.back()[t] = lightTermComponents(scene.lights[l], LightTerm(t));
    }
    // Only a light whose specular term some array needs, and can be other than 0, has its lobe
    // evaluated (or integrated).
    const bool needsSpecular = hasSpecularTerm(scene) && (out[int(LightTerm::Specular)] || totalSpecular);
    EvaluationContext context;
    context.lineOfSight = scene.viewer.lineOfSight();
    context.distantFrom = method.distantFrom;
    context.targets = method.targets;
    context.lightIndex = l;
    context.lobe = LobeModel{ needsSpecular ? specularModel_ : SpecularModel::None, m.shininess };
    const LightEvaluation evaluation = prepareEvaluation(scene.lights[l].source, context);
    // Every form the kernel evaluates has its case here: a new one does not compile until it does.
    std::visit(Overloaded{ [&](const AmbientEvaluation& ambient) { ambientLight += ambient.radiance; },
                 [&](const DistributedEvaluation& distributed)
                 {
                   if (method.targets.any() && l < inputs_.lightHiddenSamples.size() && inputs_.lightHiddenSamples[l])
                   {
                     // A fixed count's bits hold no rounds: the visibility step estimates such a light.
                     throw std::logic_error("light '" + scene.lights[l].name +
                       "' is drawn to a target: give its shadowed terms, not hidden samples");
                   }
                   distributedLights_.push_back(prepareDistributed(distributed, out, m, needsSpecular,
                     l < inputs_.lightHiddenSamples.size() ? inputs_.lightHiddenSamples[l] : nullptr,
                     l < inputs_.lightShadowedTerms.size() ? inputs_.lightShadowedTerms[l] : nullptr));
                   distributedLights_.back().shortOfTarget =
                     l < outputs_.shortOfTarget.size() ? outputs_.shortOfTarget[l] : nullptr;
                   distributedLights_.back().transferComponents = termComponents_.back()[int(LightTerm::ShTransfer)];
                 },
                 [&](const LocalEvaluation& local)
                 {
                   lights_.push_back(prepareLocal(local, out, m, needsSpecular, method.pow));
                   lights_.back().visibility =
                     l < inputs_.lightVisibility.size() ? inputs_.lightVisibility[l] : nullptr;
                   if (const LightColors* colors = inputs_.lightColors)
                   {
                     lights_.back().diffuseColor = toVec<T>(colors->diffuse.at(l));
                     lights_.back().specularColor = toVec<T>(colors->specular.at(l));
                   }
                 } },
      evaluation);
  }
  ambient_ = toVec<T>(inputs_.lightColors ? inputs_.lightColors->ambient : m.ka * ambientLight);
  needsViewer_ = twoSided_ || outputs_.flags != nullptr ||
    std::any_of(lights_.begin(), lights_.end(),
      [](const PreparedLight& light)
      { return light.needsSpecular || light.needsReflection || light.needsHalfVector; }) ||
    std::any_of(distributedLights_.begin(), distributedLights_.end(),
      [](const DistributedLightSlot& light) { return light.needsSpecular; });
}

template<typename T>
void ShadingKernel<T>::prepareNormals(const VertexBlock<T>& b, Workspace& w) const
{
  const std::size_t count = b.count;
  std::size_t nonFinite = 0;
  for (std::size_t k = 0; k < count; ++k)
  {
    nonFinite += isFiniteVertex(b, k) ? 0 : 1;
  }
  w.nonFinite = nonFinite;
  std::size_t overflowing = 0;
  for (std::size_t k = 0; k < count; ++k)
  {
    const T length2 = b.nx[k] * b.nx[k] + b.ny[k] * b.ny[k] + b.nz[k] * b.nz[k];
    const bool usable = length2 > degenerateNormalLength2<T>;
    const T length = std::sqrt(usable ? length2 : T(1));
    w.nx[k] = usable ? b.nx[k] / length : T(0);
    w.ny[k] = usable ? b.ny[k] / length : T(0);
    w.nz[k] = usable ? b.nz[k] / length : T(0);
    w.flags[k] = usable ? 0 : FlagDegenerateNormal;
    overflowing += length2 > std::numeric_limits<T>::max() ? 1 : 0;
  }
  // A finite normal whose squared length overflows (a component above 1.8e19 in float32) is
  // normalised again, scaled by its largest component first; a separate pass, since such
  // normals are rare and a branch in the loop above would stop it vectorising.
  for (std::size_t k = 0; overflowing > 0 && k < count; ++k)
  {
    const T length2 = b.nx[k] * b.nx[k] + b.ny[k] * b.ny[k] + b.nz[k] * b.nz[k];
    if (length2 > std::numeric_limits<T>::max() && isFiniteVertex(b, k))
    {
      const T scale = std::max({ std::abs(b.nx[k]), std::abs(b.ny[k]), std::abs(b.nz[k]) });
      const T x = b.nx[k] / scale, y = b.ny[k] / scale, z = b.nz[k] / scale;
      const T length = std::sqrt(x * x + y * y + z * z);
      w.nx[k] = x / length;
      w.ny[k] = y / length;
      w.nz[k] = z / length;
      --overflowing;
    }
  }
}

template<typename T>
void ShadingKernel<T>::loadMaterial(const VertexBlock<T>& b, Workspace& w) const
{
  auto load = [&](MaterialCoefficient c, std::array<Lane<T>, 3>& lanes)
  {
    if (const T* values = vertexMaterial_[int(c)])
    {
      for (std::size_t k = 0; k < b.count; ++k)
      {
        for (int channel = 0; channel < 3; ++channel)
        {
          lanes[channel][k] = values[3 * (b.first + k) + channel];
        }
      }
    }
  };
  load(MaterialCoefficient::Ambient, w.ka);
  load(MaterialCoefficient::Diffuse, w.kd);
  load(MaterialCoefficient::Specular, w.ks);
  for (const auto& [c, lane] : { std::pair{ MaterialCoefficient::Metallic, &w.metallic },
         std::pair{ MaterialCoefficient::Roughness, &w.roughness } })
  {
    if (const T* values = vertexMaterial_[int(c)])
    {
      std::copy_n(values + b.first, b.count, lane->begin());
    }
  }
  if (microfacet_ && perVertexFresnel())
  {
    // A base colour or metallic factor per vertex gives the vertex its own F0 and F90
    // (docs/vtk-renderer.md section 11.1), the same for every light.
    const bool ownBase = perVertex(MaterialCoefficient::Diffuse),
               ownMetallic = perVertex(MaterialCoefficient::Metallic);
    for (std::size_t k = 0; k < b.count; ++k)
    {
      const double metallic = ownMetallic ? double(w.metallic[k]) : microfacetMaterial_.metallic;
      const Rgb f0 = reflectanceAtNormalIncidence(
        dielectricReflectance_, metallic, ownBase ? Rgb(coefficientAt(w.kd, k)) : microfacetMaterial_.baseColor);
      const Rgb f90 = reflectanceAtGrazingIncidence(metallic, microfacetMaterial_.edgeTint, f0);
      for (int c = 0; c < 3; ++c)
      {
        w.normalFresnel[c][k] = T(f0[c]);
        w.grazingFresnel[c][k] = T(f90[c]);
      }
    }
  }
  if (const T* eta = vertexMaterial_[int(MaterialCoefficient::Shininess)])
  {
    std::copy_n(eta + b.first, b.count, w.shininess.begin());
  }
}

template<typename T>
void ShadingKernel<T>::prepareViewer(const VertexBlock<T>& b, Workspace& w) const
{
  const std::size_t count = b.count;
  if (!needsViewer_)
  {
    return;
  }
  if (localViewer_)
  {
    const std::size_t atViewer = unitVectorsFrom(viewerPosition_, b, w.vx, w.vy, w.vz, w.distance);
    // A vertex at the camera has no direction to it; it is seen head-on, along its normal.
    replaceZeroLengthByNormal(atViewer, count, w.distance, w.vx, w.vy, w.vz, w);
  }
  else
  {
    std::fill_n(w.vx.begin(), count, towardViewer_.x);
    std::fill_n(w.vy.begin(), count, towardViewer_.y);
    std::fill_n(w.vz.begin(), count, towardViewer_.z);
  }
  if (twoSided_)
  {
    for (std::size_t k = 0; k < count; ++k)
    {
      const bool turned = turnsNormalRound(w.nx[k] * w.vx[k] + w.ny[k] * w.vy[k] + w.nz[k] * w.vz[k], shadedSide_);
      const T sign = turned ? T(-1) : T(1);
      w.nx[k] *= sign;
      w.ny[k] *= sign;
      w.nz[k] *= sign;
      w.flags[k] |= turned ? FlagNormalFlipped : 0;
    }
  }
}

template<typename T>
void ShadingKernel<T>::sampleLight(const PreparedLight& light, const VertexBlock<T>& b, Workspace& w) const
{
  const std::size_t count = b.count;
  if (light.geometry == LocalEvaluation::Geometry::Distant)
  {
    std::fill_n(w.sx.begin(), count, light.toLight.x);
    std::fill_n(w.sy.begin(), count, light.toLight.y);
    std::fill_n(w.sz.begin(), count, light.toLight.z);
    std::fill_n(w.distance.begin(), count, light.distance);
    std::fill_n(w.attenuation.begin(), count, light.attenuation);
    std::fill_n(w.spotFactor.begin(), count, T(1));
    return;
  }
  const T minDistance = T(light.attenuationModel.minDistance);
  const std::size_t atLight = unitVectorsFrom(light.position, b, w.sx, w.sy, w.sz, w.distance);
  // At d = 0 the direction to the light is undefined; the light is taken to shine along the
  // normal, the limit of a light approaching the surface head-on.
  replaceZeroLengthByNormal(atLight, count, w.distance, w.sx, w.sy, w.sz, w);
  for (std::size_t k = 0; k < count; ++k)
  {
    w.flags[k] |= w.distance[k] <= minDistance ? FlagLightAtMinimumDistance : 0;
  }
  // One loop per model, so that the model's branch is outside the loop.
  const Attenuation& a = light.attenuationModel;
  auto attenuate = [&](auto falloff)
  {
    for (std::size_t k = 0; k < count; ++k)
    {
      w.attenuation[k] = falloff(std::max(w.distance[k], minDistance));
    }
  };
  switch (a.model)
  {
    case AttenuationModel::None: std::fill_n(w.attenuation.begin(), count, T(1)); break;
    case AttenuationModel::Inverse: attenuate([](T d) { return inverseFalloff(d); }); break;
    case AttenuationModel::InverseSquare: attenuate([](T d) { return inverseSquareFalloff(d); }); break;
    case AttenuationModel::ConstantLinearQuadratic:
      attenuate([k0 = T(a.constant), k1 = T(a.linear), k2 = T(a.quadratic)](T d)
        { return constantLinearQuadraticFalloff(k0, k1, k2, d); });
      break;
    case AttenuationModel::GltfRange:
      attenuate([range = T(a.range)](T d) { return gltfRangeFalloff(range, d); });
      break;
  }
  if (light.geometry == LocalEvaluation::Geometry::Spot)
  {
    const Vec3<T>& axis = light.axis;
    for (std::size_t k = 0; k < count; ++k)
    {
      w.spotFactor[k] = light.cone.factor(-(w.sx[k] * axis.x + w.sy[k] * axis.y + w.sz[k] * axis.z));
    }
  }
  else
  {
    std::fill_n(w.spotFactor.begin(), count, T(1));
  }
}

template<typename T>
void ShadingKernel<T>::addLight(const PreparedLight& light, const VertexBlock<T>& b, Workspace& w) const
{
  const std::size_t count = b.count;
  sampleLight(light, b, w);
  for (std::size_t k = 0; k < count; ++k)
  {
    const T cosIncidence = w.nx[k] * w.sx[k] + w.ny[k] * w.sy[k] + w.nz[k] * w.sz[k];
    w.cosIncidence[k] = cosIncidence;
    w.flags[k] |= cosIncidence > T(0) ? 0 : FlagLightBelowHorizon;
    w.diffuse[k] = lambertFactor(cosIncidence) * (w.attenuation[k] * w.spotFactor[k]);
  }
  // The viewer of the specular term: v, or the light itself for VTK's lone headlight.
  const Lane<T>& svx = specularViewerIsLight_ ? w.sx : w.vx;
  const Lane<T>& svy = specularViewerIsLight_ ? w.sy : w.vy;
  const Lane<T>& svz = specularViewerIsLight_ ? w.sz : w.vz;
  if (light.needsReflection)
  {
    for (std::size_t k = 0; k < count; ++k)
    {
      const Vec3<T> r =
        reflectAboutNormal(Vec3<T>(w.sx[k], w.sy[k], w.sz[k]), Vec3<T>(w.nx[k], w.ny[k], w.nz[k]), w.cosIncidence[k]);
      w.rx[k] = r.x;
      w.ry[k] = r.y;
      w.rz[k] = r.z;
      w.rDotV[k] = glm::dot(r, Vec3<T>(svx[k], svy[k], svz[k]));
    }
  }
  if (light.needsHalfVector)
  {
    for (std::size_t k = 0; k < count; ++k)
    {
      // Undefined where s = -v: then h = 0, so n.h = 0.
      bool defined = false;
      const Vec3<T> h = halfVectorOrZero(Vec3<T>(w.sx[k], w.sy[k], w.sz[k]), Vec3<T>(svx[k], svy[k], svz[k]), defined);
      w.hx[k] = h.x;
      w.hy[k] = h.y;
      w.hz[k] = h.z;
      w.nDotH[k] = glm::dot(Vec3<T>(w.nx[k], w.ny[k], w.nz[k]), h);
      w.halfVectorDefined[k] = defined ? T(1) : T(0);
      w.flags[k] |= defined ? 0 : FlagHalfVectorUndefined;
    }
  }
  if (microfacet_)
  {
    addMicrofacetTerms(light, b, w);
  }
  else
  {
    addLectureTerms(light, b, w);
  }
  if (light.out[int(LightTerm::IncidenceAngle)])
  {
    // atan2 is the costliest term here: evaluated only when its array was asked for.
    for (std::size_t k = 0; k < count; ++k)
    {
      w.incidenceAngle[k] =
        incidenceAngleDegrees(Vec3<T>(w.nx[k], w.ny[k], w.nz[k]), Vec3<T>(w.sx[k], w.sy[k], w.sz[k]));
    }
  }
}

template<typename T>
void ShadingKernel<T>::addLectureTerms(const PreparedLight& light, const VertexBlock<T>& b, Workspace& w) const
{
  const std::size_t count = b.count;
  applyVisibility(light.visibility, b, w.diffuse);
  const RgbLanes<T> diffuse = perVertex(MaterialCoefficient::Diffuse)
    ? timesCoefficient(sameLanes(w.diffuse), w.kd, count, w.diffuseRgb)
    : sameLanes(w.diffuse);
  addTimesColor(diffuse, light.diffuseColor, count, w.diffuseR, w.diffuseG, w.diffuseB);
  if (light.needsSpecular)
  {
    specularLobes(light, count, w);
    applyVisibility(light.visibility, b, w.specular);
    const RgbLanes<T> specular = perVertex(MaterialCoefficient::Specular)
      ? timesCoefficient(sameLanes(w.specular), w.ks, count, w.specularRgb)
      : sameLanes(w.specular);
    addTimesColor(specular, light.specularColor, count, w.specularR, w.specularG, w.specularB);
  }
}

template<typename T>
void ShadingKernel<T>::addMicrofacetTerms(const PreparedLight& light, const VertexBlock<T>& b, Workspace& w) const
{
  // docs/vtk-renderer.md section 11.2, VTK's PBR light loop: every cosine clamped to [1e-5, 1],
  // diffuse (1 - m)(1 - F) base / pi and specular D V F, each times the light's radiance and n.s.
  // The light's diffuse colour holds its radiance x (1 - m) base / pi, its specular colour the
  // radiance; the lanes hold the rest, channel by channel. A base colour per vertex (kd's
  // lanes) multiplies the diffuse part, as 1 - m does for a metallic factor per vertex; either
  // gives the vertex its own F0 and F90 (loadMaterial). A roughness per vertex is D's and V's.
  const std::size_t count = b.count;
  const bool perVertexBase = perVertex(MaterialCoefficient::Diffuse);
  const bool perVertexMetallic = perVertex(MaterialCoefficient::Metallic);
  const bool perVertexRoughness = perVertex(MaterialCoefficient::Roughness);
  const bool ownFresnel = perVertexFresnel();
  for (std::size_t k = 0; k < count; ++k)
  {
    const T nDotV = vtkClampedCosine(w.nx[k] * w.vx[k] + w.ny[k] * w.vy[k] + w.nz[k] * w.vz[k]);
    const T nDotL = vtkClampedCosine(w.cosIncidence[k]);
    const T hDotL = vtkClampedCosine(w.hx[k] * w.sx[k] + w.hy[k] * w.sy[k] + w.hz[k] * w.sz[k]);
    const T roughness = perVertexRoughness ? w.roughness[k] : roughness_;
    w.ggxDistribution[k] = ggxDistribution(vtkClampedCosine(w.nDotH[k]), roughness);
    w.smithVisibility[k] = smithCorrelatedVisibility(nDotV, nDotL, roughness);
    // A degenerate normal faces nothing (docs/formulas.md section 16.6), though VTK's clamps
    // would light it at n.s = 1e-5.
    const T facing = (w.flags[k] & FlagDegenerateNormal) ? T(0) : T(1);
    const T radiance = facing * nDotL * (w.attenuation[k] * w.spotFactor[k]);
    const T specular = w.ggxDistribution[k] * w.smithVisibility[k] * radiance;
    const T dielectricShare = perVertexMetallic ? T(1) - w.metallic[k] : T(1);
    for (int c = 0; c < 3; ++c)
    {
      const T fresnel = ownFresnel ? schlickFresnel(w.normalFresnel[c][k], w.grazingFresnel[c][k], hDotL)
                                   : schlickFresnel(normalFresnel_[c], grazingFresnel_[c], hDotL);
      w.fresnel[c][k] = fresnel;
      w.diffuseRgb[c][k] = (T(1) - fresnel) * radiance * ((perVertexBase ? w.kd[c][k] : T(1)) * dielectricShare);
      w.specularRgb[c][k] = fresnel * specular;
    }
  }
  for (int c = 0; c < 3; ++c)
  {
    applyVisibility(light.visibility, b, w.diffuseRgb[c]);
    applyVisibility(light.visibility, b, w.specularRgb[c]);
  }
  addTimesColor(lanesOf(w.diffuseRgb), light.diffuseColor, count, w.diffuseR, w.diffuseG, w.diffuseB);
  if (light.needsSpecular)
  {
    addTimesColor(lanesOf(w.specularRgb), light.specularColor, count, w.specularR, w.specularG, w.specularB);
  }
}

template<typename T>
void ShadingKernel<T>::specularLobes(const PreparedLight& light, std::size_t count, Workspace& w) const
{
  // docs/formulas.md sections 4, 5 and 16.1: the lobe cos^eta, cos = r.v (Phong) or n.h
  // (Blinn-Phong), clamped to 0 and only on lit vertices (Reflectance.h specularLobe), times the
  // light's attenuation and spot factor.
  const bool phong = specularModel_ == SpecularModel::Phong;
  const Lane<T>& cosine = phong ? w.rDotV : w.nDotH;
  auto litAt = [&](std::size_t k) { return (w.cosIncidence[k] > T(0)) & (phong | (w.halfVectorDefined[k] > T(0))); };
  // The approximations, and the exact power in float for a whole eta, are vectorised loops:
  // evaluated everywhere, then masked, each in its own loop (one loop doing all ran twice as
  // slow).
  if (perVertex(MaterialCoefficient::Shininess))
  {
    // Each vertex's own eta: a library call per lit vertex (a tolerance's plan keeps the exact pow).
    for (std::size_t k = 0; k < count; ++k)
    {
      w.specular[k] = specularLobe(litAt(k), cosine[k], w.shininess[k]) * (w.attenuation[k] * w.spotFactor[k]);
    }
    return;
  }
  Lane<T>& lobe = w.specular;
  auto powersOfClampedCosines = [&](auto&& raiseAll)
  {
    for (std::size_t k = 0; k < count; ++k)
    {
      lobe[k] = std::max(cosine[k], T(0));
    }
    raiseAll();
    for (std::size_t k = 0; k < count; ++k)
    {
      w.specular[k] = (litAt(k) ? lobe[k] : T(0)) * (w.attenuation[k] * w.spotFactor[k]);
    }
  };
  if (light.pow != PowMethod::Exact)
  {
    powersOfClampedCosines(
      [&]
      {
        withPowMethod(light.pow, shininess_,
          [&](auto power)
          {
            for (std::size_t k = 0; k < count; ++k)
            {
              lobe[k] = power(lobe[k]);
            }
          });
      });
    return;
  }
  if constexpr (std::is_same_v<T, float>)
  {
    if (isWholeExponent(shininess_))
    {
      powersOfClampedCosines([&] { wholePowers(lobe.data(), lobe.data(), count, unsigned(shininess_)); });
      return;
    }
  }
  // A library call per vertex: skipped where the vertex is unlit.
  for (std::size_t k = 0; k < count; ++k)
  {
    w.specular[k] = specularLobe(litAt(k), cosine[k], shininess_) * (w.attenuation[k] * w.spotFactor[k]);
  }
}

template<typename T>
void ShadingKernel<T>::storeLight(const PreparedLight& light, const VertexBlock<T>& b, const Workspace& w) const
{
  const auto& out = light.out;
  const std::size_t first = b.first;
  const std::size_t count = b.count;
  store(out[int(LightTerm::ToLight)], first, count, w.sx, w.sy, w.sz);
  store(out[int(LightTerm::Distance)], first, count, w.distance);
  store(out[int(LightTerm::Attenuation)], first, count, w.attenuation);
  store(out[int(LightTerm::SpotFactor)], first, count, w.spotFactor);
  store(out[int(LightTerm::CosIncidence)], first, count, w.cosIncidence);
  store(out[int(LightTerm::IncidenceAngle)], first, count, w.incidenceAngle);
  store(out[int(LightTerm::Reflection)], first, count, w.rx, w.ry, w.rz);
  store(out[int(LightTerm::RDotV)], first, count, w.rDotV);
  store(out[int(LightTerm::HalfVector)], first, count, w.hx, w.hy, w.hz);
  store(out[int(LightTerm::NDotH)], first, count, w.nDotH);
  store(out[int(LightTerm::GgxDistribution)], first, count, w.ggxDistribution);
  store(out[int(LightTerm::SmithVisibility)], first, count, w.smithVisibility);
  store(out[int(LightTerm::SchlickFresnel)], first, count, w.fresnel[0], w.fresnel[1], w.fresnel[2]);
  // The lanes that hold a term channel by channel: a material from arrays, or the microfacet model's F.
  const RgbLanes<T> diffuse =
    perVertex(MaterialCoefficient::Diffuse) || microfacet_ ? lanesOf(w.diffuseRgb) : sameLanes(w.diffuse);
  store(out[int(LightTerm::Diffuse)], first, count, diffuse.r, diffuse.g, diffuse.b, light.diffuseColor);
  if (light.needsSpecular)
  {
    const RgbLanes<T> specular =
      perVertex(MaterialCoefficient::Specular) || microfacet_ ? lanesOf(w.specularRgb) : sameLanes(w.specular);
    store(out[int(LightTerm::Specular)], first, count, specular.r, specular.g, specular.b, light.specularColor);
  }
  else if (T* specular = out[int(LightTerm::Specular)])
  {
    std::fill_n(specular + 3 * first, 3 * count, T(0)); // no specular model, or a black ks
  }
  if (T* visibility = out[int(LightTerm::Visibility)])
  {
    for (std::size_t k = 0; k < count; ++k)
    {
      visibility[first + k] = light.visibility ? T(light.visibility[first + k]) : T(1); // 1: no rays were cast
    }
  }
}

template<typename T>
void ShadingKernel<T>::estimateDistributedLight(
  const DistributedLightSlot& light, const VertexBlock<T>& b, Workspace& w) const
{
  const auto& out = light.out;
  auto storeRgb = [&](LightTerm term, std::size_t i, const Rgb& value)
  {
    if (T* array = out[int(term)])
    {
      array[3 * i] = T(value.x);
      array[3 * i + 1] = T(value.y);
      array[3 * i + 2] = T(value.z);
    }
  };
  // A transfer vector's light.transferComponents coefficients.
  auto storeCoefficients = [&](LightTerm term, std::size_t i, const ShBasis& values)
  {
    if (T* array = out[int(term)])
    {
      const std::size_t components = std::size_t(light.transferComponents);
      std::transform(
        values.begin(), values.begin() + components, array + components * i, [](double value) { return T(value); });
    }
  };
  for (std::size_t k = 0; k < b.count; ++k)
  {
    DistributedTerms terms;
    // A vertex without a usable normal faces nothing (and its non-finite inputs are zeroed
    // after the block).
    if (isFiniteVertex(b, k) && !(w.flags[k] & FlagDegenerateNormal))
    {
      SurfacePoint point;
      point.position = { b.px[k], b.py[k], b.pz[k] };
      point.normal = { w.nx[k], w.ny[k], w.nz[k] };
      point.toViewer = needsViewer_ ? glm::dvec3(w.vx[k], w.vy[k], w.vz[k]) : glm::dvec3(0.0);
      point.index = inputs_.sampleIds ? static_cast<std::uint64_t>(inputs_.sampleIds[b.first + k]) : b.first + k;
      if (light.shadowedTerms)
      {
        terms = unpackTerms(light.shadowedTerms + std::size_t(packedTermsSize) * (b.first + k));
      }
      else
      {
        terms = light.hiddenSamples
          ? light.shadowed->estimate(point, { light.hiddenSamples + std::size_t(light.hiddenWords) * (b.first + k) })
          : light.estimator->estimate(point);
      }
    }
    if (!light.irradiance)
    {
      w.irradianceR[k] = T(terms.irradiance.x);
      w.irradianceG[k] = T(terms.irradiance.y);
      w.irradianceB[k] = T(terms.irradiance.z);
    }
    w.integralR[k] = T(terms.specular.x);
    w.integralG[k] = T(terms.specular.y);
    w.integralB[k] = T(terms.specular.z);
    const std::size_t i = b.first + k;
    const Rgb kd = perVertex(MaterialCoefficient::Diffuse) ? Rgb(coefficientAt(w.kd, k)) : light.kd;
    const Rgb ks = perVertex(MaterialCoefficient::Specular) ? Rgb(coefficientAt(w.ks, k)) : light.ks;
    w.sampledError[k] += glm::max(kd, Rgb(1.0)) * terms.irradianceStdError + ks * terms.specularStdError;
    storeRgb(LightTerm::IrradianceStdError, i, terms.irradianceStdError);
    storeRgb(LightTerm::SpecularStdError, i, ks * terms.specularStdError);
    if (T* visibility = out[int(LightTerm::Visibility)])
    {
      visibility[i] = T(terms.visibility);
    }
    if (T* visibilityError = out[int(LightTerm::VisibilityStdError)])
    {
      visibilityError[i] = T(terms.visibilityStdError);
    }
    if (T* shortOfTarget = out[int(LightTerm::ShortOfTarget)])
    {
      shortOfTarget[i] = terms.shortOfTarget ? T(1) : T(0);
    }
    if (light.shortOfTarget)
    {
      light.shortOfTarget[i] = terms.shortOfTarget ? 1 : 0;
    }
    if (std::uint32_t* samples = outputs_.samplesDrawn)
    {
      samples[i] += static_cast<std::uint32_t>(terms.samples);
    }
    storeCoefficients(LightTerm::ShTransfer, i, terms.transfer);
    storeCoefficients(LightTerm::ShTransferStdError, i, terms.transferStdError);
  }
}

template<typename T>
void ShadingKernel<T>::addDistributedLight(
  const DistributedLightSlot& light, const VertexBlock<T>& b, Workspace& w) const
{
  const std::size_t count = b.count;
  if (light.irradiance)
  {
    // R&H eq. 13, the quadratic polynomial of the normal, written out so that GCC vectorises
    // the loop. A degenerate normal was set to 0 and gets no light.
    auto polynomial = [&](Lane<T>& out, int channel)
    {
      // Bound here, not outside: a lambda cannot capture structured bindings before C++20.
      const auto& [xx, yy, zz, xy, xz, yz, cx, cy, cz, constant] = light.irradiance->coefficients;
      for (std::size_t k = 0; k < count; ++k)
      {
        const T x = w.nx[k], y = w.ny[k], z = w.nz[k];
        const T usable = x * x + y * y + z * z > T(0.5) ? T(1) : T(0);
        out[k] = usable *
          (xx[channel] * (x * x) + yy[channel] * (y * y) + zz[channel] * (z * z) + xy[channel] * (x * y) +
            xz[channel] * (x * z) + yz[channel] * (y * z) + cx[channel] * x + cy[channel] * y + cz[channel] * z +
            constant[channel]);
      }
    };
    polynomial(w.irradianceR, 0);
    polynomial(w.irradianceG, 1);
    polynomial(w.irradianceB, 2);
  }
  // kd E and ks S; where kd or ks is per vertex, the light's is 1 and the vertex's multiplies.
  const Vec3<T> kd = toVec<T>(light.kd), ks = toVec<T>(light.ks);
  const auto& out = light.out;
  if (light.runsEstimator())
  {
    estimateDistributedLight(light, b, w);
    const RgbLanes<T> integral = perVertex(MaterialCoefficient::Specular)
      ? timesCoefficient({ w.integralR, w.integralG, w.integralB }, w.ks, count, w.specularRgb)
      : RgbLanes<T>{ w.integralR, w.integralG, w.integralB };
    for (std::size_t k = 0; k < count; ++k)
    {
      w.specularR[k] += ks.x * integral.r[k];
      w.specularG[k] += ks.y * integral.g[k];
      w.specularB[k] += ks.z * integral.b[k];
    }
    store(out[int(LightTerm::Specular)], b.first, count, integral.r, integral.g, integral.b, ks);
  }
  const RgbLanes<T> irradiance = perVertex(MaterialCoefficient::Diffuse)
    ? timesCoefficient({ w.irradianceR, w.irradianceG, w.irradianceB }, w.kd, count, w.diffuseRgb)
    : RgbLanes<T>{ w.irradianceR, w.irradianceG, w.irradianceB };
  for (std::size_t k = 0; k < count; ++k)
  {
    w.diffuseR[k] += kd.x * irradiance.r[k];
    w.diffuseG[k] += kd.y * irradiance.g[k];
    w.diffuseB[k] += kd.z * irradiance.b[k];
  }
  store(out[int(LightTerm::Irradiance)], b.first, count, w.irradianceR, w.irradianceG, w.irradianceB);
  store(out[int(LightTerm::Diffuse)], b.first, count, irradiance.r, irradiance.g, irradiance.b, kd);
  if (!light.runsEstimator())
  {
    // SH with no specular term to sample (no specular model, a black ks, or no array needs
    // it): nothing is sampled, so nothing is short of a target either.
    for (const LightTerm term :
      { LightTerm::Specular, LightTerm::SpecularStdError, LightTerm::IrradianceStdError, LightTerm::ShortOfTarget })
    {
      if (T* array = out[int(term)])
      {
        const int components = termInfo(term).components;
        std::fill_n(array + components * b.first, components * count, T(0));
      }
    }
  }
}

template<typename T>
void ShadingKernel<T>::storeTotals(const VertexBlock<T>& b, Workspace& w) const
{
  const auto& totals = outputs_.totals;
  const std::size_t first = b.first;
  const std::size_t count = b.count;
  // ka La at vertex k, and times its occlusion where there is one.
  auto ambientLightAt = [&](std::size_t k)
  { return perVertex(MaterialCoefficient::Ambient) ? ambient_ * coefficientAt(w.ka, k) : ambient_; };
  auto ambientAt = [&](std::size_t k)
  { return inputs_.ambientOcclusion ? ambientLightAt(k) * T(inputs_.ambientOcclusion[first + k]) : ambientLightAt(k); };
  if (T* ambient = totals[int(TotalTerm::Ambient)])
  {
    for (std::size_t k = 0; k < count; ++k)
    {
      const Vec3<T> a = ambientAt(k);
      std::copy_n(&a.x, 3, ambient + 3 * (first + k));
    }
  }
  store(totals[int(TotalTerm::Diffuse)], first, count, w.diffuseR, w.diffuseG, w.diffuseB);
  store(totals[int(TotalTerm::Specular)], first, count, w.specularR, w.specularG, w.specularB);
  if (T* total = totals[int(TotalTerm::Total)])
  {
    for (std::size_t k = 0; k < count; ++k)
    {
      const Vec3<T> a = ambientAt(k);
      total[3 * (first + k)] = a.x + w.diffuseR[k] + w.specularR[k];
      total[3 * (first + k) + 1] = a.y + w.diffuseG[k] + w.specularG[k];
      total[3 * (first + k) + 2] = a.z + w.diffuseB[k] + w.specularB[k];
    }
  }
  if (double* sampled = outputs_.sampledStandardError)
  {
    for (std::size_t k = 0; k < count; ++k)
    {
      const Rgb occlusion = inputs_.ambientOcclusionStdError
        ? glm::max(Rgb(ambientLightAt(k)), Rgb(1.0)) * double(inputs_.ambientOcclusionStdError[first + k])
        : Rgb(0.0);
      sampled[first + k] = largestComponent(w.sampledError[k] + occlusion);
    }
  }
  if (outputs_.flags && inputs_.flags)
  {
    for (std::size_t k = 0; k < count; ++k)
    {
      w.flags[k] |= inputs_.flags[first + k];
    }
  }
  if (outputs_.flags)
  {
    std::copy_n(w.flags.begin(), count, outputs_.flags + first);
  }
}

template<typename T>
void ShadingKernel<T>::shadeBlock(const VertexBlock<T>& b) const
{
  Workspace w;
  const std::size_t count = b.count;
  for (Lane<T>* sum : { &w.diffuseR, &w.diffuseG, &w.diffuseB, &w.specularR, &w.specularG, &w.specularB })
  {
    std::fill_n(sum->begin(), count, T(0));
  }
  std::fill_n(w.sampledError.begin(), count, Rgb(0.0));
  prepareNormals(b, w);
  loadMaterial(b, w);
  // v costs a square root and a division per vertex: only when a term or the flags need it.
  prepareViewer(b, w);
  for (const PreparedLight& light : lights_)
  {
    addLight(light, b, w);
    storeLight(light, b, w);
  }
  for (const DistributedLightSlot& light : distributedLights_)
  {
    addDistributedLight(light, b, w);
  }
  storeTotals(b, w);
  if (w.nonFinite == 0)
  {
    return;
  }
  // A NaN or Inf coordinate: every output of that vertex is 0 and its only flag says why.
  for (std::size_t k = 0; k < count; ++k)
  {
    const std::size_t i = b.first + k;
    if (isFiniteVertex(b, k))
    {
      continue;
    }
    for (std::size_t l = 0; l < outputs_.lights.size(); ++l)
    {
      for (int t = 0; t < LightTermCount; ++t)
      {
        const int components = termComponents_[l][t];
        if (T* array = outputs_.lights[l][t])
        {
          std::fill_n(array + components * i, components, T(0));
        }
      }
    }
    for (T* total : outputs_.totals)
    {
      if (total)
      {
        std::fill_n(total + 3 * i, 3, T(0));
      }
    }
    if (outputs_.flags)
    {
      outputs_.flags[i] = FlagNonFiniteInput;
    }
  }
}

template class ShadingKernel<float>;
template class ShadingKernel<double>;
}
