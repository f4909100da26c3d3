#include "ShadingKernel.h"

#include "Reflectance.h"

#include <algorithm>
#include <cmath>

namespace shadelab
{
namespace
{
template <typename T>
Vec3<T> toVec(const glm::dvec3& v)
{
  return Vec3<T>(v);
}

template <typename T>
void store(T* array, std::size_t i, T value)
{
  if (array)
  {
    array[i] = value;
  }
}

template <typename T>
void store(T* array, std::size_t i, const Vec3<T>& value)
{
  if (array)
  {
    array[3 * i] = value.x;
    array[3 * i + 1] = value.y;
    array[3 * i + 2] = value.z;
  }
}

// A normal shorter than this is treated as missing: it comes from degenerate geometry
// (zero-area triangles, isolated points), not from a surface direction.
template <typename T>
constexpr T degenerateNormalLength2 = T(1e-12);

template <typename Light>
Rgb strength(const Light& light)
{
  return light.color * light.intensity;
}
}

template <typename T>
ShadingKernel<T>::ShadingKernel(const Scene& scene, ShadingOutputs<T> outputs)
  : outputs_(std::move(outputs))
{
  const Material& m = scene.material;
  const bool vtk = scene.model == ShadingModel::VtkOpenGL2;
  // REFERENCES.md section 2: VTK's shader uses Phong with sign(df), always flips back faces,
  // and its ambient term is Ka*Ca from the property alone. Its lone-headlight shader takes
  // sf = max(0, n_z)^p: Blinn-Phong with the viewer along the light, where h = s.
  specularModel_ = vtk ? (scene.vtkLoneHeadlight ? SpecularModel::BlinnPhong : SpecularModel::Phong)
                       : m.specular;
  specularViewerIsLight_ = vtk && scene.vtkLoneHeadlight;
  twoSided_ = vtk || m.twoSided;
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
    const LightSource& source = scene.lights[l].source;
    if (const auto* ambient = std::get_if<AmbientLight>(&source))
    {
      ambientLight += strength(*ambient);
      continue;
    }
    PreparedLight light;
    light.out = outputs_.lights[l];
    Rgb color;
    if (const auto* distant = std::get_if<DistantLight>(&source))
    {
      light.toLight = toVec<T>(-unitVector(distant->direction));
      const double lengthFactor = distant->intensityFromLength ? vectorLength(distant->direction) : 1.0;
      color = strength(*distant) * lengthFactor;
    }
    else if (const auto* head = std::get_if<Headlight>(&source))
    {
      light.toLight = toVec<T>(-*scene.viewer.lineOfSight());
      color = strength(*head);
    }
    else if (const auto* point = std::get_if<PointLight>(&source))
    {
      light.kind = Kind::Point;
      light.position = toVec<T>(point->position);
      light.attenuation = point->attenuation;
      color = strength(*point);
    }
    else if (const auto* spot = std::get_if<SpotLight>(&source))
    {
      light.kind = Kind::Spot;
      light.position = toVec<T>(spot->position);
      light.axis = toVec<T>(unitVector(spot->axis));
      light.attenuation = spot->attenuation;
      light.cone = PreparedCone<T>(spot->cone);
      color = strength(*spot);
    }
    light.diffuseColor = toVec<T>(color * m.kd);
    light.specularColor = toVec<T>(color * m.ks);

    const auto& out = light.out;
    light.needsSpecular =
      specularModel_ != SpecularModel::None && (out[int(LightTerm::Specular)] || totalSpecular);
    light.needsReflection = out[int(LightTerm::Reflection)] || out[int(LightTerm::RDotV)] ||
      (light.needsSpecular && specularModel_ == SpecularModel::Phong);
    light.needsHalfVector = out[int(LightTerm::HalfVector)] || out[int(LightTerm::NDotH)] ||
      (light.needsSpecular && specularModel_ == SpecularModel::BlinnPhong);
    lights_.push_back(light);
  }
  ambient_ = toVec<T>(m.ka * ambientLight);
  needsViewer_ = twoSided_ || outputs_.flags != nullptr ||
    std::any_of(lights_.begin(), lights_.end(),
      [](const PreparedLight& light)
      { return light.needsSpecular || light.needsReflection || light.needsHalfVector; });
}

template <typename T>
typename ShadingKernel<T>::LightSample ShadingKernel<T>::sample(
  const PreparedLight& light, const Vec3<T>& position, const Vec3<T>& normal) const
{
  if (light.kind == Kind::Distant)
  {
    return { light.toLight, T(0), T(1), T(1), false };
  }
  const Vec3<T> offset = light.position - position;
  const T distance = glm::length(offset);
  // At d = 0 the direction to the light is undefined; the light is taken to shine along the
  // normal, the limit of a light approaching the surface head-on.
  const Vec3<T> toLight = distance > T(0) ? offset / distance : normal;
  const T spotFactor = light.kind == Kind::Spot ? light.cone.factor(glm::dot(-toLight, light.axis)) : T(1);
  return { toLight, distance, attenuationAt(light.attenuation, distance), spotFactor,
    distance <= T(light.attenuation.minDistance) };
}

template <typename T>
Vec3<T> ShadingKernel<T>::toViewer(const Vec3<T>& position, const Vec3<T>& normal) const
{
  if (!localViewer_)
  {
    return towardViewer_;
  }
  const Vec3<T> offset = viewerPosition_ - position;
  const T distance = glm::length(offset);
  // A vertex at the camera has no direction to it; it is seen head-on, along its normal.
  return distance > T(0) ? offset / distance : normal;
}

template <typename T>
void ShadingKernel<T>::writeZeros(std::size_t i) const
{
  const Vec3<T> zero(0);
  for (const PreparedLight& light : lights_)
  {
    for (int t = 0; t < LightTermCount; ++t)
    {
      if (termInfo(LightTerm(t)).components == 3)
      {
        store(light.out[t], i, zero);
      }
      else
      {
        store(light.out[t], i, T(0));
      }
    }
  }
  for (T* total : outputs_.totals)
  {
    store(total, i, zero);
  }
}

template <typename T>
void ShadingKernel<T>::shadeVertex(std::size_t i, const Vec3<T>& position, const Vec3<T>& rawNormal) const
{
  if (!isFinite(position) || !isFinite(rawNormal))
  {
    writeZeros(i);
    store(outputs_.flags, i, ShadingFlags(FlagNonFiniteInput));
    return;
  }

  ShadingFlags flags = 0;
  const T normalLength2 = glm::dot(rawNormal, rawNormal);
  Vec3<T> n(0);
  if (normalLength2 > degenerateNormalLength2<T>)
  {
    n = rawNormal / std::sqrt(normalLength2);
  }
  else
  {
    flags |= FlagDegenerateNormal;
  }
  // v costs a square root and a division: only when a term or the flags need it.
  const Vec3<T> v = needsViewer_ ? toViewer(position, n) : Vec3<T>(0);
  if (twoSided_ && glm::dot(n, v) < T(0))
  {
    n = -n;
    flags |= FlagNormalFlipped;
  }

  Vec3<T> diffuseSum(0);
  Vec3<T> specularSum(0);
  for (const PreparedLight& light : lights_)
  {
    const LightSample ls = sample(light, position, n);
    const Vec3<T>& s = ls.toLight;
    const T cosIncidence = glm::dot(n, s);
    const bool lit = cosIncidence > T(0);
    const T strength = ls.attenuation * ls.spotFactor;
    flags |= ls.atMinimumDistance ? FlagLightAtMinimumDistance : 0;
    flags |= lit ? 0 : FlagLightBelowHorizon;

    const Vec3<T> diffuse = (lambertFactor(cosIncidence) * strength) * light.diffuseColor;
    const Vec3<T>& specularViewer = specularViewerIsLight_ ? s : v;

    Vec3<T> r(0);
    T rDotV = 0;
    if (light.needsReflection)
    {
      r = reflectAboutNormal(s, n, cosIncidence);
      rDotV = glm::dot(r, specularViewer);
    }
    Vec3<T> h(0);
    T nDotH = 0;
    bool hDefined = true;
    if (light.needsHalfVector)
    {
      hDefined = halfVector(s, specularViewer, h);
      nDotH = glm::dot(n, h);
    }
    else if (outputs_.flags)
    {
      // The flag must not depend on which arrays were asked for.
      hDefined = isHalfVectorDefined(s, specularViewer);
    }
    flags |= hDefined ? 0 : FlagHalfVectorUndefined;
    Vec3<T> specular(0);
    if (light.needsSpecular)
    {
      const T lobe = specularModel_ == SpecularModel::Phong
        ? specularLobe(lit, rDotV, shininess_)
        : specularLobe(lit && hDefined, nDotH, shininess_);
      specular = (lobe * strength) * light.specularColor;
    }
    diffuseSum += diffuse;
    specularSum += specular;

    const auto& out = light.out;
    store(out[int(LightTerm::ToLight)], i, s);
    store(out[int(LightTerm::Distance)], i, ls.distance);
    store(out[int(LightTerm::Attenuation)], i, ls.attenuation);
    store(out[int(LightTerm::SpotFactor)], i, ls.spotFactor);
    store(out[int(LightTerm::CosIncidence)], i, cosIncidence);
    // atan2 is the costliest term here: evaluated only when its array was asked for.
    if (out[int(LightTerm::IncidenceAngle)])
    {
      store(out[int(LightTerm::IncidenceAngle)], i, incidenceAngleDegrees(n, s));
    }
    store(out[int(LightTerm::Reflection)], i, r);
    store(out[int(LightTerm::RDotV)], i, rDotV);
    store(out[int(LightTerm::HalfVector)], i, h);
    store(out[int(LightTerm::NDotH)], i, nDotH);
    store(out[int(LightTerm::Diffuse)], i, diffuse);
    store(out[int(LightTerm::Specular)], i, specular);
  }

  const auto& totals = outputs_.totals;
  store(totals[int(TotalTerm::Ambient)], i, ambient_);
  store(totals[int(TotalTerm::Diffuse)], i, diffuseSum);
  store(totals[int(TotalTerm::Specular)], i, specularSum);
  store(totals[int(TotalTerm::Total)], i, ambient_ + diffuseSum + specularSum);
  store(outputs_.flags, i, flags);
}

template class ShadingKernel<float>;
template class ShadingKernel<double>;
}
