#include "MethodChoice.h"

#include "Precision.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <stdexcept>

namespace shadelab
{
namespace
{
constexpr double unbounded = std::numeric_limits<double>::infinity();

/// The unit roundoff u: one rounding changes a value by at most u times its size.
double unitRoundoff(Precision precision)
{
  return precision == Precision::Float32 ? 0x1p-24 : 0x1p-53;
}

/// The largest attenuation at any vertex: every model falls with distance, and no vertex is
/// nearer than D - R to a light D from the centre (attenuationAt clamps to min_distance).
double peakAttenuation(const LightSource& source, const MeshExtent& mesh)
{
  const glm::dvec3* position = positionOf(source);
  if (!position)
  {
    return 1.0;
  }
  const double nearest = vectorLength(*position - mesh.centre) - mesh.radius;
  return attenuationAt(*attenuationOf(source), std::max(nearest, 0.0));
}

double diffusePeak(const LightSource& source, const Material& m)
{
  return largestComponent(emittedColor(source) * m.kd);
}

double ambientPeak(const LightSource& source, const Material& m)
{
  return largestComponent(emittedColor(source) * m.ka);
}

double specularPeak(const LightSource& source, const Material& m)
{
  return largestComponent(emittedColor(source) * m.ks);
}

bool specularComputed(const Scene& scene, const ArrayRequest& request, std::size_t light)
{
  return evaluatedSpecularModel(scene) != SpecularModel::None &&
    (request.lights[light][int(LightTerm::Specular)] || request.totals[int(TotalTerm::Specular)] ||
      request.totals[int(TotalTerm::Total)]);
}

/// Whether any of the light's geometric arrays (s, d, attenuation, ..., n.h) was requested:
/// the distant approximation would replace them by constants.
bool geometryRequested(const ArrayRequest& request, std::size_t light)
{
  const auto& terms = request.lights[light];
  return std::any_of(terms.begin(), terms.begin() + int(LightTerm::Diffuse), [](bool on) { return on; });
}

/// A relative error in a direction computed from coordinates: the offset's components carry
/// rounding of about u (|p| + |target|) each, relative to a length of at least `nearest`.
double directionError(double u, double reach, const glm::dvec3& target, double nearest)
{
  return nearest > 0 ? 4 * u * (reach + largestComponent(target)) / nearest : unbounded;
}

/// The ambient occlusion's share of what the tolerance left (`left`), and how it meets it.
OcclusionChoice chooseOcclusion(const Scene& scene, double left)
{
  OcclusionChoice choice;
  double ambient = 0;
  for (const NamedLight& light : scene.lights)
  {
    ambient += isAmbient(light.source) ? ambientPeak(light.source, scene.material) : 0;
  }
  choice.weightInTotals = std::max(1.0, ambient);
  const double share = left / choice.weightInTotals;
  const AmbientOcclusion& occlusion = *scene.ambientOcclusion;
  if (occlusion.raysFromTolerance)
  {
    choice.target = SamplingTarget{ share, occlusion.maxRays };
    choice.predictedError = share;
    return choice;
  }
  choice.predictedError = fixedRaysError(occlusion.sampling.samples);
  if (!(choice.predictedError <= share))
  {
    throw std::invalid_argument("ambient occlusion's " + std::to_string(occlusion.sampling.samples) +
      " rays per vertex can err by up to " + scientific(choice.predictedError) + " (95%), more than the " +
      scientific(share) + " the tolerance leaves it: give \"rays\": \"auto\" (--ambient-occlusion auto) to draw "
      "as many as the tolerance needs, or a larger tolerance");
  }
  return choice;
}
}

double sampledFloat32Error(double largestSampledDifference)
{
  return 2 * largestSampledDifference;
}

double fixedRaysError(int n)
{
  return 1 / std::sqrt(double(n));
}

double distantApproximationError(const PointLight& light, const Material& material, bool specular, const MeshExtent& mesh)
{
  const double D = vectorLength(light.position - mesh.centre);
  const double R = mesh.radius;
  if (!(D > R))
  {
    return unbounded;
  }
  // Every vertex is within R of the centre, so its distance d lies in [D - R, D + R] and its
  // direction s is within an angle asin(R/D) of the centre's s_c: |s - s_c| <= 2 sin(angle/2).
  const double atCentre = attenuationAt(light.attenuation, D);
  const double attenuationChange = std::max(attenuationAt(light.attenuation, D - R) - atCentre,
    atCentre - attenuationAt(light.attenuation, D + R));
  const double directionChange = 2 * std::sin(std::asin(R / D) / 2);
  // Diffuse: |a max(n.s, 0) - a_c max(n.s_c, 0)| <= |a - a_c| + a_c |s - s_c|, as max(., 0)
  // changes by no more than its argument and |n| = 1.
  const double diffuse = diffusePeak(light, material) * (attenuationChange + atCentre * directionChange);
  // Specular: moving s moves the horizon n.s = 0, where a Phong or Blinn-Phong lobe can be 1
  // (a grazing viewer), so a vertex can gain or lose its whole highlight. The only bound is
  // the term's own largest value.
  const double specularTerm = specular ? specularPeak(light, material) * attenuationAt(light.attenuation, D - R) : 0;
  return diffuse + specularTerm;
}

double powApproximationError(double lobeError, const LightSource& light, const Material& material, const MeshExtent& mesh)
{
  return specularPeak(light, material) * peakAttenuation(light, mesh) * lobeError;
}

double arithmeticError(Precision precision, const Scene& scene, const ArrayRequest& request, const MeshExtent& mesh)
{
  const double u = unitRoundoff(precision);
  const Material& m = scene.material;
  // The viewer's direction, as the lights', comes from coordinates.
  double viewerDirectionError = 4 * u;
  if (scene.viewer.position)
  {
    viewerDirectionError = directionError(
      u, mesh.reach, *scene.viewer.position, vectorLength(*scene.viewer.position - mesh.centre) - mesh.radius);
  }
  double error = 0;
  for (std::size_t l = 0; l < scene.lights.size(); ++l)
  {
    const LightSource& source = scene.lights[l].source;
    if (isAmbient(source))
    {
      error += 2 * u * ambientPeak(source, m);
      continue;
    }
    const double attenuation = peakAttenuation(source, mesh);
    double lightDirectionError = 4 * u;
    if (const glm::dvec3* position = positionOf(source))
    {
      const double nearest = vectorLength(*position - mesh.centre) - mesh.radius;
      lightDirectionError = nearest >= attenuationOf(source)->minDistance
        ? directionError(u, mesh.reach, *position, nearest)
        : unbounded;
    }
    // Normalising n, the dot products and the products each round a few times: 16 u of the
    // term's size covers them; a direction error adds itself to n.s.
    error += diffusePeak(source, m) * attenuation * (16 * u + lightDirectionError);
    if (specularComputed(scene, request, l))
    {
      // x^eta turns an error e in x into about eta e; the lobe stays within [0, 1].
      const double cosineError = 16 * u + 3 * lightDirectionError + 2 * viewerDirectionError;
      error += specularPeak(source, m) * attenuation * std::min(1.0, 16 * u + m.shininess * cosineError);
    }
  }
  return error;
}

std::vector<LightMethod> MethodPlan::methods() const
{
  std::vector<LightMethod> methods;
  for (const LightChoice& light : lights)
  {
    methods.push_back(light.method);
  }
  return methods;
}

double MethodPlan::predictedError() const
{
  double sum = arithmeticError;
  for (const LightChoice& light : lights)
  {
    sum += light.predictedError;
  }
  return sum + (occlusion ? occlusion->predictedError * occlusion->weightInTotals : 0);
}

std::vector<std::string> MethodPlan::describe() const
{
  std::vector<std::string> lines;
  lines.push_back(std::string("tolerance ") + scientific(tolerance) + ", predicted error " +
    scientific(predictedError()) + "; arithmetic " + (precision == Precision::Float32 ? "float32" : "float64") +
    " (rounding " + scientific(arithmeticError) + (roundingSampled ? ", measured on a sample of the points" : "") + ")");
  for (const LightChoice& light : lights)
  {
    std::string line = light.name + ": ";
    std::vector<std::string> parts;
    if (light.method.distantFrom)
    {
      const glm::dvec3& c = *light.method.distantFrom;
      parts.push_back("as distant from (" + scientific(c.x) + ", " + scientific(c.y) + ", " + scientific(c.z) + ")");
    }
    if (light.method.pow != PowMethod::Exact)
    {
      parts.push_back(powMethodName(light.method.pow));
    }
    for (std::size_t p = 0; p < parts.size(); ++p)
    {
      line += (p ? ", " : "") + parts[p];
    }
    line += parts.empty() ? "exact" : ", predicted error " + scientific(light.predictedError);
    if (!light.why.empty())
    {
      line += " (" + light.why + ")";
    }
    lines.push_back(line);
  }
  if (occlusion && occlusion->target)
  {
    const SamplingTarget& target = *occlusion->target;
    lines.push_back("ambient occlusion: rays auto, within " + scientific(target.error) +
      " at 95% (standard error at most " + scientific(target.standardError()) + "), " +
      std::to_string(target.minimum()) + " to " + std::to_string(target.maximum) + " rays per vertex");
  }
  else if (occlusion)
  {
    lines.push_back("ambient occlusion: a fixed count of rays, predicted error " + scientific(occlusion->predictedError) +
      " (95%)");
  }
  return lines;
}

MethodPlan chooseMethods(const Scene& scene, const ArrayRequest& request, const MeshExtent& mesh, double tolerance,
  bool float32Allowed, std::optional<double> sampledFloat32Difference)
{
  for (const NamedLight& light : scene.lights)
  {
    if (isDistributed(light.source))
    {
      throw std::invalid_argument("a tolerance cannot be met with light '" + light.name + "' of type \"" +
        lightTypeName(light.source) +
        "\": its error comes from the estimator the scene names, not from arithmetic a tolerance can choose "
        "(Monte Carlo estimators report theirs in *_std_error arrays); shade without a tolerance");
    }
  }
  MethodPlan plan;
  plan.tolerance = tolerance;
  const double deterministic = scene.ambientOcclusion ? tolerance / 10 : tolerance;
  // Each precision's rounding: a priori, or from the sample. float32's sample is taken over
  // the a priori bound, which is usually far above it but does not cover a light switched on or
  // off at a vertex's horizon (docs/formulas.md section 15), which the sample looks for; it is
  // measured against float64, whose own (far smaller) error is added. float64's is the lesser
  // of its bound and the sample's scaled by the unit roundoffs.
  double float32 = float32Allowed ? arithmeticError(Precision::Float32, scene, request, mesh) : unbounded;
  double float64 = arithmeticError(Precision::Float64, scene, request, mesh);
  bool float32Sampled = false, float64Sampled = false;
  if (float32Allowed && sampledFloat32Difference)
  {
    const double sampled = sampledFloat32Error(*sampledFloat32Difference);
    float64Sampled = sampled * 0x1p-29 < float64;
    float64 = std::min(float64, sampled * 0x1p-29);
    float32Sampled = true;
    float32 = sampled + float64;
  }
  plan.precision = float32 <= deterministic ? Precision::Float32 : Precision::Float64;
  plan.arithmeticError = plan.precision == Precision::Float32 ? float32 : float64;
  plan.roundingSampled = plan.precision == Precision::Float32 ? float32Sampled : float64Sampled;
  if (!(plan.arithmeticError <= deterministic))
  {
    throw RoundingAboveTolerance("tolerance " + scientific(tolerance) +
      " is below the predicted float64 rounding error of this scene on this mesh, " +
      scientific(plan.arithmeticError) + (deterministic < tolerance ? ", which may take a tenth of it (the rays take the rest)" : "") +
      ": give a larger tolerance, or none for the exact methods");
  }
  double left = deterministic - plan.arithmeticError;

  struct Candidate
  {
    bool distant;
    PowMethod pow;
  };
  // Cheapest first, as `shadelab-bench` measures them: a pow approximation saves at least as
  // much as the distant approximation (std::pow is a library call per lit vertex, and even the
  // exact power of a whole eta is a pass over the block per bit of eta; the direction and
  // attenuation of a point light are a few vectorised operations).
  const Candidate candidates[] = { { true, PowMethod::Schlick }, { false, PowMethod::Schlick },
    { true, PowMethod::Series }, { false, PowMethod::Series }, { true, PowMethod::Exact },
    { false, PowMethod::Exact } };
  // The lobe's error depends only on the method, the precision and eta (largestPowError
  // remembers it), and is looked up only when a light needs it.
  auto lobeError = [&](PowMethod method)
  {
    const double eta = scene.material.shininess;
    return plan.precision == Precision::Float32 ? largestPowError<float>(method, eta)
                                                : largestPowError<double>(method, eta);
  };
  for (std::size_t l = 0; l < scene.lights.size(); ++l)
  {
    const NamedLight& named = scene.lights[l];
    LightChoice choice;
    choice.name = named.name;
    if (isAmbient(named.source))
    {
      plan.lights.push_back(choice);
      continue;
    }
    const bool specular = specularComputed(scene, request, l);
    const auto* point = std::get_if<PointLight>(&named.source);
    double distantError = unbounded;
    std::string distantWhy;
    if (point && geometryRequested(request, l))
    {
      distantWhy = "not as distant: its direction arrays were requested";
    }
    else if (point)
    {
      distantError = distantApproximationError(*point, scene.material, specular, mesh);
      distantWhy = std::isinf(distantError) ? "not as distant: the light is inside the mesh's bounding sphere"
                                            : "as distant it would err by " + scientific(distantError);
    }
    std::map<PowMethod, double> powError;
    for (const PowMethod method : { PowMethod::Series, PowMethod::Schlick })
    {
      powError[method] = specular ? powApproximationError(lobeError(method), named.source, scene.material, mesh) : unbounded;
    }
    powError[PowMethod::Exact] = 0; // std::pow's own rounding is part of arithmeticError
    for (const Candidate& candidate : candidates)
    {
      if ((candidate.distant && std::isinf(distantError)) || std::isinf(powError[candidate.pow]))
      {
        continue;
      }
      const double error = (candidate.distant ? distantError : 0) + powError[candidate.pow];
      if (error <= left)
      {
        if (candidate.distant)
        {
          choice.method.distantFrom = mesh.centre;
        }
        choice.method.pow = candidate.pow;
        choice.predictedError = error;
        break;
      }
    }
    std::vector<std::string> reasons;
    if (point && !choice.method.distantFrom)
    {
      reasons.push_back(distantWhy);
    }
    if (specular && choice.method.pow != PowMethod::Schlick)
    {
      reasons.push_back("Schlick pow would err by " + scientific(powError[PowMethod::Schlick]));
    }
    if (specular && choice.method.pow == PowMethod::Exact)
    {
      reasons.push_back("series pow by " + scientific(powError[PowMethod::Series]));
    }
    for (std::size_t r = 0; r < reasons.size(); ++r)
    {
      choice.why += (r ? ", " : "") + reasons[r];
    }
    if (!reasons.empty())
    {
      choice.why += "; " + scientific(left) + " of the tolerance was left";
    }
    left -= choice.predictedError;
    plan.lights.push_back(choice);
  }
  if (scene.ambientOcclusion)
  {
    plan.occlusion = chooseOcclusion(scene, tolerance - plan.predictedError());
  }
  return plan;
}
}
