#include "vtkInterreflectionFilter.h"

#include "Interreflection.h"
#include "NumberText.h"
#include "Precision.h"
#include "ShBands.h"
#include "ShadeLabMeshPieces.h"
#include "ShadeLabMeshPolygons.h"
#include "ShadeLabPieceExchange.h"
#include "ShadeLabRealArrays.h"
#include "ShadeLabRunAborted.h"
#include "ShadeLabThreadCount.h"
#include "ShadeLabWholeMesh.h"
#include "Visibility.h"

#include "vtkDataArray.h"
#include "vtkDoubleArray.h"
#include "vtkFloatArray.h"
#include "vtkInformation.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkSMPTools.h"
#include "vtkSmartPointer.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <functional>
#include <memory>
#include <new>
#include <stdexcept>
#include <string>
#include <vector>

vtkStandardNewMacro(vtkInterreflectionFilter);

vtkInterreflectionFilter::vtkInterreflectionFilter()
  : Controller(vtkMultiProcessController::GetGlobalController())
{
}

namespace
{
/// A point array's RGB tuples as doubles.
std::vector<shadelab::Rgb> rgbValues(vtkDataArray* array)
{
  std::vector<shadelab::Rgb> values(static_cast<std::size_t>(array->GetNumberOfTuples()));
  for (vtkIdType i = 0; i < array->GetNumberOfTuples(); ++i)
  {
    array->GetTuple(i, &values[std::size_t(i)].x);
  }
  return values;
}

/// The normal made unit: the gather's rays are cosine-weighted about it, and a normal of another
/// length (a mesh's own) would tilt them. A zero normal stays zero.
glm::dvec3 unitOrZero(const glm::dvec3& normal)
{
  return shadelab::largestComponent(normal) > 0 ? shadelab::unitVector(normal) : normal;
}

/// The albedo array's tuple at a point.
shadelab::Rgb rgbAt(vtkDoubleArray* array, vtkIdType point)
{
  const double* rgb = array->GetPointer(3 * point);
  return { rgb[0], rgb[1], rgb[2] };
}

/// Zero bounces: no light from the mesh, with no error, and nothing added to the transfer.
shadelab::IndirectIrradiance noIndirectLight(std::size_t points, std::size_t transferCoefficients)
{
  shadelab::IndirectIrradiance none;
  none.irradiance.resize(points);
  none.standardError.resize(points);
  none.transfer.resize(points * transferCoefficients);
  return none;
}

/// How many coefficients the transfer arrays have together.
std::size_t coefficientsOf(const std::vector<vtkDataArray*>& transfers)
{
  std::size_t count = 0;
  for (vtkDataArray* transfer : transfers)
  {
    count += static_cast<std::size_t>(transfer->GetNumberOfComponents());
  }
  return count;
}

/// What the first bounce reflects of each transfer coefficient: kd T_k per channel, each
/// vertex's coefficients after one another, the arrays in turn.
std::vector<shadelab::Rgb> reflectedTransfer(
  const std::vector<vtkDataArray*>& transfers, const shadelab::Albedo& albedo, vtkIdType points)
{
  const std::size_t coefficients = coefficientsOf(transfers);
  std::vector<shadelab::Rgb> reflected(static_cast<std::size_t>(points) * coefficients);
  vtkSMPTools::For(0, points,
    [&](vtkIdType begin, vtkIdType end)
    {
      for (vtkIdType i = begin; i < end; ++i)
      {
        const shadelab::Rgb kd = albedo.at(static_cast<std::size_t>(i));
        shadelab::Rgb* out = &reflected[static_cast<std::size_t>(i) * coefficients];
        for (vtkDataArray* transfer : transfers)
        {
          for (int k = 0; k < transfer->GetNumberOfComponents(); ++k)
          {
            *out++ = kd * transfer->GetComponent(i, k);
          }
        }
      }
    });
  return reflected;
}

bool isAlbedo(const shadelab::Rgb& kd)
{
  auto inUnit = [](double c) { return c >= 0 && c <= 1; }; // false for NaN
  return inUnit(kd.r) && inUnit(kd.g) && inUnit(kd.b);
}

/// Every point's gather rays traced (gatherHits) and handed to `gather`: every vertex's front
/// and, with both sides, every vertex's back (point N + v, gathering about the reversed normal,
/// with lit backs), or on a mesh split over processes the points `split` owns; in hundredths of
/// them, so that progress is reported and an abort heard between them (only where the filter
/// may stop alone, a whole mesh). Returns how many met a back.
long long gatherEveryPoint(const shadelab::OccluderMesh& occluders, vtkPolyData* mesh, vtkDataArray* normals,
  const shadelab::Sampling& sampling, shadelab::ShadedSides sides, shadelab::BounceGather& gather, vtkAlgorithm* filter,
  const shadelab::SplitVertices* split)
{
  const bool both = sides == shadelab::ShadedSides::Both;
  const vtkIdType vertices = mesh->GetNumberOfPoints();
  const vtkIdType count = split ? static_cast<vtkIdType>(split->own.size()) : vertices * (both ? 2 : 1);
  auto pointAt = [&](vtkIdType k) { return split ? static_cast<vtkIdType>(split->own[std::size_t(k)]) : k; };
  const shadelab::TriangleBacks backs = both ? shadelab::TriangleBacks::Lit : shadelab::TriangleBacks::Dark;
  std::atomic<long long> backHits{ 0 };
  const vtkIdType block = std::max<vtkIdType>(count / 100, 256);
  shadelab::visitPackedPoints(normals,
    [&](auto packedNormals)
    {
      for (vtkIdType first = 0; first < count; first += block)
      {
        if (!split && filter->GetAbortExecute())
        {
          throw shadelab::RunAborted();
        }
        vtkSMPTools::For(first, std::min(count, first + block),
          [&](vtkIdType begin, vtkIdType end)
          {
            std::vector<shadelab::OccluderMesh::RayHit> hits(static_cast<std::size_t>(sampling.samples));
            long long back = 0;
            for (vtkIdType k = begin; k < end; ++k)
            {
              const vtkIdType point = pointAt(k), i = point % vertices;
              const double side = point < vertices ? 1.0 : -1.0;
              shadelab::RayVertex vertex{ {}, side * unitOrZero(packedNormals(i)), i };
              mesh->GetPoint(i, &vertex.position.x);
              back += shadelab::gatherHits(occluders, vertex, sampling, packedNormals, hits.data(), backs);
              gather.addVertex(static_cast<std::size_t>(point), hits.data());
            }
            backHits += back;
          });
        filter->UpdateProgress(
          0.9 * static_cast<double>(std::min(count, first + block)) / std::max<vtkIdType>(count, 1));
      }
    });
  occluders.checkTracing();
  return backHits;
}

/// The sweeps' loop on vtkSMPTools' threads.
void smpLoop(std::size_t count, const std::function<void(std::size_t, std::size_t)>& body)
{
  vtkSMPTools::For(0, static_cast<vtkIdType>(count),
    [&](vtkIdType begin, vtkIdType end) { body(std::size_t(begin), std::size_t(end)); });
}

/// An RGB point array of `points` values from values[first], in float64 or float32.
vtkSmartPointer<vtkDataArray> rgbArray(
  const std::string& name, const std::vector<shadelab::Rgb>& values, std::size_t first, vtkIdType points, bool float64)
{
  vtkSmartPointer<vtkDataArray> array = shadelab::realArray(name, 3, points, float64);
  for (vtkIdType i = 0; i < points; ++i)
  {
    array->SetTuple(i, &values[first + static_cast<std::size_t>(i)].x);
  }
  return array;
}

/// One transfer array's part of the carried coefficients of `points` points from firstPoint
/// (`coefficients` of them per point, this array's `count` from `first`), as a point array of
/// 3 x count components: coefficient k's channel c at 3 k + c.
vtkSmartPointer<vtkDataArray> indirectTransferArray(const std::string& name, const std::vector<shadelab::Rgb>& carried,
  std::size_t firstPoint, vtkIdType points, std::size_t first, std::size_t coefficients, int count, bool float64)
{
  vtkSmartPointer<vtkDataArray> array = shadelab::realArray(name, 3 * count, points, float64);
  for (vtkIdType i = 0; i < points; ++i)
  {
    const shadelab::Rgb* vertex = &carried[(firstPoint + static_cast<std::size_t>(i)) * coefficients + first];
    for (int k = 0; k < count; ++k)
    {
      for (int c = 0; c < 3; ++c)
      {
        array->SetComponent(i, 3 * k + c, vertex[k][c]);
      }
    }
  }
  return array;
}

/// Every point's values of a piece's array, in its type and the whole mesh's order (a
/// collective call).
vtkSmartPointer<vtkDataArray> atEveryPoint(
  vtkMultiProcessController* controller, vtkDataArray* array, const std::vector<vtkIdType>& pieceIds, vtkIdType points)
{
  const int components = array->GetNumberOfComponents();
  std::vector<double> mine(static_cast<std::size_t>(array->GetNumberOfTuples() * components));
  for (vtkIdType i = 0; i < array->GetNumberOfTuples(); ++i)
  {
    array->GetTuple(i, &mine[static_cast<std::size_t>(i * components)]);
  }
  const std::vector<double> every = shadelab::valuesAtEveryPoint(controller, pieceIds, mine, components, points);
  vtkSmartPointer<vtkDataArray> whole = vtk::TakeSmartPointer(array->NewInstance());
  whole->SetName(array->GetName());
  whole->SetNumberOfComponents(components);
  whole->SetNumberOfTuples(points);
  for (vtkIdType i = 0; i < points; ++i)
  {
    whole->SetTuple(i, &every[static_cast<std::size_t>(i * components)]);
  }
  return whole;
}

/// Whether `make` ran on every process without running out of memory (a collective call).
bool madeEverywhere(vtkMultiProcessController* controller, const std::function<void()>& make)
{
  bool made = true;
  try
  {
    make();
  }
  catch (const std::bad_alloc&)
  {
    made = false;
  }
  return shadelab::everyProcessHolds(controller, made);
}

/// The vertices a process gathers at, each once and in order, and every process's of them, in
/// process order: what the sweeps' values are shared by.
struct SharedVertices
{
  std::vector<vtkIdType> own, everyProcesses;
};

/// Every vertex's values, from each process's at its own vertices (SplitVertices::share): one
/// field at a time, so that an exchange holds 3 values a vertex whatever the fields.
void shareValues(vtkMultiProcessController* controller, const SharedVertices& vertices,
  std::vector<shadelab::Rgb>& values, std::size_t perVertex, bool ready)
{
  if (!shadelab::everyProcessHolds(controller, ready))
  {
    throw std::runtime_error("a process of the split mesh ran out of memory for interreflection's sweeps");
  }
  for (std::size_t field = 0; field < perVertex; ++field)
  {
    std::vector<double> mine;
    if (!madeEverywhere(controller, [&] { mine.reserve(3 * vertices.own.size()); }))
    {
      throw std::runtime_error("a process of the split mesh ran out of memory sharing interreflection's sweeps");
    }
    for (const vtkIdType id : vertices.own)
    {
      const shadelab::Rgb& value = values[static_cast<std::size_t>(id) * perVertex + field];
      mine.insert(mine.end(), { value.r, value.g, value.b });
    }
    const std::vector<double> every = shadelab::gathered(controller, mine, shadelab::WholeMeshOn::EveryProcess);
    for (std::size_t k = 0; k < vertices.everyProcesses.size(); ++k)
    {
      values[static_cast<std::size_t>(vertices.everyProcesses[k]) * perVertex + field] =
        shadelab::Rgb(every[3 * k], every[3 * k + 1], every[3 * k + 2]);
    }
  }
}
}

void vtkInterreflectionFilter::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "RadiosityArrayName: " << this->RadiosityArrayName << "\n";
  os << indent << "BackRadiosityArrayName: " << this->BackRadiosityArrayName << "\n";
  os << indent << "Albedo: " << this->Albedo[0] << " " << this->Albedo[1] << " " << this->Albedo[2] << "\n";
  os << indent << "AlbedoArrayName: " << this->AlbedoArrayName << "\n";
  os << indent << "Bounces: " << this->Bounces << "\n";
  os << indent << "BounceTolerance: " << this->BounceTolerance << "\n";
  os << indent << "Samples: " << this->Samples << "\n";
  os << indent << "Stratified: " << this->Stratified << "\n";
  os << indent << "KeepBounces: " << this->KeepBounces << "\n";
  for (const std::string& name : this->TransferArrayNames)
  {
    os << indent << "TransferArrayName: " << name << "\n";
  }
  os << indent << "ArrayPrefix: " << this->ArrayPrefix << "\n";
  os << indent << "NumberOfThreads: " << this->NumberOfThreads << "\n";
}

void vtkInterreflectionFilter::AddTransferArrayName(const std::string& name)
{
  this->TransferArrayNames.push_back(name);
  this->Modified();
}

void vtkInterreflectionFilter::RemoveAllTransferArrayNames()
{
  if (!this->TransferArrayNames.empty())
  {
    this->TransferArrayNames.clear();
    this->Modified();
  }
}

bool vtkInterreflectionFilter::TransferArrays(
  vtkPolyData* input, std::vector<vtkDataArray*>& arrays, const std::string& suffix)
{
  for (const std::string& front : this->TransferArrayNames)
  {
    const std::string name = front + suffix;
    vtkDataArray* transfer = input->GetPointData()->GetArray(name.c_str());
    if (!transfer || shadelab::shOrderOfCount(transfer->GetNumberOfComponents()) < 2)
    {
      vtkErrorMacro("the input has no numeric point array '"
        << name
        << "' of transfer vectors (9, 16 or 25 components: \"estimator\": \"prt\") to carry through the bounces");
      return false;
    }
    arrays.push_back(transfer);
  }
  return true;
}

void vtkInterreflectionFilter::AddArraysAnEmptyPieceLacks(vtkPolyData* piece)
{
  std::vector<std::pair<std::string, int>> needed{ { this->RadiosityArrayName, 3 } };
  if (!this->BackRadiosityArrayName.empty())
  {
    needed.emplace_back(this->BackRadiosityArrayName, 3);
  }
  if (!this->AlbedoArrayName.empty())
  {
    needed.emplace_back(this->AlbedoArrayName, 3);
  }
  for (const std::string& name : this->TransferArrayNames) // as many coefficients as the others'
  {
    vtkDataArray* transfer = piece->GetPointData()->GetArray(name.c_str());
    const std::vector<int> counts = shadelab::gathered(this->Controller,
      std::vector<int>{ transfer ? transfer->GetNumberOfComponents() : 0 }, shadelab::WholeMeshOn::EveryProcess);
    needed.emplace_back(name, *std::max_element(counts.begin(), counts.end()));
    if (!this->BackRadiosityArrayName.empty())
    {
      needed.emplace_back(name + "_back", needed.back().second);
    }
  }
  for (const auto& [name, components] : needed)
  {
    if (piece->GetNumberOfPoints() == 0 && !piece->GetPointData()->GetArray(name.c_str()))
    {
      vtkNew<vtkDoubleArray> none;
      none->SetName(name.c_str());
      none->SetNumberOfComponents(components);
      piece->GetPointData()->AddArray(none);
    }
  }
}

vtkDataArray* vtkInterreflectionFilter::RgbArray(vtkPolyData* input, const std::string& name, const char* role)
{
  vtkDataArray* array = input->GetPointData()->GetArray(name.c_str());
  if (!array || array->GetNumberOfComponents() != 3)
  {
    vtkErrorMacro("the input has no numeric point array '" << name << "' with 3 components (RGB) for " << role);
    return nullptr;
  }
  return array;
}

int vtkInterreflectionFilter::RequestData(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  vtkPolyData* input = vtkPolyData::GetData(inputVector[0]);
  vtkPolyData* output = vtkPolyData::GetData(outputVector);
  this->Report.clear();
  this->BackHits = 0;
  this->BounceCount = 0;
  this->RestBound = 0;
  return shadelab::runWithThreads(this->NumberOfThreads, [&] { return this->InterreflectPiece(input, output); });
}

int vtkInterreflectionFilter::InterreflectPiece(vtkPolyData* input, vtkPolyData* output)
{
  if (!shadelab::isPieceOfSplitMesh(this->Controller, input))
  {
    return this->Interreflect(input, output, nullptr);
  }
  // Every process holds every triangle, which its own points' rays may meet, and the sweeps
  // share each bounce's values between the processes.
  return shadelab::computeOnPiece(this->Controller, this, input, output, true, shadelab::WholeMeshOn::EveryProcess,
    [&](vtkPolyData* mesh, vtkPolyData* result, const std::vector<vtkIdType>* pieceIds)
    {
      return (pieceIds ? this->InterreflectWhole(mesh, result, *pieceIds, input)
                       : this->Interreflect(mesh, result, nullptr)) == 1;
    });
}

int vtkInterreflectionFilter::InterreflectWhole(
  vtkPolyData* whole, vtkPolyData* result, const std::vector<vtkIdType>& pieceIds, vtkPolyData* givenPiece)
{
  // An empty piece (more processes than pieces) may have none of the arrays: it takes part with
  // empty ones of the others' sizes.
  vtkNew<vtkPolyData> piece;
  piece->ShallowCopy(givenPiece);
  this->AddArraysAnEmptyPieceLacks(piece);
  // The piece's arrays, checked on every process alike before any value is exchanged.
  vtkSmartPointer<vtkDoubleArray> albedo;
  std::vector<vtkDataArray*> transfers, backTransfers;
  vtkDataArray* radiosity = this->RgbArray(piece, this->RadiosityArrayName, "the direct radiosity");
  vtkDataArray* backRadiosity = nullptr;
  const bool usable = radiosity && this->AlbedoOf(piece, albedo) && this->TransferArrays(piece, transfers) &&
    this->BackArrays(piece, transfers, backRadiosity, backTransfers);
  if (!shadelab::everyProcessHolds(this->Controller, usable))
  {
    return 0;
  }
  vtkNew<vtkPolyData> mesh; // the whole mesh with every point's radiosity, albedo and transfers
  mesh->ShallowCopy(whole);
  std::vector<vtkDataArray*> inputs = transfers;
  inputs.insert(inputs.end(), backTransfers.begin(), backTransfers.end());
  inputs.push_back(radiosity);
  if (backRadiosity)
  {
    inputs.push_back(backRadiosity);
  }
  if (albedo)
  {
    inputs.push_back(piece->GetPointData()->GetArray(this->AlbedoArrayName.c_str()));
  }
  for (vtkDataArray* array : inputs)
  {
    mesh->GetPointData()->AddArray(atEveryPoint(this->Controller, array, pieceIds, whole->GetNumberOfPoints()));
  }
  // Each vertex once: a piece may hold copies of a point (pieces read into one process). With
  // both sides, each vertex's back too, point N + v.
  SharedVertices vertices{ pieceIds, {} };
  std::sort(vertices.own.begin(), vertices.own.end());
  vertices.own.erase(std::unique(vertices.own.begin(), vertices.own.end()), vertices.own.end());
  for (std::size_t k = 0, fronts = vertices.own.size(); backRadiosity && k < fronts; ++k)
  {
    vertices.own.push_back(whole->GetNumberOfPoints() + vertices.own[k]);
  }
  vertices.everyProcesses = shadelab::gathered(this->Controller, vertices.own, shadelab::WholeMeshOn::EveryProcess);
  shadelab::SplitVertices split{ std::vector<std::size_t>(vertices.own.begin(), vertices.own.end()),
    [&](std::vector<shadelab::Rgb>& values, std::size_t perVertex, bool ready)
    { shareValues(this->Controller, vertices, values, perVertex, ready); } };
  vtkNew<vtkPolyData> computed;
  if (!shadelab::everyProcessHolds(this->Controller, this->Interreflect(mesh, computed, &split) == 1))
  {
    return 0; // where another process failed, it has said why
  }
  if (this->BounceCount > 0) // the rays of every process (a point several pieces hold casts them on each)
  {
    const std::vector<long long> every = shadelab::gathered(this->Controller,
      std::vector<long long>{ this->BackHits, this->GatherRays }, shadelab::WholeMeshOn::EveryProcess);
    this->BackHits = this->GatherRays = 0;
    for (std::size_t p = 0; p < every.size(); p += 2)
    {
      this->BackHits += every[p];
      this->GatherRays += every[p + 1];
    }
    this->Report = this->ReportOf(transfers);
  }
  for (int a = 0; a < computed->GetPointData()->GetNumberOfArrays(); ++a)
  {
    vtkDataArray* array = computed->GetPointData()->GetArray(a);
    if (!mesh->GetPointData()->HasArray(array->GetName()))
    {
      result->GetPointData()->AddArray(shadelab::tuplesAt(array, pieceIds));
    }
  }
  return 1;
}

int vtkInterreflectionFilter::Interreflect(
  vtkPolyData* input, vtkPolyData* output, const shadelab::SplitVertices* split)
{
  output->ShallowCopy(input); // every input array passes through
  if (input->GetNumberOfPoints() == 0)
  {
    return 1; // nothing in, nothing out: VTK's convention
  }
  vtkDataArray* normals = input->GetPointData()->GetNormals();
  if (!normals || normals->GetNumberOfComponents() != 3)
  {
    vtkErrorMacro("the input has no point normals: the gather rays leave about them (vtkShadingNormalsFilter "
                  "makes them)");
    return 0;
  }
  vtkDataArray* radiosity = this->RgbArray(input, this->RadiosityArrayName, "the direct radiosity");
  vtkDataArray* backRadiosity = nullptr;
  vtkSmartPointer<vtkDoubleArray> albedo;
  std::vector<vtkDataArray*> transfers, backTransfers;
  if (!radiosity || !this->AlbedoOf(input, albedo) || !this->TransferArrays(input, transfers) ||
    !this->BackArrays(input, transfers, backRadiosity, backTransfers))
  {
    return 0;
  }
  shadelab::IndirectIrradiance indirect;
  try
  {
    if (this->Bounces > 0)
    {
      indirect = this->GatherBounces(
        input, normals, radiosity, backRadiosity, albedo, transfers, backTransfers, split); // and its report
    }
    else
    {
      const std::size_t sides = backRadiosity ? 2 : 1;
      indirect =
        noIndirectLight(sides * static_cast<std::size_t>(input->GetNumberOfPoints()), coefficientsOf(transfers));
      this->Report = "0 bounces: no indirect light";
    }
  }
  catch (const shadelab::RunAborted&) // an empty output, and no error
  {
    output->Initialize();
    this->Report = "Aborted.";
    return 1;
  }
  catch (const std::exception& error) // Embree's, or no memory for the hits
  {
    output->Initialize();
    vtkErrorMacro(<< error.what());
    return 0;
  }
  this->AddIndirectArrays(output, indirect, radiosity->GetDataType() == VTK_DOUBLE, transfers);
  this->UpdateProgress(1.0);
  return 1;
}

bool vtkInterreflectionFilter::AlbedoOf(vtkPolyData* input, vtkSmartPointer<vtkDoubleArray>& perVertex)
{
  vtkDataArray* array =
    this->AlbedoArrayName.empty() ? nullptr : this->RgbArray(input, this->AlbedoArrayName, "the albedo");
  if (!this->AlbedoArrayName.empty() && !array)
  {
    return false;
  }
  perVertex = vtkDoubleArray::SafeDownCast(array); // float64 values are used where they are
  if (array && !perVertex)
  {
    perVertex = vtkSmartPointer<vtkDoubleArray>::New();
    perVertex->DeepCopy(array);
  }
  const vtkIdType points = perVertex ? perVertex->GetNumberOfTuples() : 0;
  vtkIdType bad = 0;
  while (bad < points && isAlbedo(rgbAt(perVertex, bad)))
  {
    ++bad;
  }
  if (!isAlbedo(shadelab::Rgb(this->Albedo[0], this->Albedo[1], this->Albedo[2])) || bad < points)
  {
    vtkErrorMacro("an albedo must be RGB in [0, 1] (above 1 a bounce reflects more light than arrives): "
      << (bad < points ? "'" + this->AlbedoArrayName + "' at point " + std::to_string(bad) : std::string("Albedo")));
    return false;
  }
  return true;
}

bool vtkInterreflectionFilter::BackArrays(vtkPolyData* input, const std::vector<vtkDataArray*>& transfers,
  vtkDataArray*& backRadiosity, std::vector<vtkDataArray*>& backTransfers)
{
  if (this->BackRadiosityArrayName.empty())
  {
    return true;
  }
  backRadiosity = this->RgbArray(input, this->BackRadiosityArrayName, "the backs' direct radiosity");
  if (!backRadiosity || !this->TransferArrays(input, backTransfers, "_back"))
  {
    return false;
  }
  for (std::size_t k = 0; k < backTransfers.size(); ++k) // each back as its front: the same coefficients
  {
    vtkDataArray* front = transfers[k];
    if (backTransfers[k]->GetNumberOfComponents() != front->GetNumberOfComponents())
    {
      vtkErrorMacro("point array '" << backTransfers[k]->GetName() << "' has "
                                    << backTransfers[k]->GetNumberOfComponents() << " components, and '"
                                    << front->GetName() << "' " << front->GetNumberOfComponents()
                                    << ": a transfer's backs need as many coefficients as its fronts");
      return false;
    }
  }
  return true;
}

shadelab::IndirectIrradiance vtkInterreflectionFilter::GatherBounces(vtkPolyData* input, vtkDataArray* normals,
  vtkDataArray* radiosity, vtkDataArray* backRadiosity, vtkDoubleArray* albedo,
  const std::vector<vtkDataArray*>& transfers, const std::vector<vtkDataArray*>& backTransfers,
  const shadelab::SplitVertices* split)
{
  const shadelab::ShadedSides sides = backRadiosity ? shadelab::ShadedSides::Both : shadelab::ShadedSides::Front;
  std::vector<shadelab::Rgb> direct = rgbValues(radiosity);
  if (backRadiosity)
  {
    const std::vector<shadelab::Rgb> backs = rgbValues(backRadiosity);
    direct.insert(direct.end(), backs.begin(), backs.end());
  }
  const shadelab::Sampling sampling{ this->Samples, this->Stratified };
  const shadelab::Albedo kd{ { this->Albedo[0], this->Albedo[1], this->Albedo[2] },
    albedo ? albedo->GetPointer(0) : nullptr };
  std::unique_ptr<shadelab::OccluderMesh> occluders;
  std::unique_ptr<shadelab::BounceGather> gather;
  // On a split mesh every process traces its rays before any value is shared: a failure here is
  // agreed, so that no process waits in an exchange for one that stopped.
  std::string failure;
  try
  {
    occluders = shadelab::occludersOf(input);
    std::vector<shadelab::Rgb> carried;
    for (const std::vector<vtkDataArray*>* side : { &transfers, &backTransfers }) // the fronts' points, the backs'
    {
      const std::vector<shadelab::Rgb> reflected =
        side->empty() ? std::vector<shadelab::Rgb>() : reflectedTransfer(*side, kd, input->GetNumberOfPoints());
      carried.insert(carried.end(), reflected.begin(), reflected.end());
    }
    gather = std::make_unique<shadelab::BounceGather>(*occluders, std::move(direct), sampling, carried, sides);
    this->BackHits = gatherEveryPoint(*occluders, input, normals, sampling, sides, *gather, this, split);
    occluders->releaseTracing(); // the sweeps' peak memory without the BVH
  }
  catch (const std::exception& error)
  {
    if (!split)
    {
      throw;
    }
    failure = error.what();
  }
  if (split && !shadelab::everyProcessHolds(this->Controller, failure.empty()))
  {
    throw std::runtime_error(
      failure.empty() ? "another process of the split mesh could not trace its gather rays (see its error)" : failure);
  }
  shadelab::IndirectIrradiance indirect =
    gather->bounce(kd, { this->Bounces, this->BounceTolerance }, this->KeepBounces, smpLoop, split);
  this->BounceCount = indirect.bounceCount;
  this->RestBound = indirect.restBound;
  this->GatherRays = static_cast<long long>(split ? split->own.size() : indirect.irradiance.size()) * this->Samples;
  this->LaterRays = gather->laterRays();
  this->Report = this->ReportOf(transfers);
  return indirect;
}

void vtkInterreflectionFilter::AddIndirectArrays(vtkPolyData* output, const shadelab::IndirectIrradiance& indirect,
  bool float64, const std::vector<vtkDataArray*>& transfers)
{
  vtkPointData* out = output->GetPointData();
  const vtkIdType points = output->GetNumberOfPoints();
  for (const bool back : { false, true })
  {
    if (back && this->BackRadiosityArrayName.empty())
    {
      break;
    }
    // The backs' values follow the fronts'.
    const std::size_t first = back ? static_cast<std::size_t>(points) : 0;
    auto side = [&](const std::vector<shadelab::Rgb>& values, const std::string& name)
    { out->AddArray(rgbArray(this->ArrayPrefix + name + (back ? "_back" : ""), values, first, points, float64)); };
    side(indirect.irradiance, "indirect_irradiance");
    side(indirect.standardError, "indirect_irradiance_std_error");
    for (std::size_t n = 0; n < indirect.bounces.size(); ++n)
    {
      side(indirect.bounces[n], "indirect_bounce_" + std::to_string(n + 1));
    }
    const std::size_t coefficients = coefficientsOf(transfers);
    std::size_t coefficient = 0; // the array's first coefficient among every point's
    for (vtkDataArray* transfer : transfers)
    {
      out->AddArray(indirectTransferArray(this->ArrayPrefix + transfer->GetName() + "_indirect" + (back ? "_back" : ""),
        indirect.transfer, first, points, coefficient, coefficients, transfer->GetNumberOfComponents(),
        transfer->GetDataType() == VTK_DOUBLE));
      coefficient += static_cast<std::size_t>(transfer->GetNumberOfComponents());
    }
  }
}

std::string vtkInterreflectionFilter::ReportOf(const std::vector<vtkDataArray*>& transfers) const
{
  const std::size_t rays = std::size_t(this->GatherRays);
  const bool both = !this->BackRadiosityArrayName.empty();
  std::string report = shadelab::countOf(std::size_t(this->BounceCount), "bounce") + " from '" +
    this->RadiosityArrayName + (both ? "' and '" + this->BackRadiosityArrayName : "") + "', " +
    std::to_string(this->Samples) + " gather rays per vertex" + (both ? " on each side" : "") +
    (this->BounceCount > 1 && this->LaterRays < this->Samples
        ? " (" + std::to_string(this->LaterRays) + " for the later bounces)"
        : "") +
    "; " + std::to_string(this->BackHits) + " of " + shadelab::countOf(rays, "ray") + " (" +
    shadelab::withDigits(100.0 * double(this->BackHits) / double(rays), 2) + "%) met the back of a triangle and " +
    (both ? "carried the backs' radiosity; " : "carried nothing; ") +
    (std::isfinite(this->RestBound)
        ? "the bounces past them add at most " + shadelab::scientific(this->RestBound) + " to a diffuse term"
        : std::string("with an albedo of 1 the bounces past them have no bound"));
  for (vtkDataArray* transfer : transfers)
  {
    report += "; the transfer '" + std::string(transfer->GetName()) + "' carried through them";
  }
  return report;
}
