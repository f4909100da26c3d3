#include "vtkLocalReflectanceFilter.h"

#include "ArrayCatalog.h"
#include "MethodChoice.h"
#include "SceneFrame.h"
#include "ShadeLabFieldNotes.h"
#include "ShadeLabImportedParts.h"
#include "ShadeLabIndirectLight.h"
#include "ShadeLabMaterialArrays.h"
#include "ShadeLabMeshChecks.h"
#include "ShadeLabMeshExtent.h"
#include "ShadeLabMeshPolygons.h"
#include "ShadeLabRunAborted.h"
#include "ShadeLabShadedArrays.h"
#include "ShadeLabThreadCount.h"
#include "ShadeLabWholeMesh.h"
#include "ShadingKernel.h"
#include "vtkLocalReflectanceFilterInternals.h"

#include "vtkCellArray.h"
#include "vtkCellData.h"
#include "vtkCommand.h"
#include "vtkCommunicator.h"
#include "vtkDemandDrivenPipeline.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkSMPTools.h"
#include "vtkSmartPointer.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <sstream>
#include <stdexcept>

vtkStandardNewMacro(vtkLocalReflectanceFilter);

using namespace shadelab::shading;

vtkLocalReflectanceFilter::vtkLocalReflectanceFilter()
  : Controller(vtkMultiProcessController::GetGlobalController())
  , Internals(std::make_unique<vtkInternals>())
{
  // The steps run over this filter's processes only on a split mesh (ShadeMesh sets them).
  this->Internals->NormalsStep->SetController(nullptr);
  this->Internals->VisibilityStep->SetController(nullptr);
  this->AvailableArrays->AddObserver(
    vtkCommand::ModifiedEvent, this, &vtkLocalReflectanceFilter::AvailableArraysChanged);
  this->Internals->NormalsStep->AddObserver(
    vtkCommand::ProgressEvent, this, &vtkLocalReflectanceFilter::ForwardStepProgress);
  this->Internals->VisibilityStep->AddObserver(
    vtkCommand::ProgressEvent, this, &vtkLocalReflectanceFilter::ForwardStepProgress);
  this->Internals->InterreflectionStep->AddObserver(
    vtkCommand::ProgressEvent, this, &vtkLocalReflectanceFilter::ForwardStepProgress);
}

void vtkLocalReflectanceFilter::ForwardStepProgress(vtkObject* step, unsigned long, void* done)
{
  if (this->Internals->ProgressSpan > 0)
  {
    this->UpdateProgress(this->Internals->ProgressStart + this->Internals->ProgressSpan * *static_cast<double*>(done));
  }
  if (this->Internals->Stoppable && this->GetAbortExecute())
  {
    static_cast<vtkAlgorithm*>(step)->SetAbortExecute(1);
  }
}

void vtkLocalReflectanceFilter::ReportProgress(double done)
{
  this->UpdateProgress(this->Internals->ProgressStart + this->Internals->ProgressSpan * done);
  this->StopIfAborted();
}

void vtkLocalReflectanceFilter::StopIfAborted()
{
  if (this->Internals->Stoppable && this->GetAbortExecute())
  {
    throw shadelab::RunAborted();
  }
}

void vtkLocalReflectanceFilter::StartStep(double start, double span)
{
  this->Internals->ProgressStart = start;
  this->Internals->ProgressSpan = span;
  this->StopIfAborted();
}

vtkLocalReflectanceFilter::~vtkLocalReflectanceFilter() = default;

void vtkLocalReflectanceFilter::SetLightMethods(const std::vector<shadelab::LightMethod>& methods)
{
  this->LightMethods = methods;
  this->Modified();
}

namespace
{
/// What makes the mesh's structure unusable (its coordinates are checked against the precision
/// apart), or "" when there is nothing.
std::string meshProblem(vtkPolyData* input)
{
  const vtkIdType pointCount = input->GetNumberOfPoints();
  std::ostringstream problem;
  if (input->GetNumberOfPolys() + input->GetNumberOfStrips() == 0)
  {
    problem << "the mesh has no polygons (" << input->GetNumberOfCells()
            << " vertex or line cells): surface shading needs a surface";
    return problem.str();
  }
  const std::string cells = shadelab::cellProblem(input);
  if (!cells.empty())
  {
    return cells;
  }
  vtkDataArray* normals = input->GetPointData()->GetNormals();
  if (normals && (normals->GetNumberOfComponents() != 3 || normals->GetNumberOfTuples() != pointCount))
  {
    problem << "the point normals '" << (normals->GetName() ? normals->GetName() : "") << "' have "
            << normals->GetNumberOfTuples() << " tuples of " << normals->GetNumberOfComponents()
            << " components: there must be one 3-component normal per point (" << pointCount << ")";
    return problem.str();
  }
  return "";
}
}

int vtkLocalReflectanceFilter::RequestData(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  return shadelab::runWithThreads(this->NumberOfThreads, [&] { return this->Shade(inputVector, outputVector); });
}

int vtkLocalReflectanceFilter::Shade(vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  vtkPolyData* input = vtkPolyData::GetData(inputVector[0]);
  vtkPolyData* output = vtkPolyData::GetData(outputVector);
  this->ForgetSceneProblem();
  this->NormalsReport.clear();
  this->VisibilityReport.clear();
  // A split mesh's processes must all take part in its exchanges: only a whole mesh stops.
  this->Internals->Stoppable = !shadelab::isPieceOfSplitMesh(this->Controller, input);
  if (this->Internals->Stoppable)
  {
    try
    {
      return this->ShadeMesh(input, output, shadelab::MeshPieces{});
    }
    catch (const shadelab::RunAborted&) // an empty output, and no error
    {
      output->Initialize();
      this->SamplingReport.clear();
      // Not generated, so that the next update runs again, and the steps with it.
      outputVector->GetInformationObject(0)->Set(vtkDemandDrivenPipeline::DATA_NOT_GENERATED(), 1);
      this->Internals->NormalsStep->Modified();
      this->Internals->VisibilityStep->Modified();
      return 1;
    }
  }
  const shadelab::PieceLayout layout = shadelab::pieceLayout(this->Controller, input);
  if (!layout.problem.empty())
  {
    vtkErrorMacro(<< layout.problem); // on every process alike
    return 0;
  }
  // Pieces not put together: one process holds the whole mesh, and shades it alone.
  const shadelab::MeshPieces pieces =
    layout.putTogether ? shadelab::MeshPieces{ this->Controller, &layout } : shadelab::MeshPieces{};
  const bool shaded = this->ShadeMesh(input, output, pieces) == 1;
  return shadelab::agreedOutcome(this->Controller, this, output, shaded);
}

namespace
{
/// The share of a run's progress that preparing the normals takes.
constexpr double normalsShare = 0.05;

/// The share the rays take: most of the run where each vertex casts many (ambient occlusion, an
/// area light's or a map's shadows), a quarter where it casts one per light, none without rays.
double raysShareOf(const shadelab::Scene& scene)
{
  if (!scene.needsVisibility())
  {
    return 0;
  }
  const bool manyRays = scene.ambientOcclusion ||
    std::any_of(scene.lights.begin(), scene.lights.end(),
      [](const shadelab::NamedLight& light) { return light.shadows && shadelab::isDistributed(light.source); });
  return manyRays ? 0.75 : 0.25;
}

/// Whether the tolerance's plan samples to targets (none without a tolerance: CheckLightMethods
/// forgets the last plan): each vertex's standard error is then kept for the estimate after
/// sampling, and the cost forecast.
bool planSamples(const std::optional<shadelab::MethodPlan>& plan)
{
  return plan && plan->samplingError > 0;
}

}

int vtkLocalReflectanceFilter::ShadeMesh(vtkPolyData* input, vtkPolyData* output, const shadelab::MeshPieces& pieces)
{
  // A piece without points still takes part in its steps' exchanges, and shades nothing.
  const bool empty = input->GetNumberOfPoints() == 0;
  if (empty && !pieces.split())
  {
    output->ShallowCopy(input); // nothing in, nothing out, and no error: VTK's convention
    return 1;
  }
  this->Internals->NormalsStep->SetController(pieces.processes);
  this->Internals->VisibilityStep->SetController(pieces.processes);
  std::optional<ShadingPlan> plan = this->PlanShading(input, pieces);
  if (!plan || !this->ReadMaterialArrays(input, pieces, *plan))
  {
    return 0;
  }

  output->ShallowCopy(input);
  this->StartStep(0, normalsShare);
  vtkDataArray* shadingNormals = this->PrepareNormals(input, output, pieces);
  // The step failed (on a split mesh, on every process, having said why). An empty piece has
  // none where the others kept their own.
  if (!pieces.holdEverywhere(shadingNormals || empty))
  {
    output->Initialize();
    vtkErrorMacro("preparing the normals failed (see the error above)");
    return 0;
  }
  if (this->Tolerance > 0 && !this->ChooseMethodsOnSample(input, shadingNormals, *plan, pieces))
  {
    output->Initialize();
    return 0;
  }
  SamplingOutcome sampling;
  std::vector<vtkSmartPointer<vtkDataArray>> arrays;
  std::string failure;
  try
  {
    if (this->Tolerance > 0)
    {
      this->ForecastAndAnnounce(input, shadingNormals, *plan, pieces, sampling);
    }
    arrays = this->RaysAndArrays(input, shadingNormals, *plan, pieces, sampling);
  }
  catch (const shadelab::RunAborted&)
  {
    throw; // for Shade to leave an empty output
  }
  catch (const std::exception& error) // an array, or anything else, that could not be allocated
  {
    failure = error.what();
  }
  failure = this->ReportSampling(*plan, pieces, sampling, failure);
  if (!failure.empty())
  {
    output->Initialize();
    vtkErrorMacro(<< failure);
    return 0;
  }
  for (const auto& array : arrays)
  {
    output->GetPointData()->AddArray(array);
  }
  if (!empty)
  {
    this->AddFieldNotes(output);
  }
  return 1;
}

bool vtkLocalReflectanceFilter::ChooseMethodsOnSample(
  vtkPolyData* input, vtkDataArray* shadingNormals, ShadingPlan& plan, const shadelab::MeshPieces& pieces)
{
  // What float32 rounds and what the pow approximations err are measured on a sample of the
  // points, with the normals they are shaded with, and the methods chosen again with them (the
  // same outcome on every process, which all measure the same).
  this->MeasureOnSample(this->SamplePoints(input, shadingNormals, plan, pieces), plan, pieces);
  return this->ChooseMethods(plan, false);
}

void vtkLocalReflectanceFilter::ForecastAndAnnounce(vtkPolyData* input, vtkDataArray* shadingNormals,
  const ShadingPlan& plan, const shadelab::MeshPieces& pieces, SamplingOutcome& sampling)
{
  // Where the plan samples (the same on every process), each vertex's standard error is kept
  // for the estimate after sampling, and its samples counted against the forecast.
  const std::size_t points = static_cast<std::size_t>(input->GetNumberOfPoints());
  const bool samples = planSamples(this->MethodPlan);
  sampling.standardError.resize(samples ? points : 0);
  this->StartStep(normalsShare, 0); // a forecast's pilot moves no progress bar
  this->MethodPlan->forecast = samples ? this->ForecastCost(input, shadingNormals, plan, pieces) : std::nullopt;
  sampling.samplesDrawn.resize(this->MethodPlan->forecast ? points : 0);
  this->InvokeEvent(MethodsChosenEvent);
}

std::vector<vtkSmartPointer<vtkDataArray>> vtkLocalReflectanceFilter::RaysAndArrays(vtkPolyData* input,
  vtkDataArray* shadingNormals, const ShadingPlan& plan, const shadelab::MeshPieces& pieces, SamplingOutcome& sampling)
{
  // Progress: the normals, then the rays where there are any, then the shading.
  // Progress: the normals, then the rays where there are any, then the shading, and the
  // interreflection's rays and bounces where the scene has them.
  const double raysShare = raysShareOf(plan.scene);
  // An empty piece of a split mesh takes part in the bounces' exchanges.
  const bool indirect =
    shadelab::needsInterreflection(plan.scene, plan.request) && (input->GetNumberOfPoints() > 0 || pieces.split());
  const double shadingShare = (1 - normalsShare - raysShare) * (indirect ? 0.3 : 1);
  this->StartStep(normalsShare, raysShare);
  vtkPolyData* seen = this->PrepareVisibility(input, shadingNormals, plan, pieces);
  this->StartStep(normalsShare + raysShare, shadingShare);
  std::vector<vtkSmartPointer<vtkDataArray>> arrays;
  if (input->GetNumberOfPoints() > 0)
  {
    arrays = this->ShadedArrays(input, shadingNormals, seen, plan, pieces, sampling);
  }
  if (this->Tolerance > 0 && this->MethodPlan->forecast) // what the run drew, against it
  {
    this->MethodPlan->forecast->drawn =
      shadelab::SampleCounts{ std::accumulate(sampling.samplesDrawn.begin(), sampling.samplesDrawn.end(), 0.0),
        occlusionRayCount(plan.scene, seen, this->ArrayPrefix, sampling.samplesDrawn.size()) };
  }
  this->InterreflectionReport.clear();
  if (indirect)
  {
    // Where both sides are shaded, the side the viewer does not see sends light too: its rays
    // and shading take a third of the interreflection's progress.
    const double start = normalsShare + raysShare + shadingShare, span = 1 - start;
    const bool bothSides = shadelab::shadesBothSides(plan.scene);
    std::optional<shadelab::HiddenSide> hidden;
    if (bothSides)
    {
      hidden = this->ShadeHiddenSide(input, shadingNormals, plan, pieces, start, span / 3);
    }
    this->StartStep(start + (bothSides ? span / 3 : 0), bothSides ? 2 * span / 3 : span);
    this->InterreflectionReport =
      shadelab::addIndirectLight(this->Internals->InterreflectionStep, input, shadingNormals, plan.scene, plan.request,
        plan.scene.material.arrays.any() ? &this->Internals->VertexMaterial : nullptr, this->ArrayPrefix, arrays,
        pieces, this->Tolerance > 0 ? &*this->MethodPlan->interreflection : nullptr, hidden ? &*hidden : nullptr);
    this->StopIfAborted(); // the step stopped (ForwardStepProgress asked it to)
  }
  // The rays' arrays have been used (those asked for are in `arrays`): not kept until the next run.
  this->Internals->VisibilityStep->GetOutput()->Initialize();
  return arrays;
}

std::string vtkLocalReflectanceFilter::ReportSampling(
  const ShadingPlan& plan, const shadelab::MeshPieces& pieces, SamplingOutcome& sampling, const std::string& failure)
{
  // Counted over every piece (a collective call, which an empty or failed piece joins too).
  this->SamplingReport = this->ShortOfTargetReport(plan, sampling.shortOfTarget, pieces);
  if (!planSamples(this->MethodPlan))
  {
    return failure;
  }
  try // collective too: a failed piece takes part with no values
  {
    this->MethodPlan->estimatedSamplingError =
      this->EstimatedSamplingError(failure.empty() ? std::move(sampling.standardError) : std::vector<double>(), pieces);
  }
  catch (const std::exception& error) // no memory to gather the values
  {
    return failure.empty() ? error.what() : failure;
  }
  return failure;
}

std::optional<vtkLocalReflectanceFilter::ShadingPlan> vtkLocalReflectanceFilter::PlanShading(
  vtkPolyData* input, const shadelab::MeshPieces& pieces)
{
  // Everything is checked before anything is written. Until the steps run, what differs
  // between pieces is agreed, so that every process stops alike; the rest (the settings, the
  // scene, the extent) is the same on every process.
  if (!this->CheckTolerance())
  {
    return std::nullopt;
  }
  ShadingPlan plan;
  // Under a tolerance the precision is chosen with the methods, and float64 is checked first
  // as the precision that accepts the most scenes and meshes.
  plan.precision = this->OutputPrecision == DOUBLE_PRECISION || this->Tolerance > 0 ? shadelab::Precision::Float64
                                                                                    : shadelab::Precision::Float32;
  if (!this->CheckMesh(input, pieces, plan) || !this->PlaceScene(input, pieces, plan) ||
    !this->CheckLightMethods(plan.scene) || !this->ChooseArraysAndMethods(plan) ||
    !this->CheckArrayNamesFree(input, plan.scene, pieces))
  {
    return std::nullopt;
  }
  return plan;
}

bool vtkLocalReflectanceFilter::MaterialSource::operator==(const MaterialSource& other) const
{
  return sources.coefficients == other.sources.coefficients && model == other.model && storage == other.storage &&
    points == other.points && arrays == other.arrays;
}

bool vtkLocalReflectanceFilter::ReadMaterialArrays(
  vtkPolyData* input, const shadelab::MeshPieces& pieces, ShadingPlan& plan)
{
  if (!plan.scene.material.arrays.any())
  {
    return true;
  }
  // Stored in float32 where the run is float32 for sure (no tolerance to choose float64), which
  // halves the memory; in float64 otherwise.
  const shadelab::Precision storage = this->Tolerance == 0 && this->OutputPrecision == SINGLE_PRECISION
    ? shadelab::Precision::Float32
    : shadelab::Precision::Float64;
  MaterialSource source{ plan.scene.material.arrays, plan.scene.model, storage, input->GetNumberOfPoints(), {} };
  for (const auto& coefficient : source.sources.coefficients)
  {
    vtkDataArray* array = coefficient ? input->GetPointData()->GetArray(coefficient->array.c_str()) : nullptr;
    source.arrays.emplace_back(array, array ? array->GetMTime() : 0);
  }
  const bool unchanged = this->Internals->VertexMaterialSource && *this->Internals->VertexMaterialSource == source;
  if (!pieces.holdEverywhere(unchanged) && !this->DecodeMaterialArrays(input, pieces, plan, source))
  {
    return false;
  }
  if (plan.scene.material.arrays[shadelab::MaterialCoefficient::Shininess])
  {
    const double mine = this->Internals->VertexMaterial.largest(shadelab::MaterialCoefficient::Shininess);
    double everywhere = mine;
    if (pieces.split())
    {
      pieces.processes->AllReduce(&mine, &everywhere, 1, vtkCommunicator::MAX_OP);
    }
    plan.measured.largestShininess = everywhere;
  }
  if (plan.scene.material.arrays[shadelab::MaterialCoefficient::Diffuse])
  {
    plan.measured.largestAlbedo = this->Internals->VertexMaterial.largest(shadelab::MaterialCoefficient::Diffuse);
  }
  return true;
}

bool vtkLocalReflectanceFilter::DecodeMaterialArrays(
  vtkPolyData* input, const shadelab::MeshPieces& pieces, const ShadingPlan& plan, const MaterialSource& source)
{
  this->Internals->VertexMaterialSource.reset();
  shadelab::MaterialReading reading =
    shadelab::readVertexMaterial(input, plan.scene, source.storage, pieces.processes, pieces.pointIds());
  this->Internals->VertexMaterial = std::move(reading.material);
  const std::string problem = pieces.firstProblem(reading.problem);
  if (!problem.empty())
  {
    vtkErrorMacro(<< problem);
    return false;
  }
  this->Internals->VertexMaterialSource = source;
  return true;
}

bool vtkLocalReflectanceFilter::CheckTolerance()
{
  if (!(this->Tolerance >= 0 && std::isfinite(this->Tolerance)))
  {
    vtkErrorMacro("the tolerance is " << this->Tolerance << ": it must be a finite number >= 0 (0: exact methods)");
    return false;
  }
  return true;
}

bool vtkLocalReflectanceFilter::CheckMesh(vtkPolyData* input, const shadelab::MeshPieces& pieces, ShadingPlan& plan)
{
  // A piece may lack polygons where others have them (a piece of lines, or of nothing).
  const bool polygons = input->GetNumberOfPolys() + input->GetNumberOfStrips() > 0;
  std::string problem = pieces.firstProblem(!pieces.split() || polygons ? meshProblem(input) : "");
  if (pieces.split() && problem.empty() && pieces.holdEverywhere(!polygons))
  {
    problem = meshProblem(input); // no piece has a polygon
  }
  if (problem.empty())
  {
    plan.extent = pieces.split() ? shadelab::wholeMeshExtent(pieces.processes, input) : shadelab::meshExtentOf(input);
    problem = shadelab::meshCoordinateProblem(plan.extent.reach, plan.precision);
  }
  if (!problem.empty())
  {
    vtkErrorMacro(<< problem);
    return false;
  }
  return true;
}

std::optional<shadelab::Scene> vtkLocalReflectanceFilter::SceneReadEverywhere(const shadelab::MeshPieces& pieces)
{
  const std::optional<shadelab::Scene> given = this->ReportedScene(this->Internals->SceneOfThisUpdate);
  // Each process reads the scene itself: one that could not (its file missing there, say)
  // stops them all.
  if (!pieces.holdEverywhere(given.has_value()))
  {
    if (given)
    {
      vtkErrorMacro("another process could not read the scene (see its error), so this one stops too");
    }
    return std::nullopt;
  }
  return given;
}

bool vtkLocalReflectanceFilter::PlaceScene(vtkPolyData* input, const shadelab::MeshPieces& pieces, ShadingPlan& plan)
{
  const std::optional<shadelab::Scene> given = this->SceneReadEverywhere(pieces);
  if (!given)
  {
    return false;
  }
  // A scene written relative to the mesh is placed on it here, and checked where it lands.
  plan.scene = shadelab::placedOnMesh(*given, plan.extent);
  // Every process shades with the mesh's own materials where any does, and on both sides where
  // any does: an empty piece has no parts to say so, and the steps that follow exchange between
  // the pieces.
  if (pieces.holdAnywhere(shadelab::shadesWithOwnMaterials(plan.scene, input, this->ColorByArray)))
  {
    if (plan.scene.spectral)
    {
      vtkErrorMacro("the mesh's own materials (a scene file's parts, RGB per point) cannot be shaded in the spectral "
                    "mode, which takes spectra or numbers: give the scene a \"material\"");
      return false;
    }
    plan.scene.material = shadelab::ownMaterial(plan.scene, input);
  }
  plan.scene.material.twoSided = pieces.holdAnywhere(plan.scene.material.twoSided);
  if (this->ColorByArray)
  {
    if (!shadelab::isColorMapName(this->MaterialColorMap))
    {
      vtkErrorMacro(
        "MaterialColorMap \"" << this->MaterialColorMap << "\" is not one of " << shadelab::colorMapNameList());
      return false;
    }
    shadelab::colorMaterialBy(plan.scene, this->MaterialColorArray, this->MaterialColorMap);
  }
  if (!this->SceneIsValid(shadelab::sceneProblems(plan.scene, plan.precision)))
  {
    return false;
  }
  if (this->Tolerance > 0) // one pass over the points, for bounds that are not the sphere's
  {
    plan.measured.nearestVertexDistance = shadelab::nearestPointDistances(
      plan.scene, input->GetPoints() ? input->GetPoints()->GetData() : nullptr, pieces.processes);
  }
  return true;
}

bool vtkLocalReflectanceFilter::CheckLightMethods(const shadelab::Scene& scene)
{
  this->MethodPlan.reset();
  if (!this->LightMethods.empty() && this->LightMethods.size() != scene.lights.size())
  {
    vtkErrorMacro("SetLightMethods was given " << this->LightMethods.size() << " methods for " << scene.lights.size()
                                               << " lights: give one per light, or none");
    return false;
  }
  return true;
}

bool vtkLocalReflectanceFilter::ChooseArraysAndMethods(ShadingPlan& plan)
{
  plan.methods = this->LightMethods;
  try
  {
    plan.request = shadelab::selectArrays(plan.scene, this->ArraySelection);
  }
  catch (const std::invalid_argument& error)
  {
    vtkErrorMacro(<< error.what());
    return false;
  }
  plan.float32Fits = shadelab::meshCoordinateProblem(plan.extent.reach, shadelab::Precision::Float32).empty() &&
    shadelab::sceneProblems(plan.scene, shadelab::Precision::Float32).empty();
  const std::string unplanned = shadelab::tolerancePlanProblem(plan.scene);
  if (this->Tolerance > 0 && !unplanned.empty())
  {
    vtkErrorMacro(<< unplanned << ": shade it exactly, with a tolerance of 0 and an output precision");
    return false;
  }
  if (this->Tolerance > 0 && !this->ChooseMethods(plan, true))
  {
    return false;
  }
  // Under a tolerance, its plan gives every "auto" its target (in the second pass at the latest).
  return this->Tolerance > 0 || this->SceneIsValid(shadelab::untargetedSamplingProblems(plan.scene, false));
}

void vtkLocalReflectanceFilter::AddFieldNotes(vtkPolyData* output) const
{
  shadelab::addFieldNote(output, shadelab::normalsNoteName, { this->NormalsReport });
  if (!this->VisibilityReport.empty())
  {
    shadelab::addFieldNote(output, shadelab::visibilityNoteName, { this->VisibilityReport });
  }
  if (!this->InterreflectionReport.empty())
  {
    shadelab::addFieldNote(output, shadelab::interreflectionNoteName, { this->InterreflectionReport });
  }
  if (this->Tolerance > 0)
  {
    std::vector<std::string> lines = this->MethodPlan->describe();
    lines.insert(lines.end(), this->SamplingReport.begin(), this->SamplingReport.end());
    shadelab::addFieldNote(output, shadelab::methodsNoteName, lines);
  }
}

vtkDataArray* vtkLocalReflectanceFilter::PrepareNormals(
  vtkPolyData* input, vtkPolyData* output, const shadelab::MeshPieces& pieces)
{
  vtkShadingNormalsFilter* step = this->Internals->NormalsStep;
  step->SetInputData(input);
  step->SetNormalsName(this->ComputedNormalsName());
  step->SetOrientOutward(this->OrientNormalsOutward);
  step->SetWeldCoincidentPoints(this->WeldCoincidentPoints);
  step->SetFeatureAngle(this->FeatureAngle);
  step->SetWeldTolerance(this->WeldTolerance);
  step->CheckCellsOff(); // meshProblem checked them
  // Outputs share the prepared normals: one edited in place since the step ran (and marked
  // modified) is not trusted.
  vtkDataArray* previous = step->GetOutput()->GetPointData()->GetNormals();
  // On a split mesh the step exchanges data, so every process runs it, whatever it has kept.
  if (pieces.split() || (previous && previous->GetMTime() > step->GetOutput()->GetUpdateTime()))
  {
    step->Modified();
  }
  step->Update();
  // The input's own normals, or computed ones added to the output; either may be used
  // flipped, in which case the input's own array still passes through unchanged.
  vtkDataArray* inputNormals = input->GetPointData()->GetNormals();
  vtkDataArray* shading = step->GetOutput()->GetPointData()->GetNormals();
  this->NormalsReport = step->GetReport();
  if (!inputNormals)
  {
    output->GetPointData()->SetNormals(shading);
  }
  else if (shading != inputNormals)
  {
    this->NormalsReport += " Shaded with the flipped copy; the input's array passes through unchanged.";
  }
  return shading;
}

vtkPolyData* vtkLocalReflectanceFilter::PrepareVisibility(vtkPolyData* input, vtkDataArray* shadingNormals,
  const ShadingPlan& plan, const shadelab::MeshPieces& pieces, const std::vector<vtkIdType>& rayPoints)
{
  const shadelab::Scene& scene = plan.scene;
  const shadelab::ArrayRequest& request = plan.request;
  if (!scene.needsVisibility())
  {
    return nullptr;
  }
  // The mesh's surface and the normals to shade with, and nothing else (no name can clash).
  vtkNew<vtkPolyData> surface;
  surface->SetPoints(input->GetPoints());
  surface->SetPolys(input->GetPolys());
  surface->SetStrips(input->GetStrips());
  surface->GetPointData()->SetNormals(shadingNormals);
  if (pieces.split()) // what puts the pieces together, for the surface's cells (after the vertices and lines)
  {
    surface->GetPointData()->SetGlobalIds(input->GetPointData()->GetGlobalIds());
    const vtkIdType firstPolygon = input->GetNumberOfVerts() + input->GetNumberOfLines();
    std::vector<vtkIdType> surfaceCells(static_cast<std::size_t>(input->GetNumberOfCells() - firstPolygon));
    std::iota(surfaceCells.begin(), surfaceCells.end(), firstPolygon);
    vtkCellData* cells = input->GetCellData();
    if (vtkDataArray* ids = cells->GetGlobalIds())
    {
      surface->GetCellData()->SetGlobalIds(shadelab::tuplesAt(ids, surfaceCells));
    }
    if (vtkDataArray* ghosts = cells->GetArray(vtkDataSetAttributes::GhostArrayName()))
    {
      surface->GetCellData()->AddArray(shadelab::tuplesAt(ghosts, surfaceCells));
    }
  }
  vtkMeshVisibilityFilter* step = this->Internals->VisibilityStep;
  step->CheckCellsOff(); // meshProblem checked them
  step->SetInputData(surface);
  step->SetScene(scene);
  step->SetArrayPrefix(this->ArrayPrefix);
  step->SetComputeBentNormal(request.occlusion[int(shadelab::OcclusionTerm::BentNormal)]);
  step->SetComputeSkyViewFactor(request.occlusion[int(shadelab::OcclusionTerm::SkyViewFactor)]);
  // A shadowed light drawn to a target is estimated where its rays are, as the kernel would
  // estimate it: the same targets, and the lobe where its specular term is computed.
  std::vector<vtkMeshVisibilityFilter::DrawnLight> drawn(scene.lights.size());
  for (std::size_t l = 0; l < plan.methods.size(); ++l)
  {
    drawn[l].targets = plan.methods[l].targets;
    drawn[l].lobe = { shadelab::specularComputed(scene, request, l) ? shadelab::evaluatedSpecularModel(scene)
                                                                    : shadelab::SpecularModel::None,
      scene.material.shininess };
  }
  step->SetDrawnLights(drawn);
  step->SetRayPointIds(rayPoints);
  step->Update();
  this->StopIfAborted(); // the step stopped (ForwardStepProgress asked it to)
  vtkPolyData* seen = step->GetOutput();
  if (input->GetNumberOfPoints() > 0 &&
    !seen->GetPointData()->GetArray(shadelab::visibilityFlagsArrayName(this->ArrayPrefix).c_str()))
  {
    throw std::runtime_error("casting the rays for shadows and ambient occlusion failed (see the error above)");
  }
  this->VisibilityReport = step->GetReport();
  return seen;
}

void vtkLocalReflectanceFilter::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "ArraySelection:";
  for (const std::string& entry : this->ArraySelection)
  {
    os << " " << entry;
  }
  os << "\n";
  os << indent << "NumberOfThreads: " << this->NumberOfThreads << "\n";
  os << indent << "ArrayPrefix: " << this->ArrayPrefix << "\n";
  os << indent << "ColorByArray: " << this->ColorByArray << "\n";
  os << indent << "MaterialColorArray: " << this->MaterialColorArray << "\n";
  os << indent << "MaterialColorMap: " << this->MaterialColorMap << "\n";
  os << indent << "OutputPrecision: " << this->OutputPrecision << "\n";
  os << indent << "OrientNormalsOutward: " << this->OrientNormalsOutward << "\n";
  os << indent << "WeldCoincidentPoints: " << this->WeldCoincidentPoints << "\n";
  os << indent << "FeatureAngle: " << this->FeatureAngle << "\n";
  os << indent << "WeldTolerance: " << this->WeldTolerance << "\n";
  os << indent << "Tolerance: " << this->Tolerance << "\n";
}
