// vtkLocalReflectanceFilter under a tolerance: the methods chosen, the sample of points on
// which float32's rounding and the pow approximations are measured, the cost forecast from a
// pilot, and what sampling left after the run (docs/guide/accuracy.md).
#include "vtkLocalReflectanceFilter.h"

#include "ShadeLabMeshPolygons.h"
#include "ShadeLabShadedArrays.h"
#include "ShadeLabWholeMesh.h"
#include "vtkLocalReflectanceFilterInternals.h"

#include "vtkCommunicator.h"
#include "vtkDataArrayRange.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkSMPThreadLocal.h"
#include "vtkSMPTools.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <numeric>

using namespace shadelab::shading;

namespace
{
/// How many points of a mesh (or piece) are shaded in both precisions to measure what float32
/// rounds: evenly spaced, about this many.
constexpr vtkIdType roundingSampleSize = 16384;

/// The k for taking every k-th of `count` points by id so as to keep at most `most` of them
/// (and more than most / 2): 1 where count is at most `most`.
vtkIdType everyKth(vtkIdType count, vtkIdType most)
{
  return std::max<vtkIdType>(1, (count + most - 1) / most);
}

/// Where a rounding can put a local light on the other side of a vertex's horizon, and switch
/// its terms on or off (a whole highlight, at a grazing light that the viewer sees mirrored):
/// |n.s| below this. float32 rounds n.s by about 1e-7 for a light as far from the mesh as the
/// mesh is large; the band leaves a thousandfold margin and holds few vertices (every vertex
/// of a plane under a grazing light, which are then all measured).
constexpr double horizonBand = 1e-4;

/// Where a pow approximation errs on a light's lobe by at least this share of its largest error
/// over [0, 1]: the few vertices of a large mesh whose highlight meets the method's worst x,
/// which an evenly spaced sample may pass over.
constexpr double powErrorBand = 0.9;

/// Why a point is to be measured besides the evenly spaced ones (pointsToMeasure).
enum PointToMeasure : unsigned char
{
  AtAHorizon = 1,
  AtAPowMethodsWorst = 2,
};

/// Which points the sample must hold besides the evenly spaced ones (bands of their own
/// geometry, so the same points whatever the pieces): those whose normal is within horizonBand
/// of a local light's horizon, and those where a pow approximation errs on a local light's lobe
/// by at least powErrorBand of its largest.
std::vector<unsigned char> pointsToMeasure(const shadelab::Scene& scene, vtkDataArray* points, vtkDataArray* normals)
{
  std::vector<shadelab::LocalEvaluation> lights;
  shadelab::EvaluationContext context;
  context.lineOfSight = scene.viewer.lineOfSight();
  for (const shadelab::NamedLight& light : scene.lights)
  {
    // Only local lights: a map's preparation would project it.
    if (shadelab::roleOf(light.source) == shadelab::LightRole::Local)
    {
      lights.push_back(std::get<shadelab::LocalEvaluation>(shadelab::prepareEvaluation(light.source, context)));
    }
  }
  const double eta = scene.material.shininess;
  // The lobe's cosine x: the lobe at eta 1.
  const shadelab::LobeModel cosineOfLobe{
    shadelab::hasSpecularTerm(scene) ? shadelab::evaluatedSpecularModel(scene) : shadelab::SpecularModel::None, 1.0
  };
  const bool twoSided = shadelab::shadesBothSides(scene);
  const bool measuresPow = cosineOfLobe.wanted() && eta > 0;
  // Per method, its error on x^eta at x, its largest, and the least x where it reaches the
  // band (on a grid of 4096, less a step; 0 where the grid misses it): below that no point
  // needs the error worked out.
  auto powErrorAt = [eta](int m, double x)
  {
    double error = 0;
    shadelab::withPowMethod(
      shadelab::approximatePowMethods[m], eta, [&](auto power) { error = std::abs(power(x) - std::pow(x, eta)); });
    return error;
  };
  double largestPowError[2] = { 0, 0 }, leastX[2] = { 2, 2 };
  for (int m = 0; m < 2 && measuresPow; ++m)
  {
    largestPowError[m] = shadelab::largestPowError<double>(shadelab::approximatePowMethods[m], eta);
    constexpr int steps = 4096;
    for (int k = 0; k <= steps && leastX[m] > 1; ++k)
    {
      if (powErrorAt(m, k / double(steps)) >= powErrorBand * largestPowError[m])
      {
        leastX[m] = (k - 1) / double(steps);
      }
    }
    leastX[m] = leastX[m] > 1 ? 0.0 : leastX[m];
  }
  const vtkIdType count = points->GetNumberOfTuples();
  std::vector<unsigned char> measured(static_cast<std::size_t>(count), 0);
  // The coordinates and normals in their own memory (float or double), read without a call each.
  shadelab::visitPackedPoints(points,
    [&](auto pointAt)
    {
      shadelab::visitPackedPoints(normals,
        [&](auto normalAt)
        {
          vtkSMPTools::For(0, count,
            [&](vtkIdType begin, vtkIdType end)
            {
              for (vtkIdType i = begin; i < end; ++i)
              {
                const glm::dvec3 normal = normalAt(i);
                if (!shadelab::isFinite(normal) || normal == glm::dvec3(0.0))
                {
                  continue; // shaded with ambient light only
                }
                const glm::dvec3 position = pointAt(i);
                const glm::dvec3 unit = shadelab::unitVector(normal);
                const glm::dvec3 toViewer = scene.viewer.directionFrom(position);
                for (const shadelab::LocalEvaluation& light : lights)
                {
                  const glm::dvec3 s = shadelab::towardLight(light, position).toLight;
                  const double cosine = glm::dot(unit, s);
                  unsigned char measure = std::abs(cosine) < horizonBand ? AtAHorizon : 0;
                  // The lobe's cosine x on the side the kernel shades.
                  const bool turned =
                    twoSided && shadelab::turnsNormalRound(glm::dot(unit, toViewer), scene.shadedSide);
                  const glm::dvec3 shaded = turned ? -unit : unit;
                  if (measuresPow && glm::dot(shaded, s) > 0)
                  {
                    const double x = cosineOfLobe(shaded, s, toViewer);
                    for (int m = 0; m < 2; ++m)
                    {
                      if (x >= leastX[m] && powErrorAt(m, x) >= powErrorBand * largestPowError[m])
                      {
                        measure |= AtAPowMethodsWorst;
                      }
                    }
                  }
                  measured[static_cast<std::size_t>(i)] |= measure;
                }
              }
            });
        });
    });
  return measured;
}

/// The largest difference between two shadings of the same arrays (float32's and float64's),
/// over every component of the real-valued arrays (the flags are bits, not values).
double largestDifference(
  const std::vector<vtkSmartPointer<vtkDataArray>>& a, const std::vector<vtkSmartPointer<vtkDataArray>>& b)
{
  double largest = 0;
  for (std::size_t k = 0; k < a.size(); ++k)
  {
    if (!a[k]->IsA("vtkUnsignedCharArray"))
    {
      const int components = a[k]->GetNumberOfComponents();
      for (vtkIdType v = 0; v < a[k]->GetNumberOfValues(); ++v)
      {
        largest = std::max(largest,
          std::abs(a[k]->GetComponent(v / components, int(v % components)) -
            b[k]->GetComponent(v / components, int(v % components))));
      }
    }
  }
  return largest;
}

/// A cost forecast's pilot: enough vertices for their mean cost to a few percent, a small share
/// of a large mesh's; a mesh under pilotMeshLeast is shaded without one (the run is short).
constexpr vtkIdType pilotLeast = 128, pilotMost = 2048, pilotMeshLeast = 1024;

/// How many of the pilot's vertices stopped at a maximum short of a target: a light's, or the
/// ambient occlusion's (its array in `seen`, where there is one).
std::size_t shortOfTargetCount(
  const ShortOfTarget& lights, vtkPolyData* seen, const std::string& prefix, std::size_t count)
{
  vtkDataArray* occlusion = seen
    ? seen->GetPointData()->GetArray(
        shadelab::occlusionArrayName(prefix, shadelab::OcclusionTerm::ShortOfTarget).c_str())
    : nullptr;
  std::size_t stopped = 0;
  for (std::size_t i = 0; i < count; ++i)
  {
    bool marked = occlusion && occlusion->GetComponent(static_cast<vtkIdType>(i), 0) != 0;
    for (const std::vector<std::uint8_t>& marks : lights)
    {
      marked = marked || (!marks.empty() && marks[i]);
    }
    stopped += marked ? 1 : 0;
  }
  return stopped;
}
}

std::vector<double> shadelab::nearestPointDistances(
  const shadelab::Scene& scene, vtkDataArray* points, vtkMultiProcessController* processes)
{
  const std::size_t lightCount = scene.lights.size();
  // Each thread's least squared distances; a minimum is the same in any order, so on any
  // thread count.
  vtkSMPThreadLocal<std::vector<double>> nearestSquared;
  if (points)
  {
    shadelab::visitPackedPoints(points,
      [&](auto pointAt)
      {
        vtkSMPTools::For(0, points->GetNumberOfTuples(),
          [&](vtkIdType begin, vtkIdType end)
          {
            std::vector<double>& least = nearestSquared.Local();
            least.resize(lightCount, std::numeric_limits<double>::infinity());
            for (std::size_t l = 0; l < lightCount; ++l)
            {
              if (const glm::dvec3* light = shadelab::positionOf(scene.lights[l].source))
              {
                for (vtkIdType i = begin; i < end; ++i)
                {
                  const glm::dvec3 offset = pointAt(i) - *light;
                  least[l] = std::min(least[l], glm::dot(offset, offset));
                }
              }
            }
          });
      });
  }
  std::vector<double> nearest(lightCount, std::numeric_limits<double>::infinity());
  for (const std::vector<double>& least : nearestSquared)
  {
    for (std::size_t l = 0; l < least.size(); ++l)
    {
      nearest[l] = std::min(nearest[l], std::sqrt(least[l]));
    }
  }
  if (processes && lightCount > 0)
  {
    std::vector<double> everywhere(lightCount);
    processes->AllReduce(
      nearest.data(), everywhere.data(), static_cast<vtkIdType>(lightCount), vtkCommunicator::MIN_OP);
    nearest = everywhere;
  }
  return nearest;
}

bool vtkLocalReflectanceFilter::ChooseMethods(ShadingPlan& plan, bool roundingMeasuredLater)
{
  try
  {
    this->MethodPlan =
      shadelab::chooseMethods(plan.scene, plan.request, plan.extent, this->Tolerance, plan.float32Fits, plan.measured);
  }
  catch (const shadelab::RoundingAboveTolerance& error)
  {
    if (!roundingMeasuredLater)
    {
      vtkErrorMacro(<< error.what());
    }
    return roundingMeasuredLater;
  }
  catch (const shadelab::UnboundedSceneField& error) // the scene's problem, at its field
  {
    return this->SceneIsValid({ { error.field, error.what() } });
  }
  catch (const std::invalid_argument& error)
  {
    vtkErrorMacro(<< error.what());
    return false;
  }
  plan.precision = this->MethodPlan->precision;
  plan.methods = this->MethodPlan->methods();
  if (this->MethodPlan->occlusion)
  {
    plan.scene.ambientOcclusion->target = this->MethodPlan->occlusion->target;
  }
  return true;
}

vtkLocalReflectanceFilter::PointSample vtkLocalReflectanceFilter::SamplePoints(
  vtkPolyData* input, vtkDataArray* shadingNormals, const ShadingPlan& plan, const shadelab::MeshPieces& pieces)
{
  // Points evenly spaced by their id in the whole mesh, and those where a light grazes the
  // surface: on a split mesh, the pieces' samples make up the whole mesh's, whatever the pieces.
  const vtkIdType count = input->GetNumberOfPoints();
  const std::vector<vtkIdType>* pieceIds = pieces.pointIds();
  auto idOf = [&](vtkIdType i) { return pieceIds ? (*pieceIds)[static_cast<std::size_t>(i)] : i; };
  // Global ids number the whole mesh's points 0 to n-1.
  const vtkIdType wholeCount = pieces.split() ? shadelab::wholePointCount(pieces.processes, *pieceIds) : count;
  const vtkIdType stride = everyKth(wholeCount, roundingSampleSize);
  const std::vector<unsigned char> banded = count > 0
    ? pointsToMeasure(plan.scene, input->GetPoints()->GetData(), shadingNormals)
    : std::vector<unsigned char>();
  // Every point at a horizon; of those at a pow method's worst, all of a small band (a small
  // highlight, which the evenly spaced points may miss) and about roundingSampleSize of a
  // large one, evenly spaced by id (the error is smooth along it): counted over the whole mesh,
  // so the same points whatever the pieces.
  std::vector<vtkIdType> worstIds;
  for (vtkIdType i = 0; i < count; ++i)
  {
    if (banded[static_cast<std::size_t>(i)] & AtAPowMethodsWorst)
    {
      worstIds.push_back(idOf(i));
    }
  }
  const std::size_t worstCount =
    pieces.split() ? shadelab::distinctIdCount(pieces.processes, worstIds) : worstIds.size();
  const vtkIdType worstStride = everyKth(static_cast<vtkIdType>(worstCount), roundingSampleSize);
  std::vector<vtkIdType> sample;
  PointSample taken;
  for (vtkIdType i = 0; i < count; ++i)
  {
    const unsigned char why = banded.empty() ? 0 : banded[static_cast<std::size_t>(i)];
    if (idOf(i) % stride == 0 || (why & AtAHorizon) || ((why & AtAPowMethodsWorst) && idOf(i) % worstStride == 0))
    {
      sample.push_back(i);
      taken.ids.push_back(idOf(i));
    }
  }
  if (!sample.empty())
  {
    taken.points = shadelab::tuplesAt(input->GetPoints()->GetData(), sample);
    taken.normals = shadelab::tuplesAt(shadingNormals, sample);
  }
  return taken;
}

void vtkLocalReflectanceFilter::MeasureOnSample(
  const PointSample& sample, ShadingPlan& plan, const shadelab::MeshPieces& pieces)
{
  // Every light visible and the open sky: every term that the scene can make nonzero is, and
  // rounds as it would in the shading. Each point's samples (an area light's or a map's) are
  // seeded by its id in the whole mesh, as in the shading, whatever the pieces.
  shadelab::ShadingInputs open;
  open.sampleIds = sample.ids.data();
  const shadelab::Scene& scene = plan.scene;
  auto shadeSample =
    [&](auto precision, const shadelab::ArrayRequest& request, const std::vector<shadelab::LightMethod>& methods)
  {
    using T = decltype(precision);
    return shade<T>(scene, request, methods, "", sample.points, sample.normals, open, nullptr);
  };
  const std::vector<shadelab::LightMethod> exact(scene.lights.size());
  // What float32 rounds, all lights exact, against float64; and what each pow approximation
  // adds to each light's specular term, in float32 where it fits (its rounding included).
  std::vector<double> largest(1 + 2 * scene.lights.size(), 0.0);
  if (sample.points)
  {
    if (plan.float32Fits)
    {
      largest[0] =
        largestDifference(shadeSample(float(), plan.request, exact), shadeSample(double(), plan.request, exact));
    }
    // The specular arrays of the lights a pow method applies to (point, spot, distant), which
    // the shading writes in the lights' order.
    shadelab::ArrayRequest speculars;
    speculars.lights.resize(scene.lights.size());
    std::vector<std::size_t> specularLights;
    for (std::size_t l = 0; l < scene.lights.size(); ++l)
    {
      const shadelab::LightSource& source = scene.lights[l].source;
      if (shadelab::hasSpecularTerm(scene) && !shadelab::isAmbient(source) && !shadelab::isDistributed(source))
      {
        speculars.lights[l][int(shadelab::LightTerm::Specular)] = true;
        specularLights.push_back(l);
      }
    }
    const auto reference = specularLights.empty() ? decltype(shadeSample(double(), speculars, exact))()
                                                  : shadeSample(double(), speculars, exact);
    for (std::size_t m = 0; m < 2 && !specularLights.empty(); ++m)
    {
      std::vector<shadelab::LightMethod> methods(scene.lights.size());
      for (const std::size_t l : specularLights)
      {
        methods[l].pow = shadelab::approximatePowMethods[m];
      }
      const auto approximated =
        plan.float32Fits ? shadeSample(float(), speculars, methods) : shadeSample(double(), speculars, methods);
      for (std::size_t k = 0; k < specularLights.size(); ++k)
      {
        largest[1 + 2 * specularLights[k] + m] = largestDifference({ reference[k] }, { approximated[k] });
      }
    }
  }
  if (pieces.split()) // the largest over every piece, the same on every process
  {
    std::vector<double> everywhere(largest.size());
    pieces.processes->AllReduce(
      largest.data(), everywhere.data(), static_cast<vtkIdType>(largest.size()), vtkCommunicator::MAX_OP);
    largest = everywhere;
  }
  if (plan.float32Fits)
  {
    plan.measured.sampledFloat32Difference = largest[0];
  }
  plan.measured.sampledPowDifference.resize(scene.lights.size());
  for (std::size_t l = 0; l < scene.lights.size(); ++l)
  {
    for (std::size_t m = 0; m < 2; ++m)
    {
      plan.measured.sampledPowDifference[l].of(shadelab::approximatePowMethods[m]) = largest[1 + 2 * l + m];
    }
  }
}

std::vector<std::string> vtkLocalReflectanceFilter::ShortOfTargetReport(const ShadingPlan& plan,
  const std::vector<std::vector<std::uint8_t>>& shortOfTarget, const shadelab::MeshPieces& pieces) const
{
  std::vector<std::string> report;
  for (std::size_t l = 0; l < plan.methods.size(); ++l)
  {
    if (!plan.methods[l].targets.any())
    {
      continue;
    }
    // On a split mesh, each vertex once, by its id in the whole mesh, whichever pieces hold it.
    std::vector<vtkIdType> ids;
    const std::vector<std::uint8_t> none;
    const std::vector<std::uint8_t>& marks = l < shortOfTarget.size() ? shortOfTarget[l] : none;
    for (std::size_t i = 0; i < marks.size(); ++i)
    {
      if (marks[i])
      {
        ids.push_back(pieces.split() ? (*pieces.pointIds())[i] : static_cast<vtkIdType>(i));
      }
    }
    const std::size_t vertices = pieces.split() ? shadelab::distinctIdCount(pieces.processes, ids) : ids.size();
    if (vertices > 0)
    {
      report.push_back(plan.scene.lights[l].name + ": " + std::to_string(vertices) +
        " vertices stopped at \"max_samples\" short of their target (their _std_error arrays are above it): raise it");
    }
  }
  return report;
}

double vtkLocalReflectanceFilter::EstimatedSamplingError(
  std::vector<double> standardErrors, const shadelab::MeshPieces& pieces) const
{
  // A quantile of a few tens of thousands of values is that of the whole mesh to within a
  // fraction of a percent of its share (the rank of the 95th percentile among n has a
  // standard error of sqrt(0.05 0.95 / n), 0.12% of n at 32,768), so a large mesh gives every
  // k-th vertex by its id, 32,768 to 65,536 of them, the same on any number of processes.
  constexpr vtkIdType enough = 65536;
  std::vector<vtkIdType> ids;
  const std::vector<vtkIdType>* pieceIds = pieces.pointIds();
  const vtkIdType count = static_cast<vtkIdType>(pieceIds ? pieceIds->size() : standardErrors.size());
  const vtkIdType wholeMesh = pieceIds ? shadelab::wholePointCount(pieces.processes, *pieceIds) : count;
  const vtkIdType stride = everyKth(wholeMesh, enough);
  std::vector<double> taken;
  for (vtkIdType i = 0; i < static_cast<vtkIdType>(standardErrors.size()) && i < count; ++i)
  {
    const vtkIdType id = pieceIds ? (*pieceIds)[static_cast<std::size_t>(i)] : i;
    if (id % stride == 0)
    {
      ids.push_back(id);
      taken.push_back(standardErrors[i]);
    }
  }
  return shadelab::estimatedErrorQuantile(
    pieceIds ? shadelab::valuesByDistinctId(pieces.processes, ids, taken) : std::move(taken),
    shadelab::targetConfidence);
}

std::optional<shadelab::CostForecast> vtkLocalReflectanceFilter::ForecastCost(
  vtkPolyData* input, vtkDataArray* shadingNormals, const ShadingPlan& plan, const shadelab::MeshPieces& pieces)
{
  const vtkIdType count = input->GetNumberOfPoints();
  if (pieces.split() || count < pilotMeshLeast)
  {
    return std::nullopt;
  }
  const vtkIdType stride = everyKth(count, std::clamp<vtkIdType>(count / 128, pilotLeast, pilotMost));
  std::vector<vtkIdType> pilot;
  for (vtkIdType id = 0; id < count; id += stride)
  {
    pilot.push_back(id);
  }
  // Its rays from the pilot's points only (the BVH built here is kept for the run), seeded by
  // their ids, as in the run; the time is the rays' (the BVH's build not included) and the shading's.
  vtkPolyData* seen = this->PrepareVisibility(input, shadingNormals, plan, shadelab::MeshPieces{}, pilot);
  const double raySeconds = seen ? this->Internals->VisibilityStep->GetRaySeconds() : 0.0;
  const auto shadingStart = std::chrono::steady_clock::now();
  shadelab::ShadingInputs inputs; // the scene's own material: per-vertex values are read for the whole mesh
  const std::vector<long long> ids(pilot.begin(), pilot.end());
  inputs.sampleIds = ids.data();
  if (seen)
  {
    useVisibility(seen, plan.scene, plan.request, this->ArrayPrefix, inputs);
  }
  std::vector<std::uint32_t> samples(pilot.size(), 0);
  ShortOfTarget shortOfTarget;
  shadeIn(plan.precision, plan.scene, plan.request, plan.methods, this->ArrayPrefix,
    shadelab::tuplesAt(input->GetPoints()->GetData(), pilot), shadelab::tuplesAt(shadingNormals, pilot), inputs,
    nullptr, &shortOfTarget, nullptr, &samples);
  const double pilotSeconds =
    raySeconds + std::chrono::duration<double>(std::chrono::steady_clock::now() - shadingStart).count();

  shadelab::CostForecast forecast;
  const double scale = double(count) / double(pilot.size());
  forecast.pilotVertices = pilot.size();
  forecast.meshVertices = static_cast<std::size_t>(count);
  forecast.counts.samples = scale * std::accumulate(samples.begin(), samples.end(), 0.0);
  forecast.counts.occlusionRays = scale * occlusionRayCount(plan.scene, seen, this->ArrayPrefix, pilot.size());
  forecast.shareShortOfTarget =
    double(shortOfTargetCount(shortOfTarget, seen, this->ArrayPrefix, pilot.size())) / double(pilot.size());
  forecast.seconds = scale * pilotSeconds;
  forecast.threads = vtkSMPTools::GetEstimatedNumberOfThreads();
  return forecast;
}
