#pragma once
// vtkLocalReflectanceFilter's output arrays: allocated for what the request asks, the kernel
// run over every point into them (with progress between blocks), and the arrays made beside
// the kernel's (the rays' occlusion arrays, the spectral mode's, material_clamped). Private to
// the filter (its tolerance's sample and forecast shade through them too).
#include "ArrayCatalog.h"
#include "ShadeLabLargeArrays.h"
#include "ShadingKernel.h"

#include "vtkAOSDataArrayTemplate.h"
#include "vtkArrayDispatch.h"
#include "vtkDataArrayRange.h"
#include "vtkPolyData.h"
#include "vtkSMPTools.h"
#include "vtkSmartPointer.h"

#include <algorithm>
#include <cstdint>
#include <functional>
#include <sstream>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace shadelab::shading
{
/// Allocates the requested arrays of value type T on the output and points the kernel's
/// outputs at their memory.
template<typename T>
class OutputArrays
{
public:
  using ArrayType = vtkAOSDataArrayTemplate<T>;

  OutputArrays(
    const shadelab::Scene& scene, const shadelab::ArrayRequest& request, const std::string& prefix, vtkIdType count)
  {
    // In the order of shadelab::availableArrays: totals, flags, then each light's terms.
    for (int t = 0; t < shadelab::TotalTermCount; ++t)
    {
      outputs.totals[t] = request.totals[t] ? add(shadelab::totalArrayName(prefix, TotalTerm(t)), 3, count) : nullptr;
    }
    if (request.flags)
    {
      auto flags = vtkSmartPointer<vtkUnsignedCharArray>::New();
      flags->SetName(shadelab::flagsArrayName(prefix).c_str());
      allocate<unsigned char>(flags.GetPointer(), count);
      outputs.flags = flags->GetPointer(0);
      arrays.push_back(flags);
    }
    outputs.lights.resize(scene.lights.size());
    for (std::size_t l = 0; l < scene.lights.size(); ++l)
    {
      outputs.lights[l].fill(nullptr);
      for (int t = 0; t < shadelab::LightTermCount; ++t)
      {
        if (request.lights[l][t])
        {
          outputs.lights[l][t] = add(shadelab::lightArrayName(prefix, scene.lights[l].name, LightTerm(t)),
            shadelab::lightTermComponents(scene.lights[l], LightTerm(t)), count);
        }
      }
    }
  }

  shadelab::ShadingOutputs<T> outputs;
  std::vector<vtkSmartPointer<vtkDataArray>> arrays;

private:
  T* add(const std::string& name, int components, vtkIdType count)
  {
    auto array = vtkSmartPointer<ArrayType>::New();
    array->SetName(name.c_str());
    array->SetNumberOfComponents(components);
    allocate<T>(array.GetPointer(), count);
    arrays.push_back(array);
    return array->GetPointer(0);
  }

  /// Memory for `count` tuples, in huge pages when large (ShadeLabLargeArrays.h). Throws
  /// std::runtime_error, naming the array, when there is not enough.
  template<typename Value>
  static void allocate(vtkAOSDataArrayTemplate<Value>* array, vtkIdType count)
  {
    if (!shadelab::allocateTuples(array, count))
    {
      std::ostringstream message;
      message << "not enough memory for the array '" << array->GetName() << "' ("
              << static_cast<double>(count) * array->GetNumberOfComponents() * sizeof(Value) / 1e6
              << " MB): request fewer arrays, or float32";
      throw std::runtime_error(message.str());
    }
  }
};

/// Told the share of the points done after each block of the shading; may throw
/// shadelab::RunAborted to stop it.
using ProgressReport = std::function<void(double)>;

/// Runs the kernel over all points in a vtkSMPTools loop, for any real point and normal
/// array types (dispatched once, so the loop reads raw memory).
template<typename T>
struct ShadeAllPoints
{
  const shadelab::ShadingKernel<T>& kernel;
  const ProgressReport* progress;

  template<typename PointArray, typename NormalArray>
  void operator()(PointArray* points, NormalArray* normals) const
  {
    const auto pointRange = vtk::DataArrayTupleRange<3>(points);
    const auto normalRange = vtk::DataArrayTupleRange<3>(normals);
    const vtkIdType count = pointRange.size();
    // Blocks of the SMP loop, so progress can be reported (and an abort heard) between them:
    // tenths of a large mesh, hundredths where area lights or environment maps make every
    // vertex slow (a few hundred vertices at least, a share of a second's work for two threads).
    const vtkIdType block =
      kernel.hasDistributedLights() ? std::max<vtkIdType>(count / 100, 256) : std::max<vtkIdType>(count / 10, 100000);
    for (vtkIdType first = 0; first < count; first += block)
    {
      const vtkIdType last = std::min(count, first + block);
      vtkSMPTools::For(first, last,
        [&](vtkIdType begin, vtkIdType end)
        {
          shadelab::shadeRange(kernel, static_cast<std::size_t>(begin), static_cast<std::size_t>(end),
            [&](std::size_t i, shadelab::VertexBlock<T>& block, std::size_t k)
            {
              const auto p = pointRange[i];
              const auto n = normalRange[i];
              block.set(k, shadelab::Vec3<T>(T(p[0]), T(p[1]), T(p[2])), shadelab::Vec3<T>(T(n[0]), T(n[1]), T(n[2])));
            });
        });
      if (progress)
      {
        (*progress)(static_cast<double>(last) / count);
      }
    }
  }
};

/// Per scene light (empty for those not drawn to a target), 1 at each vertex that stopped at the
/// maximum short of its target.
using ShortOfTarget = std::vector<std::vector<std::uint8_t>>;

/// The requested arrays, shaded in precision T. progress (or nullptr) is told how far it is;
/// shortOfTarget (or nullptr) receives the vertices that stopped short of their targets, and
/// standardError and samplesDrawn (or nullptr), where they are sized for every point, each
/// one's sampled standard error and count of samples (shadelab::ShadingOutputs').
template<typename T>
std::vector<vtkSmartPointer<vtkDataArray>> shade(const shadelab::Scene& scene, const shadelab::ArrayRequest& request,
  const std::vector<shadelab::LightMethod>& methods, const std::string& prefix, vtkDataArray* points,
  vtkDataArray* normals, const shadelab::ShadingInputs& inputs, const ProgressReport* progress,
  ShortOfTarget* shortOfTarget = nullptr, std::vector<double>* standardError = nullptr,
  std::vector<std::uint32_t>* samplesDrawn = nullptr)
{
  const auto count = static_cast<std::size_t>(points->GetNumberOfTuples());
  OutputArrays<T> arrays(scene, request, prefix, points->GetNumberOfTuples());
  if (standardError && standardError->size() == count)
  {
    arrays.outputs.sampledStandardError = standardError->data();
  }
  if (samplesDrawn && samplesDrawn->size() == count)
  {
    arrays.outputs.samplesDrawn = samplesDrawn->data();
  }
  if (shortOfTarget)
  {
    shortOfTarget->assign(scene.lights.size(), {});
    arrays.outputs.shortOfTarget.assign(scene.lights.size(), nullptr);
    for (std::size_t l = 0; l < methods.size(); ++l)
    {
      if (methods[l].targets.any())
      {
        (*shortOfTarget)[l].resize(static_cast<std::size_t>(points->GetNumberOfTuples()));
        arrays.outputs.shortOfTarget[l] = (*shortOfTarget)[l].data();
      }
    }
  }
  const shadelab::ShadingKernel<T> kernel(scene, arrays.outputs, methods, inputs);
  ShadeAllPoints<T> worker{ kernel, progress };
  using Reals = vtkArrayDispatch::Reals;
  if (!vtkArrayDispatch::Dispatch2ByValueType<Reals, Reals>::Execute(points, normals, worker))
  {
    worker(points, normals); // other value types, through the generic vtkDataArray API
  }

  return arrays.arrays;
}

/// shade<T> in the plan's precision: float64's or float32's arithmetic and arrays.
template<typename... Arguments>
std::vector<vtkSmartPointer<vtkDataArray>> shadeIn(Precision precision, Arguments&&... arguments)
{
  return precision == Precision::Float64 ? shade<double>(std::forward<Arguments>(arguments)...)
                                         : shade<float>(std::forward<Arguments>(arguments)...);
}

/// Points the kernel's inputs at the rays' arrays in `seen`: each shadowed light's visibility,
/// the ambient occlusion and the flags. Returns the occlusion arrays the request asks for, to
/// be output as they are (float32 whatever the precision: estimates, not exact terms).
std::vector<vtkSmartPointer<vtkDataArray>> useVisibility(vtkPolyData* seen, const shadelab::Scene& scene,
  const shadelab::ArrayRequest& request, const std::string& prefix, shadelab::ShadingInputs& inputs);

/// The spectral mode's arrays besides the kernel's linear sRGB (docs/formulas.md section 22):
/// each RGB total's XYZ twin ("<total>_xyz", by the inverse of the sRGB matrix), and
/// "total_rgb_difference", the spectral total less the RGB model's (rgbTotal).
void addSpectralArrays(
  std::vector<vtkSmartPointer<vtkDataArray>>& arrays, vtkDataArray* rgbTotal, const std::string& prefix);

/// The material_clamped array: per vertex, bit c where coefficient c's value was clamped.
vtkSmartPointer<vtkDataArray> clampedMaterialArray(const std::vector<std::uint8_t>& clamped, const std::string& prefix);

/// The ambient occlusion's rays from the pilot's points: its rays array where drawn to a
/// target, else its fixed count each.
double occlusionRayCount(const shadelab::Scene& scene, vtkPolyData* seen, const std::string& prefix, std::size_t count);
}
