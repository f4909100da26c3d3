#pragma once
// The scene's interreflection added to vtkLocalReflectanceFilter's shaded arrays
// (docs/formulas.md section 23): the direct diffuse term is the radiosity the first bounce
// reflects, vtkInterreflectionFilter gathers the bounces, and kd times their irradiance joins
// the diffuse and total terms.
#include "ArrayCatalog.h"
#include "MaterialArrays.h"
#include "MethodChoice.h"
#include "Scene.h"
#include "ShadeLabMeshPieces.h"

#include "vtkDataArray.h"
#include "vtkSmartPointer.h"

#include <string>
#include <vector>

class vtkInterreflectionFilter;
class vtkPolyData;

namespace shadelab
{
/// The request the kernel shades for interreflection: `asked`, with the diffuse total (the
/// first bounce's radiosity) and, for ambient_minus_indirect, the ambient total.
ArrayRequest withInterreflectionSources(const Scene& scene, const ArrayRequest& asked);

/// Runs `step` on the input's surface with the shading normals, from the diffuse total in
/// `arrays` and the material's kd (per vertex where `material` has it); adds kd E_ind to the
/// diffuse and total arrays and appends the interreflection arrays `asked` names, then drops the
/// totals shaded only for it. On a split mesh's piece (`pieces`), the step gathers against the
/// whole mesh, every process alike, an empty piece too (a collective call). Under a tolerance
/// (`choice`, the plan's), the bounces and the gather rays are chosen for its shares and
/// written into it. Returns the step's report. Throws std::runtime_error where the step failed.
std::string addIndirectLight(vtkInterreflectionFilter* step, vtkPolyData* input, vtkDataArray* shadingNormals,
  const Scene& scene, const ArrayRequest& asked, const VertexMaterial* material, const std::string& prefix,
  std::vector<vtkSmartPointer<vtkDataArray>>& arrays, const MeshPieces& pieces,
  InterreflectionChoice* choice = nullptr);
}
