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

#include <map>
#include <string>
#include <vector>

class vtkInterreflectionFilter;
class vtkPolyData;

namespace shadelab
{
/// The array of that name among `arrays`, or nullptr.
vtkDataArray* named(const std::vector<vtkSmartPointer<vtkDataArray>>& arrays, const std::string& name);

/// On a surface shaded on both sides, the side of each vertex that the viewer does not see,
/// shaded as the seen side is (Scene::shadedSide Hidden): its direct diffuse term, the light it
/// sends to the vertices that see that side, and its shading flags, whose FlagNormalFlipped
/// says that side is the normal's back (so the seen one is its front).
struct HiddenSide
{
  vtkSmartPointer<vtkDataArray> diffuse;
  vtkSmartPointer<vtkDataArray> flags;
  /// The transfer vectors whose bounces are asked for, by the seen side's array names.
  std::map<std::string, vtkSmartPointer<vtkDataArray>> transfers;
};

/// The request the kernel shades for interreflection: `asked`, with the diffuse total (the
/// first bounce's radiosity) and, for ambient_minus_indirect, the ambient total.
ArrayRequest withInterreflectionSources(const Scene& scene, const ArrayRequest& asked);

/// Runs `step` on the input's surface with the shading normals, from the diffuse total in
/// `arrays` and the material's kd (per vertex where `material` has it), and on a surface shaded
/// on both sides from `hidden`'s diffuse term on the other side too; adds kd E_ind to the
/// diffuse and total arrays and appends the interreflection arrays `asked` names, then drops the
/// totals shaded only for it. On a split mesh's piece (`pieces`), the step gathers against the
/// whole mesh, every process alike, an empty piece too (a collective call). Under a tolerance
/// (`choice`, the plan's), the bounces and the gather rays are chosen for its shares and
/// written into it. Returns the step's report. Throws std::runtime_error where the step failed.
std::string addIndirectLight(vtkInterreflectionFilter* step, vtkPolyData* input, vtkDataArray* shadingNormals,
  const Scene& scene, const ArrayRequest& asked, const VertexMaterial* material, const std::string& prefix,
  std::vector<vtkSmartPointer<vtkDataArray>>& arrays, const MeshPieces& pieces, InterreflectionChoice* choice = nullptr,
  const HiddenSide* hidden = nullptr);
}
