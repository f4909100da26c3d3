#include "ShadeLabShadedArrays.h"

#include "Colorimetry.h"
#include "ShadeLabMaterialArrays.h"

#include "vtkDoubleArray.h"
#include "vtkFloatArray.h"
#include "vtkPointData.h"
#include "vtkTypeUInt64Array.h"
#include "vtkUnsignedCharArray.h"

#include <glm/matrix.hpp>

namespace shadelab::shading
{
/// Points the kernel's inputs at the rays' arrays in `seen`: each shadowed light's visibility,
/// the ambient occlusion and the flags. Returns the occlusion arrays the request asks for, to
/// be output as they are (float32 whatever the precision: estimates, not exact terms).
std::vector<vtkSmartPointer<vtkDataArray>> useVisibility(vtkPolyData* seen, const shadelab::Scene& scene,
  const shadelab::ArrayRequest& request, const std::string& prefix, shadelab::ShadingInputs& inputs)
{
  vtkPointData* data = seen->GetPointData();
  auto floats = [&](const std::string& name) { return vtkFloatArray::SafeDownCast(data->GetArray(name.c_str())); };
  auto hiddenSamplesOf = [&](const std::string& light) -> const std::uint64_t*
  {
    static_assert(sizeof(vtkTypeUInt64) == sizeof(std::uint64_t), "the hidden samples' words are 64 bits");
    auto* words =
      vtkTypeUInt64Array::SafeDownCast(data->GetArray(shadelab::hiddenSamplesArrayName(prefix, light).c_str()));
    return words ? reinterpret_cast<const std::uint64_t*>(words->GetPointer(0)) : nullptr;
  };
  auto shadowedTermsOf = [&](const std::string& light) -> const double*
  {
    auto* terms = vtkDoubleArray::SafeDownCast(data->GetArray(shadelab::shadowedTermsArrayName(prefix, light).c_str()));
    return terms ? terms->GetPointer(0) : nullptr;
  };
  for (const shadelab::NamedLight& light : scene.lights)
  {
    // A local light's visibility multiplies its terms; an area light's or a map's samples are
    // weighted by the bits of those the mesh hides, or, drawn to a target, the visibility step
    // estimated it.
    const bool distributed = light.shadows && shadelab::isDistributed(light.source);
    const bool local = light.shadows && !distributed;
    inputs.lightVisibility.push_back(local
        ? floats(shadelab::lightArrayName(prefix, light.name, shadelab::LightTerm::Visibility))->GetPointer(0)
        : nullptr);
    inputs.lightHiddenSamples.push_back(distributed ? hiddenSamplesOf(light.name) : nullptr);
    inputs.lightShadowedTerms.push_back(distributed ? shadowedTermsOf(light.name) : nullptr);
  }
  std::vector<vtkSmartPointer<vtkDataArray>> requested;
  if (scene.ambientOcclusion)
  {
    inputs.ambientOcclusion =
      floats(shadelab::occlusionArrayName(prefix, shadelab::OcclusionTerm::AmbientOcclusion))->GetPointer(0);
    inputs.ambientOcclusionStdError =
      floats(shadelab::occlusionArrayName(prefix, shadelab::OcclusionTerm::AmbientOcclusionStdError))->GetPointer(0);
  }
  for (int t = 0; t < shadelab::OcclusionTermCount; ++t)
  {
    if (request.occlusion[t])
    {
      requested.push_back(data->GetArray(shadelab::occlusionArrayName(prefix, shadelab::OcclusionTerm(t)).c_str()));
    }
  }
  inputs.flags = vtkUnsignedCharArray::SafeDownCast(data->GetArray(shadelab::visibilityFlagsArrayName(prefix).c_str()))
                   ->GetPointer(0);
  return requested;
}

/// The spectral mode's arrays besides the kernel's linear sRGB (docs/formulas.md section 22):
/// each RGB total's XYZ twin ("<total>_xyz", by the inverse of the sRGB matrix), and
/// "total_rgb_difference", the spectral total less the RGB model's (rgbTotal).
void addSpectralArrays(
  std::vector<vtkSmartPointer<vtkDataArray>>& arrays, vtkDataArray* rgbTotal, const std::string& prefix)
{
  const glm::dmat3 toXyz = glm::inverse(shadelab::xyzToLinearSrgb());
  // An array of the total's type and length, 3 components, to fill.
  auto emptyLike = [](vtkDataArray* total, const std::string& name)
  {
    vtkSmartPointer<vtkDataArray> array;
    array.TakeReference(total->NewInstance());
    array->SetName(name.c_str());
    array->SetNumberOfComponents(3);
    array->SetNumberOfTuples(total->GetNumberOfTuples());
    return array;
  };
  std::vector<vtkSmartPointer<vtkDataArray>> added;
  for (const vtkSmartPointer<vtkDataArray>& array : arrays)
  {
    for (int t = 0; t < shadelab::TotalTermCount; ++t)
    {
      const std::string name = shadelab::totalArrayName(prefix, shadelab::TotalTerm(t));
      if (name != array->GetName())
      {
        continue;
      }
      const vtkSmartPointer<vtkDataArray> xyz =
        emptyLike(array, shadelab::totalXyzArrayName(prefix, shadelab::TotalTerm(t)));
      for (vtkIdType i = 0; i < array->GetNumberOfTuples(); ++i)
      {
        double rgb[3];
        array->GetTuple(i, rgb);
        const glm::dvec3 value = toXyz * glm::dvec3(rgb[0], rgb[1], rgb[2]);
        xyz->SetTuple3(i, value.x, value.y, value.z);
      }
      added.push_back(xyz);
      if (t == int(shadelab::TotalTerm::Total))
      {
        const vtkSmartPointer<vtkDataArray> difference = emptyLike(array, shadelab::rgbDifferenceArrayName(prefix));
        for (vtkIdType i = 0; i < array->GetNumberOfTuples(); ++i)
        {
          for (int c = 0; c < 3; ++c)
          {
            difference->SetComponent(i, c, array->GetComponent(i, c) - rgbTotal->GetComponent(i, c));
          }
        }
        added.push_back(difference);
      }
    }
  }
  arrays.insert(arrays.end(), added.begin(), added.end());
}

/// The material_clamped array: per vertex, bit c where coefficient c's value was clamped.
vtkSmartPointer<vtkDataArray> clampedMaterialArray(const std::vector<std::uint8_t>& clamped, const std::string& prefix)
{
  auto array = vtkSmartPointer<vtkUnsignedCharArray>::New();
  array->SetName(shadelab::materialClampedArrayName(prefix).c_str());
  array->SetNumberOfTuples(static_cast<vtkIdType>(clamped.size()));
  std::copy(clamped.begin(), clamped.end(), array->GetPointer(0));
  return array;
}

/// The ambient occlusion's rays from the pilot's points: its rays array where drawn to a
/// target, else its fixed count each.
double occlusionRayCount(const shadelab::Scene& scene, vtkPolyData* seen, const std::string& prefix, std::size_t count)
{
  if (!scene.ambientOcclusion)
  {
    return 0;
  }
  vtkDataArray* rays =
    seen->GetPointData()->GetArray(shadelab::occlusionArrayName(prefix, shadelab::OcclusionTerm::Rays).c_str());
  double sum = rays ? 0 : double(scene.ambientOcclusion->sampling.samples) * double(count);
  for (vtkIdType i = 0; rays && i < rays->GetNumberOfTuples(); ++i)
  {
    sum += rays->GetComponent(i, 0);
  }
  return sum;
}
}
