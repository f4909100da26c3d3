#ifndef ShadeLabPieceNormals_h
#define ShadeLabPieceNormals_h
// Point normals of a mesh split over processes, computed piece by piece, bit for bit as one
// process computes them on the whole mesh (vtkShadingNormalsFilter), with no process holding
// the whole mesh: each holds its piece, about its share of the point ids (sent to their owners)
// while the pieces find the points they share, and every piece's points whose edges do not pair
// up.
//
// One process sums each point's polygons' vector areas in the polygons' order (PointNormals.h).
// A piece sums its own polygons (ghost cells left out) in the order of their global ids; a point
// that other pieces hold too gets the vector area of each of their polygons at it, exchanged
// with each of those pieces alone, and sums them all again from zero in the polygons' order. The
// edge balance and the winding's closure and flux are exact sums, which add up across pieces.
// What only the whole mesh can settle is left to it (ShadeLabWholeMesh.h): copies of a point at
// one position (seams) to weld, windings to reorder, strips, a weld tolerance. The pieces find
// the first two from the points whose edges do not pair up, which every process gathers: a
// mesh's boundaries, usually a small part of it.
#include "NormalOrientation.h"
#include "ShadeLabMeshPieces.h"

#include "vtkFloatArray.h"
#include "vtkSmartPointer.h"

#include <algorithm>
#include <string>
#include <utility>
#include <vector>

class vtkDataArray;
class vtkMultiProcessController;
class vtkPolyData;

namespace shadelab
{
/// Which of a piece's points the other processes' pieces hold too, and which it holds twice (as
/// pieces appended in one process do).
struct SharedPoints
{
  /// (global id, point in the piece), by global id.
  std::vector<std::pair<vtkIdType, vtkIdType>> byGlobalId;
  /// For each process, the global ids its piece shares with this one, ascending (none for this one).
  std::vector<std::vector<vtkIdType>> withProcess;
  /// The global ids that several of the piece's points have, ascending.
  std::vector<vtkIdType> repeated;

  /// The first of byGlobalId's entries with this global id, or its end where the piece has none.
  std::vector<std::pair<vtkIdType, vtkIdType>>::const_iterator firstWith(vtkIdType globalId) const
  {
    const auto at = std::lower_bound(byGlobalId.begin(), byGlobalId.end(), std::make_pair(globalId, vtkIdType(0)));
    return at != byGlobalId.end() && at->first == globalId ? at : byGlobalId.end();
  }
};

/// The piece's shared points (a collective call): each process sends each of its global ids to
/// the id's owner (ownerOf), which answers each holder with the other processes that hold it,
/// so that a process receives about its share of the ids on any number of processes.
SHADELABFILTERS_EXPORT SharedPoints sharedPointsOf(
  vtkMultiProcessController* controller, const std::vector<vtkIdType>& globalIds);

/// Why the pieces give a point they share different `values` (its position, or its normal:
/// `what` names them, plural), as the whole mesh's gathering says it; "" where every copy has
/// the same bits. The first process's finding, on every process (a collective call). values may
/// be nullptr on an empty piece.
SHADELABFILTERS_EXPORT std::string differingSharedValues(
  vtkMultiProcessController* controller, const SharedPoints& shared, vtkDataArray* values, const std::string& what);

/// What computePieceNormals found.
struct PieceNormals
{
  /// Whether the normals were computed here (the same on every process); where not, the mesh
  /// needs to be put together.
  bool computed = false;
  /// One per point of the piece, turned outward where turnedOutward says so.
  vtkSmartPointer<vtkFloatArray> normals;
  /// Of the whole mesh's winding, which the normals follow (the same on every process).
  NormalOrientation orientation;
  bool turnedOutward = false;
};

/// The area-weighted normals of the piece's points as one process computes them on the whole
/// mesh (a collective call, on pieces without strips put together by `layout`, whose shared
/// points are `shared`), where the mesh needs no welding (`weld`: copies at one position would
/// be welded) and no reordering. Turned outward where orientOutward and the winding points in.
/// Throws on every process where one fails (the others with anotherProcessFailed).
SHADELABFILTERS_EXPORT PieceNormals computePieceNormals(vtkMultiProcessController* controller, vtkPolyData* piece,
  const PieceLayout& layout, const SharedPoints& shared, bool weld, bool orientOutward);

/// Whether the stored normals point out of the mesh, from the triangles of its polygons (their
/// fans) with the normals at their corners (NormalOrientationAccumulator). On a piece of a mesh
/// split over `piecesOver`'s processes (nullptr: a whole mesh), from its own polygons (not ghost
/// cells), with every piece's sums added: the whole mesh's answer on each process (a collective
/// call).
SHADELABFILTERS_EXPORT NormalOrientation storedNormalsOrientation(
  vtkPolyData* mesh, vtkDataArray* normals, vtkMultiProcessController* piecesOver = nullptr);
}

#endif
