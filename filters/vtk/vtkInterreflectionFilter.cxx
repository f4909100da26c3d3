#include "vtkInterreflectionFilter.h"

#include "Interreflection.h"
#include "NumberText.h"
#include "Precision.h"
#include "ShadeLabMeshPolygons.h"
#include "ShadeLabRunAborted.h"
#include "ShadeLabThreadCount.h"
#include "Visibility.h"

#include "vtkDataArray.h"
#include "vtkDoubleArray.h"
#include "vtkFloatArray.h"
#include "vtkInformation.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkSMPTools.h"
#include "vtkSmartPointer.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <string>
#include <vector>

vtkStandardNewMacro(vtkInterreflectionFilter);

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

/// Zero bounces: no light from the mesh, with no error.
shadelab::IndirectIrradiance noIndirectLight(std::size_t points)
{
  return { std::vector<shadelab::Rgb>(points), std::vector<shadelab::Rgb>(points), {} };
}

bool isAlbedo(const shadelab::Rgb& kd)
{
  auto inUnit = [](double c) { return c >= 0 && c <= 1; }; // false for NaN
  return inUnit(kd.r) && inUnit(kd.g) && inUnit(kd.b);
}

/// Every vertex's gather rays traced (gatherHits) and handed to `gather`, in hundredths of the
/// mesh, so that progress is reported and an abort heard between them. Returns how many met a
/// back.
long long gatherEveryVertex(const shadelab::OccluderMesh& occluders, vtkPolyData* mesh, vtkDataArray* normals,
  const shadelab::Sampling& sampling, shadelab::BounceGather& gather, vtkAlgorithm* filter)
{
  const vtkIdType count = mesh->GetNumberOfPoints();
  std::atomic<long long> backHits{ 0 };
  const vtkIdType block = std::max<vtkIdType>(count / 100, 256);
  shadelab::visitPackedPoints(normals,
    [&](auto packedNormals)
    {
      for (vtkIdType first = 0; first < count; first += block)
      {
        if (filter->GetAbortExecute())
        {
          throw shadelab::RunAborted();
        }
        vtkSMPTools::For(first, std::min(count, first + block),
          [&](vtkIdType begin, vtkIdType end)
          {
            std::vector<shadelab::OccluderMesh::RayHit> hits(static_cast<std::size_t>(sampling.samples));
            long long back = 0;
            for (vtkIdType i = begin; i < end; ++i)
            {
              shadelab::RayVertex vertex{ {}, unitOrZero(packedNormals(i)), i };
              mesh->GetPoint(i, &vertex.position.x);
              back += shadelab::gatherHits(occluders, vertex, sampling, packedNormals, hits.data());
              gather.addVertex(static_cast<std::size_t>(i), hits.data());
            }
            backHits += back;
          });
        filter->UpdateProgress(0.9 * static_cast<double>(std::min(count, first + block)) / count);
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

/// An RGB point array of the values, in float64 or float32.
vtkSmartPointer<vtkDataArray> rgbArray(const std::string& name, const std::vector<shadelab::Rgb>& values, bool float64)
{
  vtkSmartPointer<vtkDataArray> array = float64 ? vtkSmartPointer<vtkDataArray>(vtkSmartPointer<vtkDoubleArray>::New())
                                                : vtkSmartPointer<vtkDataArray>(vtkSmartPointer<vtkFloatArray>::New());
  array->SetName(name.c_str());
  array->SetNumberOfComponents(3);
  array->SetNumberOfTuples(static_cast<vtkIdType>(values.size()));
  for (std::size_t i = 0; i < values.size(); ++i)
  {
    array->SetTuple(static_cast<vtkIdType>(i), &values[i].x);
  }
  return array;
}
}

void vtkInterreflectionFilter::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "RadiosityArrayName: " << this->RadiosityArrayName << "\n";
  os << indent << "Albedo: " << this->Albedo[0] << " " << this->Albedo[1] << " " << this->Albedo[2] << "\n";
  os << indent << "AlbedoArrayName: " << this->AlbedoArrayName << "\n";
  os << indent << "Bounces: " << this->Bounces << "\n";
  os << indent << "BounceTolerance: " << this->BounceTolerance << "\n";
  os << indent << "Samples: " << this->Samples << "\n";
  os << indent << "Stratified: " << this->Stratified << "\n";
  os << indent << "KeepBounces: " << this->KeepBounces << "\n";
  os << indent << "ArrayPrefix: " << this->ArrayPrefix << "\n";
  os << indent << "NumberOfThreads: " << this->NumberOfThreads << "\n";
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
  return shadelab::runWithThreads(this->NumberOfThreads, [&] { return this->Interreflect(input, output); });
}

int vtkInterreflectionFilter::Interreflect(vtkPolyData* input, vtkPolyData* output)
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
  vtkSmartPointer<vtkDoubleArray> albedo;
  if (!radiosity || !this->AlbedoOf(input, albedo))
  {
    return 0;
  }
  shadelab::IndirectIrradiance indirect;
  try
  {
    if (this->Bounces > 0)
    {
      indirect = this->GatherBounces(input, normals, radiosity, albedo); // and its report
    }
    else
    {
      indirect = noIndirectLight(static_cast<std::size_t>(input->GetNumberOfPoints()));
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
  this->AddIndirectArrays(output, indirect, radiosity->GetDataType() == VTK_DOUBLE);
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

shadelab::IndirectIrradiance vtkInterreflectionFilter::GatherBounces(
  vtkPolyData* input, vtkDataArray* normals, vtkDataArray* radiosity, vtkDoubleArray* albedo)
{
  const shadelab::Sampling sampling{ this->Samples, this->Stratified };
  const std::unique_ptr<shadelab::OccluderMesh> occluders = shadelab::occludersOf(input);
  shadelab::BounceGather gather(*occluders, rgbValues(radiosity), sampling);
  this->BackHits = gatherEveryVertex(*occluders, input, normals, sampling, gather, this);
  occluders->releaseTracing(); // the sweeps' peak memory without the BVH
  const shadelab::Albedo kd{ { this->Albedo[0], this->Albedo[1], this->Albedo[2] },
    albedo ? albedo->GetPointer(0) : nullptr };
  shadelab::IndirectIrradiance indirect =
    gather.bounce(kd, { this->Bounces, this->BounceTolerance }, this->KeepBounces, smpLoop);
  this->BounceCount = indirect.bounceCount;
  this->RestBound = indirect.restBound;
  this->Report = this->ReportOf(input->GetNumberOfPoints(), gather.laterRays());
  return indirect;
}

void vtkInterreflectionFilter::AddIndirectArrays(
  vtkPolyData* output, const shadelab::IndirectIrradiance& indirect, bool float64)
{
  vtkPointData* out = output->GetPointData();
  out->AddArray(rgbArray(this->ArrayPrefix + "indirect_irradiance", indirect.irradiance, float64));
  out->AddArray(rgbArray(this->ArrayPrefix + "indirect_irradiance_std_error", indirect.standardError, float64));
  for (std::size_t n = 0; n < indirect.bounces.size(); ++n)
  {
    out->AddArray(
      rgbArray(this->ArrayPrefix + "indirect_bounce_" + std::to_string(n + 1), indirect.bounces[n], float64));
  }
}

std::string vtkInterreflectionFilter::ReportOf(vtkIdType points, int laterRays) const
{
  const std::size_t rays = std::size_t(points) * std::size_t(this->Samples);
  return shadelab::countOf(std::size_t(this->BounceCount), "bounce") + " from '" + this->RadiosityArrayName + "', " +
    std::to_string(this->Samples) + " gather rays per vertex" +
    (this->BounceCount > 1 && laterRays < this->Samples ? " (" + std::to_string(laterRays) + " for the later bounces)"
                                                        : "") +
    "; " + std::to_string(this->BackHits) + " of " + shadelab::countOf(rays, "ray") + " (" +
    shadelab::withDigits(100.0 * double(this->BackHits) / double(rays), 2) +
    "%) met the back of a triangle and carried nothing; " +
    (std::isfinite(this->RestBound)
        ? "the bounces past them add at most " + shadelab::scientific(this->RestBound) + " to a diffuse term"
        : std::string("with an albedo of 1 the bounces past them have no bound"));
}
