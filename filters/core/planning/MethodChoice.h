#pragma once
// Computing no more than the scene needs: given a tolerance on the absolute error of every
// shaded value, choose the cheapest arithmetic and, per light, the cheapest approximations
// whose predicted errors fit in it together. The predictions are upper bounds derived below
// in MethodChoice.cpp; tests check them against measured errors on the meshes in data/.
#include "ArrayCatalog.h"
#include "LightMethod.h"
#include "MeshExtent.h"
#include "Scene.h"
#include "SequentialSampling.h"

#include <optional>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace shadelab
{
struct LightChoice
{
  std::string name;
  LightMethod method;
  /// Of the approximations chosen for this light, and of its samples' share where they are
  /// drawn to one (at 95% confidence).
  double predictedError = 0;
  std::string why; // why no cheaper method was taken, or "" when the cheapest was
  /// An area light or a map: its deterministic part's error (SH's band limit), and whether its
  /// estimates of E and S are sampled (and so drawn to a share of the tolerance).
  double approximationError = 0;
  bool sampledIrradiance = false, sampledSpecular = false;
};

/// How the scene's ambient occlusion meets its share of the tolerance.
struct OcclusionChoice
{
  /// Rays drawn per vertex to this target ("rays": "auto"); nullopt: the scene's fixed count.
  std::optional<SamplingTarget> target;
  /// The occlusion's predicted error at 95% confidence: the target's, or a fixed count's bound.
  double predictedError = 0;
  /// How much an error of the occlusion moves the totals: the ambient lights' ka La (at least 1,
  /// for the ambient_occlusion array itself).
  double weightInTotals = 1;

  /// Its predicted error as it reaches the totals.
  double errorInTotals() const { return predictedError * weightInTotals; }
};

/// How interreflection meets its share of the tolerance (docs/formulas.md section 23.5): the
/// plan gives it half of the tolerance and the direct terms the rest divided by how far their
/// errors reach through the bounces; its bounces and gather rays are chosen in the run, once
/// the direct light is known.
struct InterreflectionChoice
{
  /// rho, the largest albedo over the channels and the vertices, below 1: a bounce carries at
  /// most rho times the light of the one before it.
  double largestAlbedo = 0;
  /// Its share in the totals' units: a tenth for what the bounces left out add, the rest for
  /// the gather's sampling (at 95%).
  double share = 0;
  /// Chosen in the run: the bounces, and the bound on what those past them add.
  int bounces = 0;
  double bouncesLeftOut = 0;
  /// Chosen in the run: the first run's gather rays per vertex, then the count kept.
  int firstSamples = 0, samples = 0;
  /// The sampling's error after the run, from the vertices' standard errors
  /// (estimatedErrorQuantile at 95%): an estimate.
  std::optional<double> estimatedSamplingError;

  double truncationShare() const { return share / 10; }
  double samplingShare() const { return share - truncationShare(); }
  /// An error e of the direct diffuse term reaches the totals as e + rho e + rho^2 e + ...
  double directGrowth() const { return 1 / (1 - largestAlbedo); }
  /// Its line of the plan: the shares.
  std::string describe() const;
  /// After the run: what was chosen, and the gather's error.
  std::string describeRun() const;
};

/// The gather rays per vertex that meet `share`, from a first run of firstRays whose error was
/// estimated at firstError: the error taken to fall as 1 / sqrt(N) (stratified rays fall at least
/// as fast), the count a power of two times firstRays, at most `maximum` (and at least
/// firstRays: the first run's rays are kept where they meet the share).
int gatherRaysWithin(double firstError, int firstRays, double share, int maximum);

/// The samples that area lights and maps draw, and the rays of ambient occlusion, over a mesh.
struct SampleCounts
{
  double samples = 0;
  double occlusionRays = 0;

  /// "25 million samples (4100 per vertex) and 720 thousand occlusion rays (120 per vertex)",
  /// each where there are any, per vertex of a mesh of `vertices`.
  std::string describe(std::size_t vertices) const;
};

/// What a plan that samples is forecast to cost, before the run: a pilot of a few of the
/// vertices, evenly spaced by id, is shaded with it (rays included) and scaled to the mesh.
struct CostForecast
{
  std::size_t pilotVertices = 0, meshVertices = 0;
  SampleCounts counts;           // the pilot's, scaled to the mesh
  double shareShortOfTarget = 0; // of the pilot's vertices, those stopped at a maximum short of a target
  double seconds = 0;            // casting the rays and shading, at the pilot's pace per vertex
  int threads = 1;
  /// After the run, what it drew (nullopt before it).
  std::optional<SampleCounts> drawn;

  /// "forecast from 256 of the 6002 vertices: about 25 million samples (4100 per vertex), ..."
  std::string describe() const;
};

struct MethodPlan
{
  Precision precision = Precision::Float64;
  double arithmeticError = 0;               // predicted rounding error of the chosen precision
  bool roundingSampled = false;             // float32's from a sample of the mesh (errorFromSample), not a priori
  std::vector<LightChoice> lights;          // one per scene light (ambient lights have nothing to choose)
  std::optional<OcclusionChoice> occlusion; // where the scene has ambient occlusion
  std::optional<InterreflectionChoice> interreflection;
  double tolerance = 0;
  /// The part of predictedError() that sampling takes (at 95%): the shares of the estimates
  /// drawn to a target, and a fixed count of occlusion rays' bound; 0 where nothing is sampled.
  double samplingError = 0;
  /// After the run, sampling's part as the vertices' own standard errors put it: the error 95%
  /// of the vertices are within were their errors normal (estimatedErrorQuantile). An estimate,
  /// not a bound like samplingError: where the stopping rule stops a vertex on a standard error
  /// that its few samples put too low, the error can exceed it. nullopt before the run.
  std::optional<double> estimatedSamplingError;
  /// Where the plan samples, its cost forecast before the run (nullopt: not forecast).
  std::optional<CostForecast> forecast;

  std::vector<LightMethod> methods() const;
  /// arithmeticError, every light's predictedError and the sampled estimates' errors as they
  /// reach the arrays, grown through interreflection's bounces, and interreflection's share: at
  /// most tolerance (the sampled part at 95% confidence).
  double predictedError() const;
  /// predictedError() with sampling's part as estimated after the run, and interreflection's
  /// as its chosen bounces and its gather's standard errors put it, once they are.
  double estimatedError() const;
  /// One line for the precision, then one per light, for the console and the field data, the
  /// forecast's where there is one, and after the run the samples drawn against it and
  /// sampling's part of the error as estimated.
  std::vector<std::string> describe() const;
};

/// The pow approximations a tolerance may choose, as the sample measures them (see below).
constexpr PowMethod approximatePowMethods[] = { PowMethod::Schlick, PowMethod::Series };

/// A light's largest specular difference from the exact pow on the sample, per method.
struct SampledPowDifferences
{
  double schlick = 0, series = 0;
  double& of(PowMethod method) { return method == PowMethod::Schlick ? schlick : series; }
  double of(PowMethod method) const { return method == PowMethod::Schlick ? schlick : series; }
};

/// What the filter measures on the mesh's points, where its bounding sphere alone bounds the
/// errors too loosely.
struct MeshMeasurements
{
  /// Per scene light, the least distance from it to any vertex, for the lights with a position
  /// (the others' entries are unused); empty: not measured. The bounding sphere says only
  /// D - R, which is 0 for a light inside it: the largest attenuation would be the light's
  /// clamp at min_distance.
  std::vector<double> nearestVertexDistance;
  /// The largest difference between float32 and float64 shading on a sample of the points
  /// (all lights exact); nullopt: not measured, float32's rounding is bounded a priori.
  std::optional<double> sampledFloat32Difference;
  /// Per scene light, the largest difference that Schlick's and the series pow make to its
  /// specular term on that sample (float64, the light where it is); empty: not measured.
  std::vector<SampledPowDifferences> sampledPowDifference;
  /// The largest shininess over the whole mesh where the material reads it from an array;
  /// nullopt: not measured (the lobe's rounding is then bounded by its full size).
  std::optional<double> largestShininess;
  /// The largest kd component over the whole mesh where the material reads kd from an array;
  /// nullopt: not measured (interreflection's bounces are then not bounded).
  std::optional<double> largestAlbedo;
};

/// The least distance from a light at `position` to any vertex: the measured one where there
/// is one, else the bounding sphere's D - R (at least 0).
double nearestVertexDistance(
  const glm::dvec3& position, const MeshExtent& mesh, const MeshMeasurements& measured, std::size_t light);

/// Predicted largest error of evaluating a point light as distant from mesh.centre, or
/// +infinity where the approximation does not hold (the light inside the mesh's bounding
/// sphere). specular: whether the light's specular term is computed.
double distantApproximationError(
  const PointLight& light, const Material& material, bool specular, const MeshExtent& mesh);

/// Predicted largest error that a pow method adds to the specular term of the scene's light l,
/// given the method's largest error on the lobe x^eta itself (largestPowError at the
/// material's eta).
double powApproximationError(double lobeError, const Scene& scene, std::size_t light, const MeshExtent& mesh,
  const MeshMeasurements& measured = {});

/// Predicted largest rounding error of the requested values (all lights exact) in this
/// precision.
double arithmeticError(Precision precision, const Scene& scene, const ArrayRequest& request, const MeshExtent& mesh,
  const MeshMeasurements& measured = {});

/// An error predicted from the largest difference measured on a sample of the mesh's points
/// (float32's rounding, a pow approximation's): twice it, as the mesh's largest can exceed
/// the sample's (docs/formulas.md section 15). float64's rounding is float32's times 2^-29,
/// the ratio of their unit roundoffs: the same operations, each rounding 2^29 times finer.
double errorFromSample(double largestSampledDifference);

/// What chooseMethods throws when even float64 is predicted to round by more than the
/// tolerance allows: the filter then waits for a sample's measurement before it refuses.
struct RoundingAboveTolerance : std::invalid_argument
{
  using std::invalid_argument::invalid_argument;
};

/// What chooseMethods throws when a field of the scene keeps the tolerance from bounding it (a
/// fixed count of samples or rays, an estimator without a bound): the field as a JSON pointer
/// ("/lights/0/samples"), so that the message can name the scene and the field the user wrote.
struct UnboundedSceneField : std::invalid_argument
{
  UnboundedSceneField(std::string field, const std::string& why)
    : std::invalid_argument(why)
    , field(std::move(field))
  {
  }
  std::string field;
};

/// The error at 95% confidence of a fraction estimated from n rays, whatever the fraction:
/// two standard errors of a mean of n values in [0, 1], whose variance is at most 1/4
/// (stratification only lowers it), so 1 / sqrt(n).
double fixedRaysError(int n);

/// The cheapest plan whose predicted error is at most tolerance (> 0). Where the scene samples
/// (ambient occlusion, an area light's or a map's Monte Carlo estimates), the arithmetic and
/// approximations may take a tenth of the tolerance and the sampling the rest, what they leave
/// included, in equal shares: a sampled estimate's cost grows as
/// the inverse square of its error, so the nine tenths cost 1.23 times the rays of all of it,
/// while float32 and the approximations rarely need more than a tenth. scene must have no
/// sceneProblems() and request must come from selectArrays(scene, ...). float32Allowed: false
/// when the mesh or scene does not fit float32 at all. With a sampledFloat32Difference,
/// float32's error is the sample's (errorFromSample) rather than the a priori bound, and
/// float64's the lesser of the two; with sampledPowDifference, a pow approximation's is the
/// lesser of its bound and the sample's. Throws std::invalid_argument when even
/// float64 with exact methods is predicted to exceed the tolerance (RoundingAboveTolerance),
/// a fixed count of rays to exceed the share left for it, or an area light or map cannot be
/// bounded (its estimator has no bound, its samples are a fixed count, or its SH irradiance
/// errs by more than is left): UnboundedSceneField, naming the field. With interreflection,
/// its "bounces" and "samples" must be "auto" and kd below 1 (InterreflectionChoice). measured: what the filter
/// measured on the points (nothing: the bounding sphere's bounds and float32's a priori).
MethodPlan chooseMethods(const Scene& scene, const ArrayRequest& request, const MeshExtent& mesh, double tolerance,
  bool float32Allowed = true, const MeshMeasurements& measured = {});

/// Why no tolerance can plan this scene, whatever its value, or "" where one can: the vtk_pbr
/// model, whose terms the plan's bounds (which are the lecture model's) do not cover.
std::string tolerancePlanProblem(const Scene& scene);
}
