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

#include <functional>
#include <string>
#include <vector>

class vtkAlgorithm;
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
  /// The points in the order of their global ids, which must number them 0 to n-1 (each
  /// point's id is its index here, and seeds its samples); polygons and strips in the order of
  /// their global cell ids; ghost cells left out; point normals where asked for and the pieces
  /// have them. nullptr where every piece is empty, and on the empty pieces where one process
  /// holds the whole mesh.
  vtkSmartPointer<vtkPolyData> mesh;
  /// Each point of the piece's index in mesh: its global id. Empty where the piece is the
  /// whole mesh or is empty.
  std::vector<vtkIdType> pieceIds;
  /// Why the pieces do not make one mesh; the same text on every process.
  std::string problem;
};

/// Gathers the whole mesh from every process's piece (a collective call). Where one process
/// has all the points and they have no global ids, its piece is the whole mesh and only a few
/// counts are exchanged. Several pieces with points need global point and cell ids.
SHADELABFILTERS_EXPORT WholeMesh gatherWholeMesh(vtkMultiProcessController* controller, vtkPolyData* piece, bool withNormals);

/// A filter's work on a mesh taken whole: into result, at the points pieceIds lists (nullptr:
/// every point); arrays it adds have a value per listed point, except computed normals, which
/// have one per point. Returns whether it succeeded (having reported why not).
using PieceComputation =
  std::function<bool(vtkPolyData* mesh, vtkPolyData* result, const std::vector<vtkIdType>* pieceIds)>;

/// A filter's RequestData for a piece of a split mesh (a collective call): gathers the whole
/// mesh, computes on it for the piece's points, and gives output the piece with what was
/// computed. Returns 1, or 0 on every process where any failed (each failure reported through
/// `filter`), so that no process waits for a failed one in a later collective call.
SHADELABFILTERS_EXPORT int computeOnPiece(vtkMultiProcessController* controller, vtkAlgorithm* filter,
  vtkPolyData* piece, vtkPolyData* output, bool withNormals, const PieceComputation& compute);

/// values' tuples at ids, in a new array of the same type and name.
SHADELABFILTERS_EXPORT vtkSmartPointer<vtkDataArray> tuplesAt(vtkDataArray* values, const std::vector<vtkIdType>& ids);
}

#endif
