// vtkLocalReflectanceFilter's pass of the kernel over the points: the arrays of the side the
// viewer sees, and for interreflection on a surface shaded on both sides, the other side's.
#include "vtkLocalReflectanceFilterInternals.h"

#include "ArrayCatalog.h"
#include "ShadeLabIndirectLight.h"
#include "ShadeLabShadedArrays.h"

#include "vtkPolyData.h"

#include <stdexcept>

using namespace shadelab::shading;

shadelab::HiddenSide vtkLocalReflectanceFilter::ShadeHiddenSide(vtkPolyData* input, vtkDataArray* shadingNormals,
  const ShadingPlan& plan, const shadelab::MeshPieces& pieces, double start, double span)
{
  // Its diffuse term alone: no interreflection of its own, and no ambient occlusion, which
  // only the ambient term takes.
  ShadingPlan hidden = plan;
  hidden.scene.shadedSide = shadelab::ShadedSide::Hidden;
  hidden.scene.interreflection.reset();
  hidden.scene.ambientOcclusion.reset();
  hidden.request = shadelab::selectArrays(hidden.scene, { "diffuse", "shading_flags" });
  for (std::size_t l = 0; l < plan.request.indirectTransfer.size(); ++l) // the transfers whose bounces are asked for
  {
    hidden.request.lights[l][int(shadelab::LightTerm::ShTransfer)] = plan.request.indirectTransfer[l];
  }
  const std::string seenSideReport = this->VisibilityReport;
  this->StartStep(start, span / 2);
  vtkPolyData* hiddenSideRays = this->PrepareVisibility(input, shadingNormals, hidden, pieces);
  if (hiddenSideRays)
  {
    this->VisibilityReport =
      seenSideReport + " Then for the side of each vertex hidden from the viewer: " + this->VisibilityReport;
  }
  if (input->GetNumberOfPoints() == 0) // an empty piece joins the rays' exchanges only
  {
    return {};
  }
  this->StartStep(start + span / 2, span / 2);
  SamplingOutcome unreported; // the seen side's sampling is the one reported
  std::vector<vtkSmartPointer<vtkDataArray>> arrays =
    this->ShadedArrays(input, shadingNormals, hiddenSideRays, hidden, pieces, unreported);
  auto made = [&](const std::string& name)
  {
    if (vtkDataArray* array = shadelab::named(arrays, name))
    {
      return vtkSmartPointer<vtkDataArray>(array);
    }
    throw std::logic_error("the hidden side's shading made no array '" + name + "'");
  };
  shadelab::HiddenSide side{ made(shadelab::totalArrayName(this->ArrayPrefix, shadelab::TotalTerm::Diffuse)),
    made(shadelab::flagsArrayName(this->ArrayPrefix)), {} };
  for (std::size_t l = 0; l < plan.request.indirectTransfer.size(); ++l)
  {
    if (plan.request.indirectTransfer[l])
    {
      const std::string name =
        shadelab::lightArrayName(this->ArrayPrefix, plan.scene.lights[l].name, shadelab::LightTerm::ShTransfer);
      side.transfers[name] = made(name);
    }
  }
  return side;
}

std::vector<vtkSmartPointer<vtkDataArray>> vtkLocalReflectanceFilter::ShadedArrays(vtkPolyData* input,
  vtkDataArray* shadingNormals, vtkPolyData* seen, const ShadingPlan& plan, const shadelab::MeshPieces& pieces,
  SamplingOutcome& sampling)
{
  shadelab::ShadingInputs inputs;
  if (pieces.split()) // each point's samples are seeded by its index in the whole mesh
  {
    static_assert(sizeof(vtkIdType) == sizeof(long long), "ids seed samples as 64-bit integers");
    inputs.sampleIds = reinterpret_cast<const long long*>(pieces.pointIds()->data());
  }
  if (plan.scene.material.arrays.any())
  {
    if (plan.precision == shadelab::Precision::Float32)
    {
      this->Internals->VertexMaterial.withFloat32(); // under a tolerance that chose float32: from float64
    }
    inputs.material = &this->Internals->VertexMaterial;
  }
  // Besides the kernel's: the occlusion arrays asked for, and which material values were clamped.
  std::vector<vtkSmartPointer<vtkDataArray>> besideShading = seen
    ? useVisibility(seen, plan.scene, plan.request, this->ArrayPrefix, inputs)
    : std::vector<vtkSmartPointer<vtkDataArray>>();
  if (plan.scene.material.arrays.clamps())
  {
    besideShading.push_back(clampedMaterialArray(this->Internals->VertexMaterial.clamped, this->ArrayPrefix));
  }
  vtkDataArray* points = input->GetPoints()->GetData();
  // The spectral mode always has its total, in XYZ too, and its difference from the RGB model.
  shadelab::ArrayRequest request = shadelab::withInterreflectionSources(plan.scene, plan.request);
  std::optional<shadelab::LightColors> spectralColors;
  if (plan.scene.spectral)
  {
    spectralColors = shadelab::spectralLightColors(plan.scene);
    inputs.lightColors = &*spectralColors;
    request.totals[int(shadelab::TotalTerm::Total)] = true;
  }
  const ProgressReport progress = [this](double done) { this->ReportProgress(done); };
  auto shadeWith = [&](const shadelab::ArrayRequest& asked, SamplingOutcome* outcome)
  {
    return shadeIn(plan.precision, plan.scene, asked, plan.methods, this->ArrayPrefix, points, shadingNormals, inputs,
      &progress, outcome ? &outcome->shortOfTarget : nullptr, outcome ? &outcome->standardError : nullptr,
      outcome ? &outcome->samplesDrawn : nullptr);
  };

  std::vector<vtkSmartPointer<vtkDataArray>> arrays = shadeWith(request, &sampling);
  if (spectralColors)
  {
    inputs.lightColors = nullptr; // the kernel's own products of RGB values: the RGB model
    shadelab::ArrayRequest totalAlone = shadelab::selectArrays(plan.scene, { "total" });
    totalAlone.flags = false;
    const std::vector<vtkSmartPointer<vtkDataArray>> rgbModel = shadeWith(totalAlone, nullptr);
    addSpectralArrays(arrays, rgbModel.front(), this->ArrayPrefix);
  }
  arrays.insert(arrays.end(), besideShading.begin(), besideShading.end());
  return arrays;
}
