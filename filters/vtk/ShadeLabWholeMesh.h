#ifndef ShadeLabWholeMesh_h
#define ShadeLabWholeMesh_h
// A mesh split over processes (MPI ranks under pvbatch or mpirun), put back together.
//
// What ShadeLab computes at a point depends on the whole mesh: its normal on the polygons
// around it, welded with copies at its position and turned by the winding and the outward
// test of the whole surface; the scene's placement and the tolerance's plan on the mesh's
// extent; its shadows and occlusion on every triangle. So a filter given a piece gathers the
// whole mesh's geometry on every process (points by global id, polygons by global cell id),
// computes on it exactly as one process would, and keeps its own piece's points. Every process
// holds the whole surface; the shading and the rays, the costly part, are divided.
#include "ShadeLabFiltersModule.h"

#include "vtkSmartPointer.h"
#include "vtkType.h"

#include <string>
#include <vector>

class vtkDataArray;
class vtkMultiProcessController;
class vtkPolyData;

namespace shadelab
{
/// Whether `piece` is to be treated as part of a mesh split over the controller's processes:
/// there are several processes, or the piece's points have global ids (pieces read in one
/// process from a .pvtp, say). The answer is the same on every process.
SHADELABFILTERS_EXPORT bool isPieceOfSplitMesh(vtkMultiProcessController* controller, vtkPolyData* piece);

/// The whole mesh a piece belongs to, and where the piece's points are in it.
struct WholeMesh
{
  /// Points in the order of their global ids, polygons and strips in the order of their global
  /// cell ids (without cell ids: by process, then as in the piece); ghost cells are left out.
  /// Point normals when asked for and the pieces have them. nullptr when this process's piece
  /// is empty and another holds the whole mesh.
  vtkSmartPointer<vtkPolyData> mesh;
  /// For each point of the piece, its index in mesh (empty when the piece is the whole).
  std::vector<vtkIdType> pieceIds;
  /// Why the pieces do not make one mesh; the same text on every process.
  std::string problem;
};

/// Gathers the whole mesh from every process's piece (a collective call). Where only one
/// process has points, its piece is the whole mesh and nothing is exchanged.
SHADELABFILTERS_EXPORT WholeMesh gatherWholeMesh(vtkMultiProcessController* controller, vtkPolyData* piece, bool withNormals);

/// The first process's problem where any process has one ("" where none has): every process
/// stops, or none does, with the same message (a collective call).
SHADELABFILTERS_EXPORT std::string agreedProblem(vtkMultiProcessController* controller, const std::string& problem);

/// values' tuples at ids, in a new array of the same type and name.
SHADELABFILTERS_EXPORT vtkSmartPointer<vtkDataArray> tuplesAt(vtkDataArray* values, const std::vector<vtkIdType>& ids);
}

#endif
