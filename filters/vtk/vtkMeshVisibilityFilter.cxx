#include "vtkMeshVisibilityFilter.h"

#include "ArrayCatalog.h"
#include "ShadeLabFieldNotes.h"
#include "ShadeLabThreadCount.h"
#include "ShadeLabLargeArrays.h"
#include "ShadeLabMeshChecks.h"
#include "ShadeLabMeshExtent.h"
#include "ShadeLabMeshPolygons.h"
#include "ShadeLabWholeMesh.h"
#include "ShadingFlags.h"
#include "SceneFrame.h"
#include "Visibility.h"

#include "vtkDataArrayRange.h"
#include "vtkFloatArray.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkSMPTools.h"
#include "vtkUnsignedCharArray.h"

#include <glm/geometric.hpp>

#include <algorithm>
#include <chrono>
#include <memory>
#include <optional>
#include <sstream>

vtkStandardNewMacro(vtkMeshVisibilityFilter);

namespace
{
/// A light whose shadows the mesh casts, as the rays see it.
struct ShadowedLight
{
  std::string name;
  shadelab::LocalEvaluation evaluation;
  vtkSmartPointer<vtkFloatArray> visibility;

  /// The unit direction to the light from p, and how far it is.
  shadelab::LightDirection towardLight(const glm::dvec3& p) const
  {
    if (evaluation.geometry == shadelab::LocalEvaluation::Geometry::Distant)
    {
      return { evaluation.toLight, std::numeric_limits<double>::infinity() };
    }
    const glm::dvec3 d = evaluation.position - p;
    const double distance = glm::length(d);
    return { distance > 0 ? d / distance : glm::dvec3(0.0), distance };
  }
};

/// A float32 array of count tuples in huge pages; throws std::runtime_error naming it when
/// there is not enough memory.
vtkSmartPointer<vtkFloatArray> floatArray(const std::string& name, int components, vtkIdType count)
{
  auto array = vtkSmartPointer<vtkFloatArray>::New();
  array->SetName(name.c_str());
  array->SetNumberOfComponents(components);
  if (!shadelab::allocateTuples<float>(array, count))
  {
    throw std::runtime_error("not enough memory for the array '" + name + "'");
  }
  return array;
}

double secondsSince(std::chrono::steady_clock::time_point start)
{
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
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
    newest = std::max({ newest, cells->GetMTime(), cells->GetOffsetsArray()->GetMTime(),
      cells->GetConnectivityArray()->GetMTime() });
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
    const shadelab::MeshPolygons polygons(mesh);
    shadelab::visitPackedPoints(mesh->GetPoints()->GetData(),
      [&](auto points)
      {
        built.occluders = std::make_unique<shadelab::OccluderMesh>(
          points, static_cast<std::size_t>(mesh->GetNumberOfPoints()), polygons.list());
      });
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
  this->Report.clear();
  if (!shadelab::isPieceOfSplitMesh(this->Controller, input))
  {
    return this->CastRaysFrom(input, output, nullptr);
  }
  // Every process holds every triangle, which its own points' rays may meet.
  return shadelab::computeOnPiece(this->Controller, this, input, output, true, shadelab::WholeMeshOn::EveryProcess,
    [this](vtkPolyData* mesh, vtkPolyData* result, const std::vector<vtkIdType>* pieceIds)
    { return this->CastRaysFrom(mesh, result, pieceIds) == 1; });
}

int vtkMeshVisibilityFilter::CastRaysFrom(vtkPolyData* input, vtkPolyData* output, const std::vector<vtkIdType>* rayPoints)
{
  const vtkIdType pointCount = input->GetNumberOfPoints();
  const vtkIdType count = rayPoints ? static_cast<vtkIdType>(rayPoints->size()) : pointCount;
  if (count == 0)
  {
    output->ShallowCopy(input);
    return 1; // nothing to see, and no error: VTK's convention
  }
  const std::string cells = this->CheckCells ? shadelab::cellProblem(input) : std::string();
  if (!cells.empty())
  {
    vtkErrorMacro(<< cells);
    return 0;
  }
  vtkDataArray* normalArray = input->GetPointData()->GetNormals();
  if (!normalArray || normalArray->GetNumberOfComponents() != 3 || normalArray->GetNumberOfTuples() != pointCount)
  {
    vtkErrorMacro("the mesh needs one 3-component point normal per point to cast rays from: run "
                  "vtkShadingNormalsFilter first (vtkLocalReflectanceFilter does)");
    return 0;
  }
  const std::optional<shadelab::Scene> given = this->ReportedScene(this->ReadScene());
  if (!given)
  {
    return 0;
  }
  // The mesh's extent only where the scene is in its frame (a pass over the points).
  const shadelab::Scene scene =
    given->frame == shadelab::SceneFrame::Mesh ? shadelab::placedOnMesh(*given, shadelab::meshExtentOf(input)) : *given;
  const std::vector<shadelab::SceneProblem> problems = shadelab::sceneProblems(scene);
  if (!problems.empty())
  {
    vtkErrorMacro("scene " << problems.front().path << ": " << problems.front().message);
    return 0;
  }
  output->ShallowCopy(input); // checked: every input array passes through
  std::vector<ShadowedLight> lights;
  shadelab::EvaluationContext context;
  context.lineOfSight = scene.viewer.lineOfSight();
  for (std::size_t l = 0; l < scene.lights.size(); ++l)
  {
    if (scene.lights[l].shadows)
    {
      context.lightIndex = l;
      // sceneProblems allows shadows on local lights only.
      lights.push_back({ scene.lights[l].name,
        std::get<shadelab::LocalEvaluation>(shadelab::prepareEvaluation(scene.lights[l].source, context)), nullptr });
    }
  }
  if (lights.empty() && !scene.ambientOcclusion)
  {
    this->Report = "Nothing to cast rays for: no light has shadows and the scene has no ambient occlusion.";
    return 1;
  }

  const auto buildStart = std::chrono::steady_clock::now();
  bool reused = false;
  const shadelab::OccluderMesh* occluders = nullptr;
  try
  {
    occluders = &this->OccludersFor(input, reused);
  }
  catch (const std::exception& error) // Embree's, or no memory for the triangles
  {
    output->Initialize();
    vtkErrorMacro(<< error.what());
    return 0;
  }
  const double buildSeconds = secondsSince(buildStart);

  std::vector<vtkSmartPointer<vtkDataArray>> written;
  vtkSmartPointer<vtkFloatArray> occlusion, standardError, bentNormal, skyView;
  vtkSmartPointer<vtkUnsignedCharArray> flags;
  shadelab::OcclusionSettings settings;
  try
  {
    for (ShadowedLight& light : lights)
    {
      light.visibility = floatArray(
        shadelab::lightArrayName(this->ArrayPrefix, light.name, shadelab::LightTerm::Visibility), 1, count);
      written.push_back(light.visibility);
    }
    if (scene.ambientOcclusion)
    {
      settings.sampling = scene.ambientOcclusion->sampling;
      settings.maxDistance = scene.ambientOcclusion->maxDistance;
      settings.bentNormal = this->ComputeBentNormal;
      settings.skyViewFactor = this->ComputeSkyViewFactor;
      using shadelab::OcclusionTerm;
      occlusion = floatArray(shadelab::occlusionArrayName(this->ArrayPrefix, OcclusionTerm::AmbientOcclusion), 1, count);
      standardError = floatArray(shadelab::occlusionArrayName(this->ArrayPrefix, OcclusionTerm::AmbientOcclusionStdError), 1, count);
      written.insert(written.end(), { occlusion, standardError });
      if (settings.bentNormal)
      {
        bentNormal = floatArray(shadelab::occlusionArrayName(this->ArrayPrefix, OcclusionTerm::BentNormal), 3, count);
        written.push_back(bentNormal);
      }
      if (settings.skyViewFactor)
      {
        skyView = floatArray(shadelab::occlusionArrayName(this->ArrayPrefix, OcclusionTerm::SkyViewFactor), 1, count);
        written.push_back(skyView);
      }
    }
    flags = vtkSmartPointer<vtkUnsignedCharArray>::New();
    flags->SetName(shadelab::visibilityFlagsArrayName(this->ArrayPrefix).c_str());
    if (!shadelab::allocateTuples<unsigned char>(flags, count))
    {
      throw std::runtime_error("not enough memory for the visibility flags");
    }
    written.push_back(flags);
  }
  catch (const std::exception& error)
  {
    output->Initialize();
    vtkErrorMacro(<< error.what());
    return 0;
  }

  const bool twoSided = scene.material.twoSided || scene.model == shadelab::ShadingModel::VtkOpenGL2;
  const auto points = vtk::DataArrayTupleRange<3>(input->GetPoints()->GetData());
  const auto normals = vtk::DataArrayTupleRange<3>(normalArray);
  // Vertex i as the rays see it: no normal (so no ray) where the kernel sees none or the
  // position is not finite; for occlusion under two-sided shading, the normal turned toward
  // the viewer, as the kernel turns it.
  auto rayVertex = [&](vtkIdType i, shadelab::RayVertex& vertex, glm::dvec3& occlusionNormal)
  {
    const vtkIdType id = rayPoints ? (*rayPoints)[static_cast<std::size_t>(i)] : i;
    const auto p = points[id];
    const auto n = normals[id];
    vertex = { { p[0], p[1], p[2] }, { n[0], n[1], n[2] }, id };
    const double length2 = glm::dot(vertex.normal, vertex.normal);
    const glm::dvec3& q = vertex.position;
    const bool usable = length2 > 1e-12 && std::isfinite(length2) && std::isfinite(q.x) && std::isfinite(q.y) && std::isfinite(q.z);
    vertex.normal = usable ? vertex.normal / std::sqrt(length2) : glm::dvec3(0.0);
    const glm::dvec3 towardViewer = scene.viewer.position ? *scene.viewer.position - vertex.position : -scene.viewer.viewDirection;
    occlusionNormal = twoSided && glm::dot(vertex.normal, towardViewer) < 0 ? -vertex.normal : vertex.normal;
  };
  const auto raysStart = std::chrono::steady_clock::now();
  // Vertices in fixed groups of 16 (not split by the threads' ranges), each light's rays from a
  // group traced as one packet: the same packets, and so the same bits, on any thread count.
  // Tenths of the mesh at a time, so that progress is reported between them.
  constexpr int group = shadelab::OccluderMesh::bundleSize;
  const vtkIdType groups = (count + group - 1) / group;
  const vtkIdType block = std::max<vtkIdType>(groups / 10, 64);
  try
  {
    for (vtkIdType firstGroup = 0; firstGroup < groups; firstGroup += block)
    {
      const vtkIdType lastGroup = std::min(groups, firstGroup + block);
      vtkSMPTools::For(firstGroup, lastGroup,
        [&](vtkIdType beginGroup, vtkIdType endGroup)
        {
          shadelab::RayVertex vertices[group];
          glm::dvec3 occlusionNormals[group];
          shadelab::LightDirection directions[group];
          shadelab::LightVisibility seen[group];
          for (vtkIdType g = beginGroup; g < endGroup; ++g)
          {
            const vtkIdType first = g * group;
            const int size = static_cast<int>(std::min<vtkIdType>(group, count - first));
            for (int k = 0; k < size; ++k)
            {
              rayVertex(first + k, vertices[k], occlusionNormals[k]);
              flags->SetValue(first + k, 0);
            }
            for (const ShadowedLight& light : lights)
            {
              for (int k = 0; k < size; ++k)
              {
                directions[k] = light.towardLight(vertices[k].position);
              }
              shadelab::lightVisibility(*occluders, vertices, directions, size, twoSided, seen);
              for (int k = 0; k < size; ++k)
              {
                light.visibility->SetValue(first + k, seen[k].visible ? 1.0f : 0.0f);
                if (seen[k].blockedByOwnTriangle)
                {
                  flags->SetValue(first + k, flags->GetValue(first + k) | shadelab::FlagHiddenByOwnTriangle);
                }
              }
            }
            for (int k = 0; occlusion && k < size; ++k)
            {
              const vtkIdType i = first + k;
              const shadelab::OcclusionEstimate ao = shadelab::ambientOcclusion(
                *occluders, { vertices[k].position, occlusionNormals[k], vertices[k].id }, settings);
              occlusion->SetValue(i, static_cast<float>(ao.occlusion));
              standardError->SetValue(i, static_cast<float>(ao.standardError));
              if (bentNormal)
              {
                const glm::vec3 bent(ao.bentNormal);
                bentNormal->SetTypedTuple(i, &bent.x);
              }
              if (skyView)
              {
                skyView->SetValue(i, static_cast<float>(ao.skyViewFactor));
              }
            }
          }
        });
      this->UpdateProgress(static_cast<double>(lastGroup) / groups);
    }
    occluders->checkTracing();
  }
  catch (const std::exception& error)
  {
    output->Initialize();
    vtkErrorMacro(<< error.what());
    return 0;
  }
  const double raySeconds = secondsSince(raysStart);
  for (const auto& array : written)
  {
    output->GetPointData()->AddArray(array);
  }
  const std::uint64_t raysPerVertex = lights.size() +
    (occlusion ? static_cast<std::uint64_t>(settings.sampling.samples) * (settings.skyViewFactor ? 2 : 1) : 0);
  std::ostringstream report;
  report << "Cast up to " << raysPerVertex * static_cast<std::uint64_t>(count) << " rays (" << raysPerVertex
         << " per vertex) against " << occluders->triangleCount() << " triangles: BVH "
         << (reused ? "reused" : "built in " + std::to_string(buildSeconds) + " s") << ", rays " << raySeconds << " s.";
  this->Report = report.str();
  shadelab::addFieldNote(output, shadelab::visibilityNoteName, { this->Report });
  return 1;
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
