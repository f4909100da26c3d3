#include "vtkMeshVisibilityFilter.h"

#include "ArrayCatalog.h"
#include "Overloaded.h"
#include "SceneFrame.h"
#include "ShadeLabFieldNotes.h"
#include "ShadeLabLargeArrays.h"
#include "ShadeLabMeshChecks.h"
#include "ShadeLabMeshExtent.h"
#include "ShadeLabMeshPolygons.h"
#include "ShadeLabRunAborted.h"
#include "ShadeLabThreadCount.h"
#include "ShadeLabWholeMesh.h"
#include "ShadingFlags.h"
#include "Visibility.h"

#include "vtkDataArrayRange.h"
#include "vtkDemandDrivenPipeline.h"
#include "vtkDoubleArray.h"
#include "vtkFloatArray.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkIntArray.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkSMPTools.h"
#include "vtkTypeUInt64Array.h"
#include "vtkUnsignedCharArray.h"

#include <glm/geometric.hpp>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <memory>
#include <optional>
#include <sstream>

vtkStandardNewMacro(vtkMeshVisibilityFilter);

namespace
{
/// A light whose shadows the mesh casts, as the rays see it: a local light, with one ray per
/// vertex and its visibility, or an area light or map, with a ray per sample and the bits of those
/// the mesh hides.
struct ShadowedLight
{
  std::string name;
  shadelab::LocalEvaluation evaluation;
  vtkSmartPointer<vtkFloatArray> visibility;
  std::shared_ptr<const shadelab::ShadowedLightEstimator> distributed; // null for a local light
  vtkSmartPointer<vtkTypeUInt64Array> hidden;
  /// Drawn to a target: estimated here, its rays traced round by round (terms), and how many
  /// rays the vertices cast.
  bool drawnToTarget = false;
  vtkSmartPointer<vtkDoubleArray> terms;
  std::shared_ptr<std::atomic<std::uint64_t>> raysCast = std::make_shared<std::atomic<std::uint64_t>>(0);
  bool enclosed = false; // inside the mesh: hidden from every vertex outside (FlagLightEnclosed)

  /// Where the light is, if it is anywhere: a positional light's position, an area light's centre.
  std::optional<glm::dvec3> position() const
  {
    if (distributed)
    {
      return distributed->emitterCentre();
    }
    if (evaluation.geometry == shadelab::LocalEvaluation::Geometry::Distant)
    {
      return std::nullopt;
    }
    return evaluation.position;
  }
};

/// An array of count tuples in huge pages (float32 for the estimates, 64-bit words for a distributed
/// light's hidden samples, float64 for the estimates of one drawn to a target); throws
/// std::runtime_error naming it when there is not enough memory.
template<typename Array>
vtkSmartPointer<Array> pointArray(const std::string& name, int components, vtkIdType count)
{
  auto array = vtkSmartPointer<Array>::New();
  array->SetName(name.c_str());
  array->SetNumberOfComponents(components);
  if (!shadelab::allocateTuples<typename Array::ValueType>(array, count))
  {
    throw std::runtime_error("not enough memory for the array '" + name + "'");
  }
  return array;
}

double secondsSince(std::chrono::steady_clock::time_point start)
{
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

/// The scene's lights with shadows, as the rays see them (their arrays not yet allocated), those
/// drawn to a target as the shading would draw them.
std::vector<ShadowedLight> shadowedLights(
  const shadelab::Scene& scene, const std::vector<vtkMeshVisibilityFilter::DrawnLight>& drawn)
{
  std::vector<ShadowedLight> lights;
  shadelab::EvaluationContext context;
  context.lineOfSight = scene.viewer.lineOfSight();
  for (std::size_t l = 0; l < scene.lights.size(); ++l)
  {
    if (scene.lights[l].shadows)
    {
      // The distributed lights' samples are seeded by the light's index, as the kernel seeds them.
      context.lightIndex = l;
      context.targets = l < drawn.size() ? drawn[l].targets : shadelab::SampleTargets{};
      context.lobe = l < drawn.size() ? drawn[l].lobe : shadelab::LobeModel{};
      ShadowedLight light;
      light.name = scene.lights[l].name;
      light.drawnToTarget = shadelab::isDistributed(scene.lights[l].source) && context.targets.any();
      std::visit(
        shadelab::Overloaded{ [&](const shadelab::LocalEvaluation& local) { light.evaluation = local; },
          [&](const shadelab::DistributedEvaluation& distributed) { light.distributed = distributed.shadowed; },
          [](const shadelab::AmbientEvaluation&)
          { throw std::logic_error("an ambient light casts no shadows (sceneProblems refuses it)"); } },
        shadelab::prepareEvaluation(scene.lights[l].source, context));
      lights.push_back(std::move(light));
    }
  }
  return lights;
}

/// Finds the lights the mesh encloses.
void findEnclosedLights(const shadelab::OccluderMesh& occluders, std::vector<ShadowedLight>& lights)
{
  for (ShadowedLight& light : lights)
  {
    const std::optional<glm::dvec3> position = light.position();
    light.enclosed = position && shadelab::enclosesPoint(occluders, *position);
  }
}

/// What the rays write besides each light's visibility, a value per ray point in each array.
struct RayArrays
{
  shadelab::OcclusionSettings settings;
  /// The ambient occlusion's: nullptr without it (bentNormal and skyView also where not asked
  /// for, rays where the count is fixed).
  vtkSmartPointer<vtkFloatArray> occlusion, standardError, bentNormal, skyView, shortOfTarget;
  vtkSmartPointer<vtkIntArray> rays;
  vtkSmartPointer<vtkUnsignedCharArray> flags;
  /// Every array, the lights' visibility included, in the output's order.
  std::vector<vtkSmartPointer<vtkDataArray>> written;
};

/// The ambient occlusion's arrays, those settings asks for.
void addOcclusionArrays(RayArrays& arrays, const std::string& prefix, vtkIdType count)
{
  auto add = [&](shadelab::OcclusionTerm term, int components)
  {
    vtkSmartPointer<vtkFloatArray> array =
      pointArray<vtkFloatArray>(shadelab::occlusionArrayName(prefix, term), components, count);
    arrays.written.push_back(array);
    return array;
  };
  if (arrays.settings.target)
  {
    arrays.rays =
      pointArray<vtkIntArray>(shadelab::occlusionArrayName(prefix, shadelab::OcclusionTerm::Rays), 1, count);
    arrays.written.push_back(arrays.rays);
    arrays.shortOfTarget =
      pointArray<vtkFloatArray>(shadelab::occlusionArrayName(prefix, shadelab::OcclusionTerm::ShortOfTarget), 1, count);
    arrays.written.push_back(arrays.shortOfTarget);
  }
  arrays.occlusion = add(shadelab::OcclusionTerm::AmbientOcclusion, 1);
  arrays.standardError = add(shadelab::OcclusionTerm::AmbientOcclusionStdError, 1);
  if (arrays.settings.bentNormal)
  {
    arrays.bentNormal = add(shadelab::OcclusionTerm::BentNormal, 3);
  }
  if (arrays.settings.skyViewFactor)
  {
    arrays.skyView = add(shadelab::OcclusionTerm::SkyViewFactor, 1);
  }
}

/// The arrays the rays write, count values each: each light's visibility (into `lights`), the
/// ambient occlusion's where the scene has it, and the flags. Throws std::runtime_error where
/// there is not enough memory.
RayArrays allocateRayArrays(std::vector<ShadowedLight>& lights, const shadelab::Scene& scene, const std::string& prefix,
  bool bentNormal, bool skyViewFactor, vtkIdType count)
{
  RayArrays arrays;
  for (ShadowedLight& light : lights)
  {
    if (light.distributed && light.drawnToTarget)
    {
      light.terms = pointArray<vtkDoubleArray>(
        shadelab::shadowedTermsArrayName(prefix, light.name), shadelab::packedTermsSize, count);
      arrays.written.push_back(light.terms);
    }
    else if (light.distributed)
    {
      light.hidden = pointArray<vtkTypeUInt64Array>(shadelab::hiddenSamplesArrayName(prefix, light.name),
        shadelab::hiddenSampleWords(light.distributed->shadowRayCount()), count);
      arrays.written.push_back(light.hidden);
    }
    else
    {
      light.visibility = pointArray<vtkFloatArray>(
        shadelab::lightArrayName(prefix, light.name, shadelab::LightTerm::Visibility), 1, count);
      arrays.written.push_back(light.visibility);
    }
  }
  if (scene.ambientOcclusion)
  {
    arrays.settings.sampling = scene.ambientOcclusion->sampling;
    arrays.settings.maxDistance = scene.ambientOcclusion->maxDistance;
    arrays.settings.target = scene.ambientOcclusion->target;
    arrays.settings.bentNormal = bentNormal;
    arrays.settings.skyViewFactor = skyViewFactor;
    addOcclusionArrays(arrays, prefix, count);
  }
  arrays.flags = vtkSmartPointer<vtkUnsignedCharArray>::New();
  arrays.flags->SetName(shadelab::visibilityFlagsArrayName(prefix).c_str());
  if (!shadelab::allocateTuples<unsigned char>(arrays.flags, count))
  {
    throw std::runtime_error("not enough memory for the visibility flags");
  }
  arrays.written.push_back(arrays.flags);
  return arrays;
}

/// The points the rays leave from, as the rays see them: no normal (so no ray) where the kernel
/// sees none or the position is not finite; for occlusion under two-sided shading, the normal
/// turned toward the viewer, as the kernel turns it.
class RayVertices
{
public:
  RayVertices(vtkPolyData* input, const std::vector<vtkIdType>* rayPoints, const shadelab::Scene& scene)
    : twoSided(shadelab::shadesBothSides(scene))
    , shadedSide(scene.shadedSide)
    , selfShadowing(scene.selfShadowing)
    , points(vtk::DataArrayTupleRange<3>(input->GetPoints()->GetData()))
    , normals(vtk::DataArrayTupleRange<3>(input->GetPointData()->GetNormals()))
    , rayPoints(rayPoints)
    , viewer(scene.viewer)
  {
  }

  /// Whether the surface is shaded on both sides, which the rays leave from alike, and which.
  const bool twoSided;
  const shadelab::ShadedSide shadedSide;
  /// Which triangles hide a shadowed light.
  const shadelab::SelfShadowing selfShadowing;

  /// Ray point i: the input's point that rayPoints lists at i (without a list, point i), and the
  /// unit direction to the viewer from it.
  void at(vtkIdType i, shadelab::RayVertex& vertex, glm::dvec3& occlusionNormal, glm::dvec3& toViewer) const
  {
    const vtkIdType id = this->rayPoints ? (*this->rayPoints)[static_cast<std::size_t>(i)] : i;
    const auto p = this->points[id];
    const auto n = this->normals[id];
    vertex = { { p[0], p[1], p[2] }, { n[0], n[1], n[2] }, id };
    const double length2 = glm::dot(vertex.normal, vertex.normal);
    const glm::dvec3& q = vertex.position;
    const bool usable =
      length2 > 1e-12 && std::isfinite(length2) && std::isfinite(q.x) && std::isfinite(q.y) && std::isfinite(q.z);
    vertex.normal = usable ? vertex.normal / std::sqrt(length2) : glm::dvec3(0.0);
    toViewer = this->viewer.directionFrom(vertex.position);
    const bool turned =
      this->twoSided && shadelab::turnsNormalRound(glm::dot(vertex.normal, toViewer), this->shadedSide);
    occlusionNormal = turned ? -vertex.normal : vertex.normal;
    if (toViewer == glm::dvec3(0.0)) // at a local viewer: seen along its normal, as the kernel sees it
    {
      toViewer = occlusionNormal;
    }
  }

private:
  using Tuples = decltype(vtk::DataArrayTupleRange<3>(static_cast<vtkDataArray*>(nullptr)));
  const Tuples points, normals;
  const std::vector<vtkIdType>* rayPoints;
  const shadelab::Viewer& viewer;
};

constexpr int groupSize = shadelab::rayVertexGroup;

/// Up to rayVertexGroup consecutive ray points, whose rays to each light share packets.
struct RayGroup
{
  vtkIdType first = 0; // the first point's index among the ray points
  int size = 0;
  shadelab::RayVertex vertices[groupSize];
  glm::dvec3 occlusionNormals[groupSize];
  glm::dvec3 toViewer[groupSize];
};

/// Group g of the count ray points, their flags cleared for the rays to set.
void startGroup(const RayVertices& vertices, vtkIdType g, vtkIdType count, vtkUnsignedCharArray* flags, RayGroup& group)
{
  group.first = g * groupSize;
  group.size = static_cast<int>(std::min<vtkIdType>(groupSize, count - group.first));
  for (int k = 0; k < group.size; ++k)
  {
    vertices.at(group.first + k, group.vertices[k], group.occlusionNormals[k], group.toViewer[k]);
    flags->SetValue(group.first + k, 0);
  }
}

/// Adds flag to the point's flags.
void addFlag(vtkUnsignedCharArray* flags, vtkIdType i, shadelab::ShadingFlag flag)
{
  flags->SetValue(i, flags->GetValue(i) | flag);
}

/// The estimates of a distributed light drawn to a target at each of the group's points, from
/// the side the kernel shades (the occlusion normal): each point's samples drawn in rounds, each
/// round's rays traced before it is weighted. Flags the points that send a ray to a light the
/// mesh encloses.
void estimateSoftShadows(const shadelab::OccluderMesh& occluders, const ShadowedLight& light, const RayGroup& group,
  shadelab::SelfShadowing selfShadowing, vtkUnsignedCharArray* flags)
{
  std::uint64_t cast = 0;
  for (int k = 0; k < group.size; ++k)
  {
    const shadelab::RayVertex& vertex = group.vertices[k];
    double* row = light.terms->GetPointer(std::size_t(shadelab::packedTermsSize) * std::size_t(group.first + k));
    if (vertex.normal == glm::dvec3(0.0))
    {
      shadelab::packTerms({}, row); // no ray: the kernel gives the vertex no light
      continue;
    }
    const shadelab::SurfacePoint point{ vertex.position, group.occlusionNormals[k], group.toViewer[k],
      static_cast<std::uint64_t>(vertex.id) };
    shadelab::RoundShadowTracer tracer(occluders, point, vertex.id, selfShadowing);
    shadelab::packTerms(light.distributed->estimate(point, tracer), row);
    cast += tracer.cast();
    if (tracer.cast() > 0 && light.enclosed)
    {
      addFlag(flags, group.first + k, shadelab::FlagLightEnclosed);
    }
  }
  *light.raysCast += cast;
}

/// The distributed light's samples that the mesh hides from each of the group's points, from the
/// side the kernel shades (the occlusion normal), the points' rays sharing packets; flags the
/// points that send a ray to a light the mesh encloses.
void traceSoftShadows(const shadelab::OccluderMesh& occluders, const ShadowedLight& light, const RayGroup& group,
  shadelab::SelfShadowing selfShadowing, vtkUnsignedCharArray* flags)
{
  const int words = light.hidden->GetNumberOfComponents();
  shadelab::HiddenSampleTracer tracer(occluders, selfShadowing);
  for (int k = 0; k < group.size; ++k)
  {
    const shadelab::RayVertex& vertex = group.vertices[k];
    static_assert(sizeof(vtkTypeUInt64) == sizeof(std::uint64_t), "the hidden samples' words are 64 bits");
    auto* bits =
      reinterpret_cast<std::uint64_t*>(light.hidden->GetPointer(std::size_t(words) * std::size_t(group.first + k)));
    if (vertex.normal == glm::dvec3(0.0))
    {
      std::fill_n(bits, words, 0u); // no ray: the kernel gives the vertex no light
      continue;
    }
    const shadelab::SurfacePoint point{ vertex.position, group.occlusionNormals[k], glm::dvec3(0.0),
      static_cast<std::uint64_t>(vertex.id) };
    if (tracer.add(*light.distributed, point, vertex.id, bits) > 0 && light.enclosed)
    {
      addFlag(flags, group.first + k, shadelab::FlagLightEnclosed);
    }
  }
  tracer.flush();
}

/// The light's visibility from the group's points, their rays sharing packets; flags the points
/// whose own triangles hide it, and those it is hidden from when the mesh encloses it.
void traceShadows(const shadelab::OccluderMesh& occluders, const ShadowedLight& light, const RayGroup& group,
  const RayVertices& vertices, vtkUnsignedCharArray* flags)
{
  if (light.terms)
  {
    estimateSoftShadows(occluders, light, group, vertices.selfShadowing, flags);
    return;
  }
  if (light.distributed)
  {
    traceSoftShadows(occluders, light, group, vertices.selfShadowing, flags);
    return;
  }
  shadelab::LightDirection directions[groupSize];
  shadelab::LightVisibility seen[groupSize];
  for (int k = 0; k < group.size; ++k)
  {
    directions[k] = shadelab::towardLight(light.evaluation, group.vertices[k].position);
  }
  shadelab::lightVisibility(
    occluders, group.vertices, directions, group.size, vertices.twoSided, seen, vertices.selfShadowing);
  for (int k = 0; k < group.size; ++k)
  {
    const vtkIdType i = group.first + k;
    light.visibility->SetValue(i, seen[k].visible ? 1.0f : 0.0f);
    if (seen[k].blockedByOwnTriangle)
    {
      addFlag(flags, i, shadelab::FlagHiddenByOwnTriangle);
    }
    if (light.enclosed && !seen[k].visible)
    {
      addFlag(flags, i, shadelab::FlagLightEnclosed);
    }
  }
}

/// The ambient occlusion at the group's points.
void traceOcclusion(const shadelab::OccluderMesh& occluders, const RayGroup& group, const RayArrays& arrays)
{
  for (int k = 0; k < group.size; ++k)
  {
    const vtkIdType i = group.first + k;
    const shadelab::OcclusionEstimate ao = shadelab::ambientOcclusion(
      occluders, { group.vertices[k].position, group.occlusionNormals[k], group.vertices[k].id }, arrays.settings);
    arrays.occlusion->SetValue(i, static_cast<float>(ao.occlusion));
    arrays.standardError->SetValue(i, static_cast<float>(ao.standardError));
    if (arrays.rays)
    {
      const shadelab::SamplingTarget& target = *arrays.settings.target;
      arrays.rays->SetValue(i, ao.rays);
      // In float32, as ambient_occlusion_std_error holds it (and the report counts it).
      const bool above = static_cast<float>(ao.standardError) > static_cast<float>(target.standardError());
      arrays.shortOfTarget->SetValue(i, ao.rays >= target.maximum && above ? 1.0f : 0.0f);
    }
    if (arrays.bentNormal)
    {
      const glm::vec3 bent(ao.bentNormal);
      arrays.bentNormal->SetTypedTuple(i, &bent.x);
    }
    if (arrays.skyView)
    {
      arrays.skyView->SetValue(i, static_cast<float>(ao.skyViewFactor));
    }
  }
}

/// Every ray from the count ray points into the arrays, in a vtkSMPTools loop, with progress
/// reported through `filter`. Throws where the tracing failed, and shadelab::RunAborted where
/// `stoppable` and the filter was asked to abort (checked before each block).
void castRays(const shadelab::OccluderMesh& occluders, const std::vector<ShadowedLight>& lights,
  const RayArrays& arrays, const RayVertices& vertices, vtkIdType count, vtkAlgorithm* filter, bool stoppable)
{
  // Vertices in fixed groups (not split by the threads' ranges), each light's rays from a group
  // sharing packets: the same packets on any thread count (and Embree's answer to a ray does
  // not depend on its packet, HiddenSampleTracer).
  // Hundredths of the mesh at a time, so that progress is reported, and an abort heard,
  // between them within a share of a second; at least 32 groups, so that the threads' wait at
  // the end of each block stays a small part of it.
  const vtkIdType groups = (count + groupSize - 1) / groupSize;
  const vtkIdType block = std::max<vtkIdType>(groups / 100, 32);
  for (vtkIdType firstGroup = 0; firstGroup < groups; firstGroup += block)
  {
    if (stoppable && filter->GetAbortExecute())
    {
      throw shadelab::RunAborted();
    }
    const vtkIdType lastGroup = std::min(groups, firstGroup + block);
    vtkSMPTools::For(firstGroup, lastGroup,
      [&](vtkIdType beginGroup, vtkIdType endGroup)
      {
        RayGroup group;
        for (vtkIdType g = beginGroup; g < endGroup; ++g)
        {
          startGroup(vertices, g, count, arrays.flags, group);
          for (const ShadowedLight& light : lights)
          {
            traceShadows(occluders, light, group, vertices, arrays.flags);
          }
          if (arrays.occlusion)
          {
            traceOcclusion(occluders, group, arrays);
          }
        }
      });
    filter->UpdateProgress(static_cast<double>(lastGroup) / groups);
  }
  occluders.checkTracing();
}

/// How long the BVH (unless reused) and the rays took.
struct RayTimes
{
  bool reused = false;
  double buildSeconds = 0;
  double raySeconds = 0;
};

/// What the ambient occlusion drawn to a target cast: rays per vertex, and the vertices that
/// stopped at the maximum short of the target.
std::string occlusionRaysReport(const RayArrays& arrays, vtkIdType count)
{
  const shadelab::SamplingTarget& target = *arrays.settings.target;
  std::uint64_t total = 0;
  int fewest = target.maximum, most = 0;
  vtkIdType short_ = 0;
  for (vtkIdType i = 0; i < count; ++i)
  {
    const int rays = arrays.rays->GetValue(i);
    total += static_cast<std::uint64_t>(rays);
    fewest = std::min(fewest, rays);
    most = std::max(most, rays);
    short_ += arrays.shortOfTarget->GetValue(i) == 1.0f ? 1 : 0;
  }
  std::ostringstream report;
  report << "Ambient occlusion to within " << target.error << " at 95% (standard error at most "
         << target.standardError() << "): " << total << " rays, " << double(total) / double(count) << " per vertex ("
         << fewest << " to " << most << ")" << (arrays.settings.skyViewFactor ? ", and the sky view factor's own" : "")
         << ".";
  if (short_ > 0)
  {
    report << " " << short_ << " vertices reached the maximum of " << target.maximum
           << " rays short of the target (ambient_occlusion_short_of_target 1, their ambient_occlusion_std_error above "
           << target.standardError() << "): raise \"max_rays\".";
  }
  return report.str();
}

/// The report of a run that cast rays: how many, against how many triangles, and how long.
std::string raysReport(const RayArrays& arrays, const std::vector<ShadowedLight>& lights, vtkIdType count,
  std::size_t triangles, const RayTimes& times)
{
  std::uint64_t lightRays = 0;
  for (const ShadowedLight& light : lights)
  {
    if (!light.drawnToTarget)
    {
      lightRays += light.distributed ? static_cast<std::uint64_t>(light.distributed->shadowRayCount()) : 1;
    }
  }
  const bool fixedOcclusion = arrays.occlusion && !arrays.settings.target;
  const std::uint64_t raysPerVertex = lightRays +
    (fixedOcclusion
        ? static_cast<std::uint64_t>(arrays.settings.sampling.samples) * (arrays.settings.skyViewFactor ? 2 : 1)
        : 0);
  std::ostringstream report;
  report << "Cast ";
  if (raysPerVertex > 0)
  {
    const bool drawnToTargets = arrays.rays ||
      std::any_of(lights.begin(), lights.end(), [](const ShadowedLight& light) { return light.drawnToTarget; });
    report << "up to " << raysPerVertex * static_cast<std::uint64_t>(count) << " rays (" << raysPerVertex
           << " per vertex" << (drawnToTargets ? ", and those drawn to targets below" : "") << ")";
  }
  else
  {
    report << "the rays drawn to targets (below)";
  }
  report << " against " << triangles << " triangles: BVH "
         << (times.reused ? "reused" : "built in " + std::to_string(times.buildSeconds) + " s") << ", rays "
         << times.raySeconds << " s.";
  if (arrays.rays)
  {
    report << " " << occlusionRaysReport(arrays, count);
  }
  for (const ShadowedLight& light : lights)
  {
    if (light.drawnToTarget)
    {
      report << " The light '" << light.name << "', drawn to its target round by round: " << light.raysCast->load()
             << " shadow rays, " << double(light.raysCast->load()) / double(count) << " per vertex.";
    }
  }
  for (const ShadowedLight& light : lights)
  {
    if (light.enclosed)
    {
      report << " The light '" << light.name << "' is inside the mesh (every ray from it meets a triangle): no vertex "
             << "outside gets its light (shading_flags 128).";
    }
  }
  return report.str();
}
}

vtkMeshVisibilityFilter::vtkMeshVisibilityFilter()
  : Controller(vtkMultiProcessController::GetGlobalController())
{
}
vtkMeshVisibilityFilter::~vtkMeshVisibilityFilter() = default;

namespace
{
/// The newest modification time of what the rays see of the mesh.
vtkMTimeType geometryTime(vtkPolyData* mesh)
{
  vtkMTimeType newest = std::max(mesh->GetPoints()->GetMTime(), mesh->GetPoints()->GetData()->GetMTime());
  for (vtkCellArray* cells : { mesh->GetPolys(), mesh->GetStrips() })
  {
    // VTK 9.1's vtkCellArray::GetMTime does not look at its arrays.
    newest = std::max(
      { newest, cells->GetMTime(), cells->GetOffsetsArray()->GetMTime(), cells->GetConnectivityArray()->GetMTime() });
  }
  return newest;
}
}

const shadelab::OccluderMesh& vtkMeshVisibilityFilter::OccludersFor(vtkPolyData* mesh, bool& reused)
{
  BuiltOccluders& built = this->Built;
  reused = built.occluders && built.points == mesh->GetPoints() && built.polys == mesh->GetPolys() &&
    built.strips == mesh->GetStrips() && geometryTime(mesh) <= built.builtAfter;
  if (!reused)
  {
    built = {};
    built.occluders = shadelab::occludersOf(mesh);
    built.points = mesh->GetPoints();
    built.polys = mesh->GetPolys();
    built.strips = mesh->GetStrips();
    built.builtAfter = geometryTime(mesh);
  }
  return *built.occluders;
}

int vtkMeshVisibilityFilter::RequestData(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  return shadelab::runWithThreads(this->NumberOfThreads, [&] { return this->CastRays(inputVector, outputVector); });
}

int vtkMeshVisibilityFilter::CastRays(vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  vtkPolyData* input = vtkPolyData::GetData(inputVector[0]);
  vtkPolyData* output = vtkPolyData::GetData(outputVector);
  this->ForgetSceneProblem();
  this->Report.clear();
  this->RaySeconds = 0;
  // A split mesh's processes must all take part in its exchanges: only a whole mesh stops.
  this->Stoppable = !shadelab::isPieceOfSplitMesh(this->Controller, input);
  if (this->Stoppable)
  {
    const int result = this->CastRaysFrom(input, output, this->RayPointIds.empty() ? nullptr : &this->RayPointIds);
    if (this->GetAbortExecute()) // not generated, so that the next update runs again
    {
      outputVector->GetInformationObject(0)->Set(vtkDemandDrivenPipeline::DATA_NOT_GENERATED(), 1);
    }
    return result;
  }
  // Every process holds every triangle, which its own points' rays may meet.
  return shadelab::computeOnPiece(this->Controller, this, input, output, true, shadelab::WholeMeshOn::EveryProcess,
    [this](vtkPolyData* mesh, vtkPolyData* result, const std::vector<vtkIdType>* pieceIds)
    { return this->CastRaysFrom(mesh, result, pieceIds) == 1; });
}

int vtkMeshVisibilityFilter::CastRaysFrom(
  vtkPolyData* input, vtkPolyData* output, const std::vector<vtkIdType>* rayPoints)
{
  const vtkIdType count = rayPoints ? static_cast<vtkIdType>(rayPoints->size()) : input->GetNumberOfPoints();
  if (count == 0)
  {
    output->ShallowCopy(input);
    return 1; // nothing to see, and no error: VTK's convention
  }
  const std::string problem = this->InputProblem(input);
  if (!problem.empty())
  {
    vtkErrorMacro(<< problem);
    return 0;
  }
  const std::optional<shadelab::Scene> scene = this->PlacedScene(input);
  if (!scene)
  {
    return 0;
  }
  output->ShallowCopy(input); // checked: every input array passes through
  std::vector<ShadowedLight> lights = shadowedLights(*scene, this->DrawnLights);
  if (lights.empty() && !scene->ambientOcclusion)
  {
    this->Report = "Nothing to cast rays for: no light has shadows and the scene has no ambient occlusion.";
    return 1;
  }

  RayTimes times;
  const shadelab::OccluderMesh* occluders = nullptr;
  RayArrays arrays;
  try
  {
    const auto buildStart = std::chrono::steady_clock::now();
    occluders = &this->OccludersFor(input, times.reused);
    times.buildSeconds = secondsSince(buildStart);
    findEnclosedLights(*occluders, lights);
    arrays =
      allocateRayArrays(lights, *scene, this->ArrayPrefix, this->ComputeBentNormal, this->ComputeSkyViewFactor, count);
    const auto raysStart = std::chrono::steady_clock::now();
    castRays(*occluders, lights, arrays, RayVertices(input, rayPoints, *scene), count, this, this->Stoppable);
    times.raySeconds = secondsSince(raysStart);
  }
  catch (const shadelab::RunAborted&) // an empty output, and no error
  {
    output->Initialize();
    this->Report = "Aborted.";
    return 1;
  }
  catch (const std::exception& error) // Embree's, no memory for the triangles or the arrays, or a ray's failure
  {
    output->Initialize();
    vtkErrorMacro(<< error.what());
    return 0;
  }
  for (const auto& array : arrays.written)
  {
    output->GetPointData()->AddArray(array);
  }
  this->Report = raysReport(arrays, lights, count, occluders->triangleCount(), times);
  this->RaySeconds = times.raySeconds;
  shadelab::addFieldNote(output, shadelab::visibilityNoteName, { this->Report });
  return 1;
}

std::string vtkMeshVisibilityFilter::InputProblem(vtkPolyData* input) const
{
  const std::string cells = this->CheckCells ? shadelab::cellProblem(input) : std::string();
  if (!cells.empty())
  {
    return cells;
  }
  vtkDataArray* normals = input->GetPointData()->GetNormals();
  if (!normals || normals->GetNumberOfComponents() != 3 || normals->GetNumberOfTuples() != input->GetNumberOfPoints())
  {
    return "the mesh needs one 3-component point normal per point to cast rays from: run "
           "vtkShadingNormalsFilter first (vtkLocalReflectanceFilter does)";
  }
  return "";
}

std::optional<shadelab::Scene> vtkMeshVisibilityFilter::PlacedScene(vtkPolyData* input)
{
  const std::optional<shadelab::Scene> given = this->ReportedScene(this->ReadScene());
  if (!given)
  {
    return std::nullopt;
  }
  // The mesh's extent only where the scene is in its frame (a pass over the points).
  const shadelab::Scene scene =
    given->frame == shadelab::SceneFrame::Mesh ? shadelab::placedOnMesh(*given, shadelab::meshExtentOf(input)) : *given;
  if (!this->SceneIsValid(shadelab::sceneProblems(scene)))
  {
    return std::nullopt;
  }
  std::vector<shadelab::SceneProblem> untargeted = shadelab::untargetedSamplingProblems(scene, true);
  for (std::size_t l = 0; l < scene.lights.size() && untargeted.empty(); ++l)
  {
    const shadelab::Sampling* sampling = shadelab::samplingOf(scene.lights[l].source);
    if (scene.lights[l].shadows && sampling && sampling->fromTolerance &&
      !(l < this->DrawnLights.size() && this->DrawnLights[l].targets.any()))
    {
      untargeted.push_back({ "/lights/" + std::to_string(l) + "/samples",
        "\"auto\" with shadows takes the count of light '" + scene.lights[l].name +
          "' from a tolerance's plan: "
          "shade it with vtkLocalReflectanceFilter under a tolerance (shadelab shade --tolerance), or give it a number "
          "of samples" });
    }
  }
  return this->SceneIsValid(untargeted) ? std::optional<shadelab::Scene>(scene) : std::nullopt;
}

void vtkMeshVisibilityFilter::SetRayPointIds(const std::vector<vtkIdType>& ids)
{
  if (ids != this->RayPointIds)
  {
    this->RayPointIds = ids;
    this->Modified();
  }
}

void vtkMeshVisibilityFilter::SetDrawnLights(const std::vector<DrawnLight>& lights)
{
  this->DrawnLights = lights;
  this->Modified();
}

void vtkMeshVisibilityFilter::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "NumberOfThreads: " << this->NumberOfThreads << "\n";
  os << indent << "ArrayPrefix: " << this->ArrayPrefix << "\n";
  os << indent << "ComputeBentNormal: " << this->ComputeBentNormal << "\n";
  os << indent << "ComputeSkyViewFactor: " << this->ComputeSkyViewFactor << "\n";
  os << indent << "CheckCells: " << this->CheckCells << "\n";
}
