#include "MethodChoice.h"

#include "NumberText.h"
#include "Precision.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <stdexcept>
#include <type_traits>

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

/// The largest attenuation at any vertex: every model falls with distance (attenuationAt
/// clamps to min_distance).
double peakAttenuation(const Scene& scene, std::size_t light, const MeshExtent& mesh, const MeshMeasurements& measured)
{
  const LightSource& source = scene.lights[light].source;
  const glm::dvec3* position = positionOf(source);
  return position ? attenuationAt(*attenuationOf(source), nearestVertexDistance(*position, mesh, measured, light))
                  : 1.0;
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

/// Whether any light's estimates may be sampled to a share of the tolerance.
bool samplesAnyLight(const Scene& scene)
{
  return std::any_of(scene.lights.begin(), scene.lights.end(),
    [](const NamedLight& light) { return samplingOf(light.source) && samplingOf(light.source)->fromTolerance; });
}

/// What a tolerance can bound of a distributed light's estimator: each type answers for its
/// own (LightType.h), so that a distributed type that does not fails to compile here.
ToleranceBounds toleranceBoundsOf(const NamedLight& light, const Material& m)
{
  return std::visit(
    [&](const auto& source) -> ToleranceBounds
    {
      if constexpr (std::decay_t<decltype(source)>::role == LightRole::Distributed)
      {
        return source.toleranceBounds(m, light.shadows);
      }
      else
      {
        throw std::logic_error("light '" + light.name + "' is not integrated over a solid angle: it has no estimator");
      }
    },
    light.source);
}

/// An area light's or a map's choice: its deterministic error charged to what is `left`, and
/// which of its estimates are sampled (their shares come later, drawToShare). Throws
/// std::invalid_argument where the tolerance cannot bound the light.
LightChoice distributedChoice(const NamedLight& light, std::size_t index, const Material& m, bool specular, double left)
{
  LightChoice choice;
  choice.name = light.name;
  const ToleranceBounds bounds = toleranceBoundsOf(light, m);
  // field: the light's field at fault, "estimator" or "samples".
  auto refuse = [&](const std::string& field, const std::string& why)
  {
    throw UnboundedSceneField("/lights/" + std::to_string(index) + "/" + field,
      "a tolerance cannot bound light '" + light.name + "' of type \"" + lightTypeName(light.source) + "\": " + why +
        "; or shade without a tolerance");
  };
  if (!bounds.unbounded.empty())
  {
    refuse("estimator", bounds.unbounded);
  }
  // Under shadows E is sampled whatever the estimator: an exact or SH E is the unshadowed one
  // times the samples' visible fraction.
  choice.sampledIrradiance = bounds.sampledIrradiance || light.shadows;
  choice.sampledSpecular = specular;
  if ((choice.sampledIrradiance || choice.sampledSpecular) && !samplingOf(light.source)->fromTolerance)
  {
    refuse("samples",
      "its Monte Carlo estimates from " + std::to_string(samplingOf(light.source)->samples) +
        " samples have no error bound before they are drawn: give it " + bounds.autoSamples +
        ", which draws each vertex's samples until their standard error meets a share of the tolerance");
  }
  // E's error reaches its own array as it is, and the diffuse term times kd.
  choice.approximationError = bounds.irradianceError * std::max(1.0, largestComponent(m.kd));
  if (!(choice.approximationError <= left))
  {
    refuse("estimator",
      "its spherical-harmonic irradiance can err by " + scientific(choice.approximationError) + ", more than the " +
        scientific(left) +
        " of the tolerance left for it: use \"estimator\": \"monte_carlo\" (--envmap-estimator "
        "monte_carlo) with " +
        bounds.autoSamples);
  }
  choice.predictedError = choice.approximationError;
  return choice;
}

/// The targets of a light's sampled estimates for its share of the tolerance (in the totals'
/// units): the share split between E and S where both are sampled, each divided by kd or ks
/// where those exceed 1 (E's and S's own arrays hold it too).
void drawToShare(const Sampling& sampling, const Material& m, double share, LightChoice& choice)
{
  const double part = share / ((choice.sampledIrradiance ? 1 : 0) + (choice.sampledSpecular ? 1 : 0));
  auto target = [&](double k)
  { return SamplingTarget::atLeast(part / std::max(1.0, k), sampling.samples, sampling.maximum); };
  if (choice.sampledIrradiance)
  {
    choice.method.targets.irradiance = target(largestComponent(m.kd));
  }
  if (choice.sampledSpecular)
  {
    choice.method.targets.specular = target(largestComponent(m.ks));
  }
  choice.predictedError += share;
}

/// How the ambient occlusion meets its share of the tolerance (`share`, in the totals' units).
OcclusionChoice chooseOcclusion(const Scene& scene, double share)
{
  OcclusionChoice choice;
  double ambient = 0;
  for (const NamedLight& light : scene.lights)
  {
    ambient += isAmbient(light.source) ? ambientPeak(light.source, scene.material) : 0;
  }
  choice.weightInTotals = std::max(1.0, ambient);
  const double ownShare = share / choice.weightInTotals;
  const AmbientOcclusion& occlusion = *scene.ambientOcclusion;
  if (occlusion.sampling.fromTolerance)
  {
    choice.target = SamplingTarget::forFraction(ownShare, occlusion.sampling.maximum);
    choice.predictedError = ownShare;
    return choice;
  }
  choice.predictedError = fixedRaysError(occlusion.sampling.samples);
  if (!(choice.predictedError <= ownShare))
  {
    throw UnboundedSceneField("/ambient_occlusion/rays",
      "ambient occlusion's " + std::to_string(occlusion.sampling.samples) + " rays per vertex can err by up to " +
        scientific(choice.predictedError) + " (95%), more than the " + scientific(ownShare) +
        " the tolerance leaves it: give \"rays\": \"auto\" (--ambient-occlusion auto) to draw "
        "as many as the tolerance needs, or a larger tolerance");
  }
  return choice;
}
}

double errorFromSample(double largestSampledDifference)
{
  return 2 * largestSampledDifference;
}

double fixedRaysError(int n)
{
  return 1 / std::sqrt(double(n));
}

double distantApproximationError(
  const PointLight& light, const Material& material, bool specular, const MeshExtent& mesh)
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
  const double attenuationChange =
    std::max(attenuationAt(light.attenuation, D - R) - atCentre, atCentre - attenuationAt(light.attenuation, D + R));
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

double nearestVertexDistance(
  const glm::dvec3& position, const MeshExtent& mesh, const MeshMeasurements& measured, std::size_t light)
{
  const double outsideTheSphere = std::max(vectorLength(position - mesh.centre) - mesh.radius, 0.0);
  return measured.nearestVertexDistance.empty() ? outsideTheSphere
                                                : std::max(outsideTheSphere, measured.nearestVertexDistance[light]);
}

double powApproximationError(
  double lobeError, const Scene& scene, std::size_t light, const MeshExtent& mesh, const MeshMeasurements& measured)
{
  return specularPeak(scene.lights[light].source, scene.material) * peakAttenuation(scene, light, mesh, measured) *
    lobeError;
}

double arithmeticError(Precision precision, const Scene& scene, const ArrayRequest& request, const MeshExtent& mesh,
  const MeshMeasurements& measured)
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
    const double attenuation = peakAttenuation(scene, l, mesh, measured);
    double lightDirectionError = 4 * u;
    if (const glm::dvec3* position = positionOf(source))
    {
      const double nearest = nearestVertexDistance(*position, mesh, measured, l);
      lightDirectionError =
        nearest >= attenuationOf(source)->minDistance ? directionError(u, mesh.reach, *position, nearest) : unbounded;
    }
    // Normalising n, the dot products and the products each round a few times: 16 u of the
    // term's size covers them; a direction error adds itself to n.s.
    error += diffusePeak(source, m) * attenuation * (16 * u + lightDirectionError);
    if (specularComputed(scene, request, l))
    {
      // x^eta turns an error e in x into about eta e; the lobe stays within [0, 1]. A shininess
      // per vertex (from an array) counts at its largest, and unmeasured, at the lobe's full size.
      const double cosineError = 16 * u + 3 * lightDirectionError + 2 * viewerDirectionError;
      const std::optional<double> eta =
        m.arrays[MaterialCoefficient::Shininess] ? measured.largestShininess : std::optional<double>(m.shininess);
      const double lobeError = eta ? std::min(1.0, 16 * u + *eta * cosineError) : 1.0;
      error += specularPeak(source, m) * attenuation * lobeError;
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

namespace
{
/// The direct terms' predicted error: the rounding, each light's, and the occlusion's.
double directError(const MethodPlan& plan)
{
  double sum = plan.arithmeticError;
  for (const LightChoice& light : plan.lights)
  {
    sum += light.predictedError;
  }
  return sum + (plan.occlusion ? plan.occlusion->errorInTotals() : 0);
}
}

double MethodPlan::predictedError() const
{
  const double direct = directError(*this);
  return interreflection ? direct * interreflection->directGrowth() + interreflection->share : direct;
}

double MethodPlan::estimatedError() const
{
  const double direct = directError(*this) - samplingError + estimatedSamplingError.value_or(samplingError);
  if (!interreflection)
  {
    return direct;
  }
  const InterreflectionChoice& indirect = *interreflection;
  return direct * indirect.directGrowth() +
    (indirect.bounces > 0 ? indirect.bouncesLeftOut : indirect.truncationShare()) +
    indirect.estimatedSamplingError.value_or(indirect.samplingShare());
}

std::string InterreflectionChoice::describe() const
{
  return "interreflection: a share of " + scientific(share) + " (" + scientific(truncationShare()) +
    " for the bounces left out, " + scientific(samplingShare()) + " for the gather at 95%); kd up to " +
    withDigits(largestAlbedo, 3) + ", so the direct terms' errors count " + withDigits(directGrowth(), 3) + " times";
}

std::string InterreflectionChoice::describeRun() const
{
  std::string line = "interreflection chose " + countOf(std::size_t(bounces), "bounce") + " (the rest add at most " +
    scientific(bouncesLeftOut) +
    (bouncesLeftOut > truncationShare()
        ? ", above its share: " + std::to_string(bounces) + " bounces is the most a scene may ask for"
        : "") +
    ") and " + std::to_string(samples) + " gather rays per vertex";
  line += samples > firstSamples ? " (after a first run of " + std::to_string(firstSamples) + ")" : "";
  if (estimatedSamplingError)
  {
    line += "; the gather errs by about " + scientific(*estimatedSamplingError) + " at 95% of the vertices" +
      (*estimatedSamplingError > samplingShare()
          ? ", above its share: " + std::to_string(samples) + " rays is the most \"max_samples\" allows"
          : "");
  }
  return line;
}

int gatherRaysWithin(double firstError, int firstRays, double share, int maximum)
{
  int rays = firstRays;
  // The error at 2N rays is the error at N over sqrt(2).
  for (double error = firstError; error > share && 2 * rays <= maximum; error /= std::sqrt(2.0))
  {
    rays *= 2;
  }
  return rays;
}

namespace
{
/// "within E at 95% (standard error at most E/2), N to M <unit> per vertex".
std::string targetText(const SamplingTarget& target, const char* unit)
{
  return "within " + scientific(target.error) + " at 95% (standard error at most " +
    scientific(target.standardError()) + "), " + std::to_string(target.minimum) + " to " +
    std::to_string(target.maximum) + " " + unit + " per vertex";
}
}

std::string SampleCounts::describe(std::size_t vertices) const
{
  const double perVertex = vertices ? 1.0 / double(vertices) : 0.0;
  std::string text;
  for (const auto& [count, noun] :
    { std::pair{ samples, " samples (" }, std::pair{ occlusionRays, " occlusion rays (" } })
  {
    if (count > 0)
    {
      text += (text.empty() ? "" : " and ") + roughCount(count) + noun + roughCount(count * perVertex) + " per vertex)";
    }
  }
  return text.empty() ? "nothing sampled" : text;
}

std::string CostForecast::describe() const
{
  return "forecast from " + std::to_string(pilotVertices) + " of the " + std::to_string(meshVertices) +
    " vertices: about " + counts.describe(meshVertices) + ", " + std::to_string(std::lround(100 * shareShortOfTarget)) +
    "% of the vertices at a maximum short of their target, about " + withDigits(seconds, 2) + " s on " +
    countOf(std::size_t(threads), "thread");
}

std::vector<std::string> MethodPlan::describe() const
{
  std::vector<std::string> lines;
  // What was chosen, then why: the predicted errors of all of it fit the tolerance.
  lines.push_back(std::string("arithmetic ") + (precision == Precision::Float32 ? "float32" : "float64") +
    " (rounding " + scientific(arithmeticError) + (roundingSampled ? ", measured on a sample of the points" : "") +
    ") and the methods below, chosen so that their predicted errors, " + scientific(predictedError()) +
    " in all, stay within the tolerance " + scientific(tolerance));
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
    if (light.approximationError > 0)
    {
      parts.push_back("SH irradiance within " + scientific(light.approximationError));
    }
    for (const auto& [integral, target] :
      { std::pair{ "E", light.method.targets.irradiance }, std::pair{ "S", light.method.targets.specular } })
    {
      if (target)
      {
        parts.push_back(std::string(integral) + " sampled to " + targetText(*target, "samples"));
      }
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
    lines.push_back("ambient occlusion: rays auto, " + targetText(*occlusion->target, "rays"));
  }
  else if (occlusion)
  {
    lines.push_back(
      "ambient occlusion: a fixed count of rays, predicted error " + scientific(occlusion->predictedError) + " (95%)");
  }
  if (interreflection)
  {
    lines.push_back(interreflection->describe());
  }
  if (forecast)
  {
    lines.push_back(forecast->describe());
  }
  if (forecast && forecast->drawn)
  {
    lines.push_back("drew " + forecast->drawn->describe(forecast->meshVertices));
  }
  if (estimatedSamplingError)
  {
    lines.push_back("after sampling: an error of about " + scientific(estimatedError()) + " at 95% of the vertices (" +
      scientific(*estimatedSamplingError) +
      " estimated from their standard errors, where the plan bounds sampling's part by " + scientific(samplingError) +
      ")");
  }
  if (interreflection && interreflection->bounces > 0)
  {
    lines.push_back(interreflection->describeRun());
    lines.push_back("after the bounces: an error of about " + scientific(estimatedError()) + " at 95% of the vertices");
  }
  return lines;
}

namespace
{
/// The precision whose rounding fits `deterministic`, the tolerance's part that is not
/// sampled, and that rounding: a priori, or from the sample. float32's sample is taken over
/// the a priori bound, which is usually far above it but does not cover a light switched on or
/// off at a vertex's horizon (docs/formulas.md section 15), which the sample looks for; it is
/// measured against float64, whose own (far smaller) error is added. float64's is the lesser
/// of its bound and the sample's scaled by the unit roundoffs.
void choosePrecision(MethodPlan& plan, const Scene& scene, const ArrayRequest& request, const MeshExtent& mesh,
  double deterministic, bool float32Allowed, const MeshMeasurements& measured)
{
  double float32 = float32Allowed ? arithmeticError(Precision::Float32, scene, request, mesh, measured) : unbounded;
  double float64 = arithmeticError(Precision::Float64, scene, request, mesh, measured);
  bool float32Sampled = false, float64Sampled = false;
  // The sample is shaded with one shininess: a shininess per vertex keeps the bounds.
  if (float32Allowed && measured.sampledFloat32Difference && !scene.material.arrays[MaterialCoefficient::Shininess])
  {
    const double sampled = errorFromSample(*measured.sampledFloat32Difference);
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
    throw RoundingAboveTolerance("tolerance " + scientific(plan.tolerance) +
      " is below the predicted float64 rounding error of this scene on this mesh, " + scientific(plan.arithmeticError) +
      (deterministic < plan.tolerance ? ", which may take a tenth of it (the rays take the rest)" : "") +
      ": give a larger tolerance, or none for the exact methods");
  }
}

/// What a local light's approximations would err by: the distant approximation (infinite
/// where it does not apply, with why) and each pow method.
struct LocalLightErrors
{
  double distant = unbounded;
  std::string distantWhy;
  std::map<PowMethod, double> pow;
  bool oneShininess = true;
};

LocalLightErrors localLightErrors(const Scene& scene, std::size_t l, bool specular, const ArrayRequest& request,
  const MeshExtent& mesh, const MeshMeasurements& measured, Precision precision)
{
  LocalLightErrors errors;
  const auto* point = std::get_if<PointLight>(&scene.lights[l].source);
  if (point && geometryRequested(request, l))
  {
    errors.distantWhy = "not as distant: its direction arrays were requested";
  }
  else if (point)
  {
    errors.distant = distantApproximationError(*point, scene.material, specular, mesh);
    errors.distantWhy = std::isinf(errors.distant) ? "not as distant: the light is inside the mesh's bounding sphere"
                                                   : "as distant it would err by " + scientific(errors.distant);
  }
  // A pow approximation's bound charges the lobe's largest error at the light's peak, which
  // few meshes meet together (a highlight where the lobe errs most, on the vertex nearest the
  // light): the sample's measure is taken where it is lower. The lobe's error depends only on
  // the method, the precision and eta (largestPowError remembers it). A shininess per vertex
  // (from an array) has no one lobe to approximate: exact pow.
  errors.oneShininess = !scene.material.arrays[MaterialCoefficient::Shininess];
  const double eta = scene.material.shininess;
  for (const PowMethod method : approximatePowMethods)
  {
    double& error = errors.pow[method];
    error = unbounded;
    if (specular && errors.oneShininess)
    {
      const double lobe =
        precision == Precision::Float32 ? largestPowError<float>(method, eta) : largestPowError<double>(method, eta);
      error = powApproximationError(lobe, scene, l, mesh, measured);
    }
    if (specular && errors.oneShininess && !measured.sampledPowDifference.empty())
    {
      error = std::min(error, errorFromSample(measured.sampledPowDifference[l].of(method)));
    }
  }
  errors.pow[PowMethod::Exact] = 0; // std::pow's own rounding is part of arithmeticError
  return errors;
}

/// Why a local light was not given a cheaper method, for the plan's description.
std::string whyNotCheaper(
  const LightChoice& choice, const LocalLightErrors& errors, bool point, bool specular, double left)
{
  std::vector<std::string> reasons;
  if (point && !choice.method.distantFrom)
  {
    reasons.push_back(errors.distantWhy);
  }
  if (specular && !errors.oneShininess)
  {
    reasons.push_back("exact pow: the shininess varies per vertex");
  }
  else if (specular && choice.method.pow != PowMethod::Schlick)
  {
    reasons.push_back("Schlick pow would err by " + scientific(errors.pow.at(PowMethod::Schlick)));
  }
  if (specular && errors.oneShininess && choice.method.pow == PowMethod::Exact)
  {
    reasons.push_back("series pow by " + scientific(errors.pow.at(PowMethod::Series)));
  }
  std::string why;
  for (std::size_t r = 0; r < reasons.size(); ++r)
  {
    why += (r ? ", " : "") + reasons[r];
  }
  return reasons.empty() ? why : why + "; " + scientific(left) + " of the tolerance was left";
}

/// A point or spot light's (or a distant light's, a headlight's) methods: the cheapest of the
/// distant and pow approximations whose error fits what is `left`.
LightChoice localChoice(const Scene& scene, std::size_t l, bool specular, const ArrayRequest& request,
  const MeshExtent& mesh, const MeshMeasurements& measured, Precision precision, double left)
{
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
  const LocalLightErrors errors = localLightErrors(scene, l, specular, request, mesh, measured, precision);
  LightChoice choice;
  choice.name = scene.lights[l].name;
  for (const Candidate& candidate : candidates)
  {
    const double error = (candidate.distant ? errors.distant : 0) + errors.pow.at(candidate.pow);
    if (!std::isinf(error) && error <= left)
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
  const bool point = std::holds_alternative<PointLight>(scene.lights[l].source);
  choice.why = whyNotCheaper(choice, errors, point, specular, left);
  return choice;
}

/// The sampling's part of the tolerance, what the plan's deterministic errors leave, in equal
/// shares to the occlusion and to each light that samples.
void shareSampling(MethodPlan& plan, const Scene& scene)
{
  std::vector<std::size_t> sampledLights;
  for (std::size_t l = 0; l < plan.lights.size(); ++l)
  {
    if (plan.lights[l].sampledIrradiance || plan.lights[l].sampledSpecular)
    {
      sampledLights.push_back(l);
    }
  }
  const double share =
    (plan.tolerance - plan.predictedError()) / double(sampledLights.size() + (scene.ambientOcclusion ? 1 : 0));
  for (const std::size_t l : sampledLights)
  {
    drawToShare(*samplingOf(scene.lights[l].source), scene.material, share, plan.lights[l]);
  }
  if (scene.ambientOcclusion)
  {
    plan.occlusion = chooseOcclusion(scene, share);
  }
  plan.samplingError = (sampledLights.empty() ? 0 : share * double(sampledLights.size())) +
    (plan.occlusion ? plan.occlusion->errorInTotals() : 0);
}
}

namespace
{
/// Interreflection's largest albedo, what a tolerance needs of its settings, and its share
/// (set by the caller). Throws UnboundedSceneField where a tolerance cannot bound it.
InterreflectionChoice chooseInterreflection(const Scene& scene, const MeshMeasurements& measured)
{
  const Interreflection& settings = *scene.interreflection;
  const std::string orShade = "; or shade without a tolerance";
  if (!settings.bouncesFromTolerance)
  {
    throw UnboundedSceneField("/interreflection/bounces",
      "a tolerance cannot bound what the bounces past a fixed " + std::to_string(settings.bounces) +
        " leave out: give \"bounces\": \"auto\" (--bounces auto), which takes as many as the tolerance needs" +
        orShade);
  }
  if (!settings.sampling.fromTolerance)
  {
    throw UnboundedSceneField("/interreflection/samples",
      "interreflection's gather from a fixed " + std::to_string(settings.sampling.samples) +
        " rays per vertex has no error bound before they are traced: give \"samples\": \"auto\", which chooses "
        "the count from the standard errors of a first run" +
        orShade);
  }
  const ArrayCoefficient* kdArray = scene.material.arrays[MaterialCoefficient::Diffuse]
    ? &*scene.material.arrays[MaterialCoefficient::Diffuse]
    : nullptr;
  InterreflectionChoice choice;
  choice.largestAlbedo = kdArray ? measured.largestAlbedo.value_or(1.0) : largestComponent(scene.material.kd);
  if (!(choice.largestAlbedo < 1))
  {
    throw UnboundedSceneField("/material/kd",
      (kdArray ? "the array '" + kdArray->array + "' gives kd" : std::string("kd")) + " up to " +
        withDigits(choice.largestAlbedo, 3) +
        ": a surface that reflects all the light it receives lets no bounce fade (in a closed mesh their sum "
        "diverges), so a tolerance cannot bound how many are needed: give kd below 1" +
        orShade + " and a number of bounces");
  }
  return choice;
}
}

std::string tolerancePlanProblem(const Scene& scene)
{
  return scene.model == ShadingModel::VtkPbr
    ? "the vtk_pbr model has no tolerance plan yet (its bounds are the lecture model's)"
    : "";
}

MethodPlan chooseMethods(const Scene& scene, const ArrayRequest& request, const MeshExtent& mesh, double tolerance,
  bool float32Allowed, const MeshMeasurements& measured)
{
  if (scene.interreflection)
  {
    // Half for interreflection; the other half reaches the totals through the bounces too.
    InterreflectionChoice indirect = chooseInterreflection(scene, measured);
    indirect.share = tolerance / 2;
    Scene direct = scene;
    direct.interreflection.reset();
    MethodPlan plan = chooseMethods(
      direct, request, mesh, (tolerance - indirect.share) / indirect.directGrowth(), float32Allowed, measured);
    plan.tolerance = tolerance;
    plan.interreflection = indirect;
    return plan;
  }
  MethodPlan plan;
  plan.tolerance = tolerance;
  // Where anything is sampled, the deterministic errors take a tenth and sampling the rest.
  const double deterministic = scene.ambientOcclusion || samplesAnyLight(scene) ? tolerance / 10 : tolerance;
  choosePrecision(plan, scene, request, mesh, deterministic, float32Allowed, measured);
  double left = deterministic - plan.arithmeticError;
  for (std::size_t l = 0; l < scene.lights.size(); ++l)
  {
    const NamedLight& light = scene.lights[l];
    const bool specular = specularComputed(scene, request, l);
    LightChoice choice;
    choice.name = light.name;
    switch (roleOf(light.source))
    {
      case LightRole::Ambient: break;
      case LightRole::Distributed: choice = distributedChoice(light, l, scene.material, specular, left); break;
      case LightRole::Local:
        choice = localChoice(scene, l, specular, request, mesh, measured, plan.precision, left);
        break;
    }
    left -= choice.predictedError;
    plan.lights.push_back(choice);
  }
  shareSampling(plan, scene);
  return plan;
}
}
