#ifndef ShadeLabWholeMesh_h
#define ShadeLabWholeMesh_h
// A mesh split over processes (MPI ranks under pvbatch or mpirun), put back together.
//
// What ShadeLab computes at a point depends on the whole mesh: its normal on the polygons
// around it, welded with copies at its position and turned by the winding and the outward
// test of the whole surface; the scene's placement and the tolerance's plan on the mesh's
// extent; its shadows and occlusion on every triangle. So a filter given a piece gathers the
// whole mesh's geometry (points by global id, polygons by global cell id) where it must, and
// computes on it exactly as one process would:
// - the normals are computed piece by piece (ShadeLabPieceNormals.h); only a mesh with copies to
//   weld, windings to reorder or strips is gathered on the first process alone, which computes
//   its normals and sends each piece its points' values;
// - the rays, which meet every triangle, are cast by each process from its own points, against
//   the whole mesh gathered on every process;
// - the mesh's extent is reduced from the pieces' (ShadeLabMeshExtent.h), and each process
//   shades its own piece.
#include "ShadeLabFiltersModule.h"
#include "ShadeLabMeshPieces.h"

#include "vtkSmartPointer.h"
#include "vtkType.h"

#include <cstddef>
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

/// Where the whole mesh is gathered: on every process, or on the first only.
enum class WholeMeshOn
{
  EveryProcess,
  FirstProcess
};

/// Checks the pieces' global ids and cells (point normals included) and says how they lie,
/// exchanging only counts and point ids: what gatherWholeMesh checks before it gathers.
SHADELABFILTERS_EXPORT PieceLayout pieceLayout(vtkMultiProcessController* controller, vtkPolyData* piece);

/// The whole mesh a piece belongs to, and where the piece's points are in it.
struct WholeMesh
{
  /// The points in the order of their global ids, which must number them 0 to n-1 (each
  /// point's id is its index here, and seeds its samples); polygons and strips in the order of
  /// their global cell ids; ghost cells left out; point normals where asked for and the pieces
  /// have them. nullptr where every piece is empty, on the empty pieces where one process
  /// holds the whole mesh, and on the processes it is not gathered on.
  vtkSmartPointer<vtkPolyData> mesh;
  /// Whether the pieces were put together (the same on every process).
  bool putTogether = false;
  /// Each point of the piece's index in mesh: its global id. Empty where the piece is the
  /// whole mesh or is empty.
  std::vector<vtkIdType> pieceIds;
  /// Gathered on the first process only, there: every piece's pieceIds, in process order.
  std::vector<vtkIdType> everyPieceIds;
  /// Why the pieces do not make one mesh; the same text on every process.
  std::string problem;
};

/// Gathers the whole mesh from every process's piece (a collective call), on every process or
/// on the first only. Where one process has all the points and they have no global ids, its
/// piece is the whole mesh and only a few counts are exchanged. Several pieces with points need
/// global point and cell ids.
SHADELABFILTERS_EXPORT WholeMesh gatherWholeMesh(vtkMultiProcessController* controller, vtkPolyData* piece,
  bool withNormals, WholeMeshOn where = WholeMeshOn::EveryProcess);

/// A filter's work on a mesh taken whole: into result, at the points pieceIds lists (nullptr:
/// every point of a mesh no other process shares; an empty list for an empty piece of a split
/// mesh, whose process takes part in the work's exchanges); arrays it adds have a value per listed point, except
/// computed normals, which have one per point (on the first process alone, every array has one per point). Returns
/// whether it succeeded (having reported why not).
using PieceComputation =
  std::function<bool(vtkPolyData* mesh, vtkPolyData* result, const std::vector<vtkIdType>* pieceIds)>;

/// A filter's RequestData for a piece of a split mesh (a collective call): gathers the whole
/// mesh `where` and computes on it there, for the piece's points on every process, or for every
/// point on the first process, which then sends each piece its points' values. Gives output
/// the piece with what was computed. Returns 1, or 0 on every process where any failed (each
/// failure reported through `filter`), so that no process waits for a failed one in a later
/// collective call.
SHADELABFILTERS_EXPORT int computeOnPiece(vtkMultiProcessController* controller, vtkAlgorithm* filter,
  vtkPolyData* piece, vtkPolyData* output, bool withNormals, WholeMeshOn where, const PieceComputation& compute);

/// How many times gatherWholeMesh has put a whole mesh together on this process: a step that
/// leaves it unchanged held no more of the mesh than the pieces' exchanges brought it.
SHADELABFILTERS_EXPORT std::size_t wholeMeshesPutTogetherHere();

/// values' tuples at ids, in a new array of the same type and name.
SHADELABFILTERS_EXPORT vtkSmartPointer<vtkDataArray> tuplesAt(vtkDataArray* values, const std::vector<vtkIdType>& ids);

}

#endif
