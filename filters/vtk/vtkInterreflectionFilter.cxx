#include "vtkInterreflectionFilter.h"

#include "Interreflection.h"
#include "NumberText.h"
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
              shadelab::RayVertex vertex{ {}, packedNormals(i), i };
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
  vtkDataArray* radiosityArray = this->RgbArray(input, this->RadiosityArrayName, "the direct radiosity");
  if (!radiosityArray)
  {
    return 0;
  }
  vtkDataArray* albedoArray =
    this->AlbedoArrayName.empty() ? nullptr : this->RgbArray(input, this->AlbedoArrayName, "the albedo");
  if (!this->AlbedoArrayName.empty() && !albedoArray)
  {
    return 0;
  }
  const shadelab::Rgb uniformAlbedo(this->Albedo[0], this->Albedo[1], this->Albedo[2]);
  const std::vector<shadelab::Rgb> albedo = albedoArray ? rgbValues(albedoArray) : std::vector<shadelab::Rgb>();
  const auto badAlbedo =
    std::find_if(albedo.begin(), albedo.end(), [](const shadelab::Rgb& kd) { return !isAlbedo(kd); });
  if (!isAlbedo(uniformAlbedo) || badAlbedo != albedo.end())
  {
    vtkErrorMacro("an albedo must be RGB in [0, 1] (above 1 a bounce reflects more light than arrives): "
      << (badAlbedo != albedo.end()
             ? "'" + this->AlbedoArrayName + "' at point " + std::to_string(badAlbedo - albedo.begin())
             : std::string("Albedo")));
    return 0;
  }
  const std::size_t points = static_cast<std::size_t>(input->GetNumberOfPoints());
  int laterRays = 0;
  shadelab::IndirectIrradiance indirect{ std::vector<shadelab::Rgb>(points), std::vector<shadelab::Rgb>(points), {} };
  try
  {
    if (this->Bounces > 0)
    {
      const std::unique_ptr<shadelab::OccluderMesh> occluders = shadelab::occludersOf(input);
      shadelab::BounceGather gather(*occluders, rgbValues(radiosityArray), { this->Samples, this->Stratified });
      laterRays = gather.laterRays();
      this->BackHits = gatherEveryVertex(*occluders, input, normals, { this->Samples, this->Stratified }, gather, this);
      indirect = gather.bounce(
        { uniformAlbedo, albedo.empty() ? nullptr : &albedo[0].x }, this->Bounces, this->KeepBounces, smpLoop);
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
  const bool float64 = radiosityArray->GetDataType() == VTK_DOUBLE;
  vtkPointData* out = output->GetPointData();
  out->AddArray(rgbArray(this->ArrayPrefix + "indirect_irradiance", indirect.irradiance, float64));
  out->AddArray(rgbArray(this->ArrayPrefix + "indirect_irradiance_std_error", indirect.standardError, float64));
  for (std::size_t n = 0; n < indirect.bounces.size(); ++n)
  {
    out->AddArray(
      rgbArray(this->ArrayPrefix + "indirect_bounce_" + std::to_string(n + 1), indirect.bounces[n], float64));
  }
  const std::size_t rays = this->Bounces > 0 ? points * std::size_t(this->Samples) : 0;
  this->Report = shadelab::countOf(std::size_t(this->Bounces), "bounce") + " from '" + this->RadiosityArrayName +
    "', " + std::to_string(this->Samples) + " gather rays per vertex" +
    (this->Bounces > 1 && laterRays < this->Samples ? " (" + std::to_string(laterRays) + " for the later bounces)"
                                                    : "") +
    "; " + std::to_string(this->BackHits) + " of " + shadelab::countOf(rays, "ray") + " (" +
    shadelab::withDigits(rays == 0 ? 0.0 : 100.0 * double(this->BackHits) / double(rays), 2) +
    "%) met the back of a triangle and carried nothing";
  this->UpdateProgress(1.0);
  return 1;
}
