#include "vtkTransferRelightFilter.h"

#include "EnvironmentLightEstimator.h"
#include "EnvironmentMap.h"
#include "RadianceTransfer.h"
#include "ShadeLabRealArrays.h"

#include "vtkArrayDispatch.h"
#include "vtkDataArrayRange.h"
#include "vtkDoubleArray.h"
#include "vtkFloatArray.h"
#include "vtkInformation.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkSMPTools.h"
#include "vtkSmartPointer.h"

#include <algorithm>
#include <cmath>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

vtkStandardNewMacro(vtkTransferRelightFilter);

namespace
{
/// The order of a transfer array of this many components: 2 to largestShOrder, or -1.
int orderOfComponents(int components)
{
  const int order = shadelab::shOrderOfCount(components);
  return order >= 2 ? order : -1;
}

/// A transfer's values in the order of its array's components.
double* valuesOf(shadelab::TransferVector& vector)
{
  return vector.data();
}
double* valuesOf(shadelab::ChannelTransfer& vector)
{
  static_assert(sizeof(shadelab::ChannelTransfer) == 3 * sizeof(double) * std::tuple_size<shadelab::ChannelTransfer>(),
    "an RGB value is three doubles, packed");
  return &vector[0].x;
}

/// Each vertex's irradiance, the dot product of the radiance's coefficients with its transfer:
/// Vector, one number per coefficient (TransferVector), or an RGB value per coefficient
/// (ChannelTransfer, component 3 k + c).
template<typename Vector>
struct RelightWorker
{
  const shadelab::ShCoefficients* radiance;

  template<typename TransferArray, typename IrradianceArray>
  void operator()(TransferArray* transfer, IrradianceArray* irradiance) const
  {
    const auto vectors = vtk::DataArrayTupleRange(transfer);
    auto out = vtk::DataArrayTupleRange<3>(irradiance);
    const int components = transfer->GetNumberOfComponents();
    vtkSMPTools::For(0, transfer->GetNumberOfTuples(),
      [&](vtkIdType begin, vtkIdType end)
      {
        for (vtkIdType i = begin; i < end; ++i)
        {
          Vector vector{};
          const auto tuple = vectors[i];
          std::copy(tuple.begin(), tuple.begin() + components, valuesOf(vector));
          const shadelab::Rgb e = shadelab::irradianceFromTransfer(*radiance, vector);
          out[i][0] = e.x;
          out[i][1] = e.y;
          out[i][2] = e.z;
        }
      });
  }
};

/// An RGB array, float64 for a float64 transfer and float32 otherwise, of each vertex's dot
/// product of the radiance with the transfer (Vector as RelightWorker's).
template<typename Vector>
vtkSmartPointer<vtkDataArray> relit(
  vtkDataArray* transfer, const shadelab::ShCoefficients& radiance, const std::string& name)
{
  vtkSmartPointer<vtkDataArray> irradiance =
    shadelab::realArray(name, 3, transfer->GetNumberOfTuples(), transfer->GetDataType() == VTK_DOUBLE);
  using Reals = vtkArrayDispatch::Reals;
  RelightWorker<Vector> worker{ &radiance };
  if (!vtkArrayDispatch::Dispatch2ByValueType<Reals, Reals>::Execute(transfer, irradiance.Get(), worker))
  {
    worker(transfer, irradiance.Get()); // a transfer array of another type, through vtkDataArray's API
  }
  return irradiance;
}
}

void vtkTransferRelightFilter::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "EnvironmentMapFileName: " << this->EnvironmentMapFileName << "\n";
  os << indent << "Rotation: " << this->Rotation << "\n";
  os << indent << "Intensity: " << this->Intensity << "\n";
  os << indent << "Color: " << this->Color[0] << " " << this->Color[1] << " " << this->Color[2] << "\n";
  os << indent << "TransferArrayName: " << this->TransferArrayName << "\n";
  os << indent << "UseIndirectTransfer: " << this->UseIndirectTransfer << "\n";
  os << indent << "OutputArrayName: " << this->OutputArrayName << "\n";
}

vtkDataArray* vtkTransferRelightFilter::FindTransfer(vtkPolyData* input)
{
  vtkPointData* points = input->GetPointData();
  const std::string suffix = "_sh_transfer"; // <prefix><light>_sh_transfer
  std::vector<std::string> found;
  for (int a = 0; a < points->GetNumberOfArrays(); ++a)
  {
    const char* name = points->GetArrayName(a);
    const std::string given = name ? name : "";
    const bool named = this->TransferArrayName.empty()
      ? given.size() >= suffix.size() && given.compare(given.size() - suffix.size(), suffix.size(), suffix) == 0
      : given == this->TransferArrayName;
    if (named)
    {
      found.push_back(given);
    }
  }
  if (found.size() != 1)
  {
    std::string names;
    for (const std::string& name : found)
    {
      names += (names.empty() ? "" : ", ") + name;
    }
    if (!this->TransferArrayName.empty())
    {
      vtkErrorMacro("the input has no point array '" << this->TransferArrayName << "'");
    }
    else if (found.empty())
    {
      vtkErrorMacro("the input has no point array whose name ends in '_sh_transfer': shade the mesh with "
                    "\"estimator\": \"prt\" (shadelab shade --envmap-estimator prt) first");
    }
    else
    {
      vtkErrorMacro("the input has several transfer arrays (" << names << "): set TransferArrayName to one of them");
    }
    return nullptr;
  }
  vtkDataArray* transfer = points->GetArray(found.front().c_str());
  if (!transfer)
  {
    vtkErrorMacro("point array '" << found.front() << "' is not a transfer vector: it is not numeric");
    return nullptr;
  }
  if (orderOfComponents(transfer->GetNumberOfComponents()) < 0)
  {
    vtkErrorMacro("point array '" << found.front()
                                  << "' is not a transfer vector: it must have 9, 16 or 25 "
                                     "components (orders 2, 3, 4), not "
                                  << transfer->GetNumberOfComponents());
    return nullptr;
  }
  if (found.front() == this->OutputArrayName)
  {
    vtkErrorMacro("OutputArrayName is the transfer array's name, '" << found.front()
                                                                    << "': choose another name for the irradiance");
    return nullptr;
  }
  return transfer;
}

bool vtkTransferRelightFilter::FindIndirectTransfer(vtkPolyData* input, vtkDataArray* transfer, vtkDataArray*& indirect)
{
  const std::string name = std::string(transfer->GetName()) + "_indirect";
  indirect = this->UseIndirectTransfer ? input->GetPointData()->GetArray(name.c_str()) : nullptr;
  if (indirect && indirect->GetNumberOfComponents() != 3 * transfer->GetNumberOfComponents())
  {
    vtkErrorMacro("point array '" << name << "' is not the indirect part of '" << transfer->GetName()
                                  << "': it must have 3 components per coefficient, "
                                  << 3 * transfer->GetNumberOfComponents() << ", not "
                                  << indirect->GetNumberOfComponents()
                                  << " (or turn UseIndirectTransfer off to relight without it)");
    return false;
  }
  return true;
}

int vtkTransferRelightFilter::RequestData(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  vtkPolyData* input = vtkPolyData::GetData(inputVector[0]);
  vtkPolyData* output = vtkPolyData::GetData(outputVector);
  output->ShallowCopy(input);
  this->Report.clear();
  vtkDataArray* transfer = this->FindTransfer(input);
  vtkDataArray* indirect = nullptr;
  if (!transfer || !this->FindIndirectTransfer(input, transfer, indirect))
  {
    return 0;
  }
  if (!std::isfinite(this->Rotation))
  {
    vtkErrorMacro("Rotation must be a finite angle in degrees");
    return 0;
  }
  if (!std::all_of(this->Color, this->Color + 3, [](double c) { return std::isfinite(c) && c >= 0; }))
  {
    vtkErrorMacro("Color's components must be finite numbers >= 0");
    return 0;
  }
  shadelab::EnvironmentLight light;
  light.file = this->EnvironmentMapFileName;
  light.rotationDegrees = this->Rotation;
  light.intensity = this->Intensity;
  light.color = shadelab::Rgb(this->Color[0], this->Color[1], this->Color[2]);
  try
  {
    light.map = std::make_shared<const shadelab::EnvironmentMap>(shadelab::readEnvironmentMap(light.file));
  }
  catch (const std::runtime_error& error)
  {
    vtkErrorMacro(<< error.what());
    return 0;
  }
  const int order = orderOfComponents(transfer->GetNumberOfComponents());
  const shadelab::ShCoefficients radiance = shadelab::worldRadianceCoefficients(light, order);
  const vtkSmartPointer<vtkDataArray> irradiance =
    relit<shadelab::TransferVector>(transfer, radiance, this->OutputArrayName);
  const bool replaces = output->GetPointData()->HasArray(this->OutputArrayName.c_str());
  this->Report = std::string("'") + this->OutputArrayName + "' from '" + transfer->GetName() + "' (order " +
    std::to_string(order) + ", " + std::to_string(shadelab::shCount(order)) + " coefficients) under " + light.file;
  if (indirect)
  {
    const std::string indirectName = this->OutputArrayName + "_indirect";
    const vtkSmartPointer<vtkDataArray> bounced = relit<shadelab::ChannelTransfer>(indirect, radiance, indirectName);
    for (vtkIdType i = 0; i < irradiance->GetNumberOfTuples(); ++i)
    {
      for (int c = 0; c < 3; ++c)
      {
        irradiance->SetComponent(i, c, irradiance->GetComponent(i, c) + bounced->GetComponent(i, c));
      }
    }
    output->GetPointData()->AddArray(bounced);
    this->Report += ", with the light the mesh reflects onto itself from '" + std::string(indirect->GetName()) +
      "' (alone in '" + indirectName + "')";
  }
  output->GetPointData()->AddArray(irradiance);
  this->Report += replaces ? "; it replaces the input's array of that name" : "";
  return 1;
}
