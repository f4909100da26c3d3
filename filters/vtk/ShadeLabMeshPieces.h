#ifndef ShadeLabMeshPieces_h
#define ShadeLabMeshPieces_h
// The pieces of a mesh split over processes as the filters' steps see them, and the collective
// calls that keep the processes in step (a failure on one stops all alike) or reduce a value
// over every piece. Putting the pieces together is ShadeLabWholeMesh.h's.
#include "ShadeLabFiltersModule.h"

#include "MeshExtent.h"

#include "vtkType.h"

#include <cstddef>
#include <string>
#include <vector>

class vtkAlgorithm;
class vtkMultiProcessController;
class vtkPolyData;

namespace shadelab
{
/// How a process's piece lies in the whole mesh (a collective call's answer).
struct PieceLayout
{
  /// Why the pieces do not make one mesh; the same text on every process.
  std::string problem;
  /// Whether the pieces are put together into one mesh (the same on every process). Where they
  /// are not, one process holds the whole mesh (or none holds any), and it needs nobody else.
  bool putTogether = false;
  /// Each point of the piece's index in the whole mesh (its global id), where put together.
  std::vector<vtkIdType> pieceIds;
};

/// The first process's text that is not empty ("" where all are), on every process (a
/// collective call): the first problem, where any process has one, so that all stop with it.
SHADELABFILTERS_EXPORT std::string firstText(vtkMultiProcessController* controller, const std::string& text);

/// Whether `mine` holds on every process (a collective call).
SHADELABFILTERS_EXPORT bool everyProcessHolds(vtkMultiProcessController* controller, bool mine);

/// The error a process reports when it stops because another failed on its piece.
SHADELABFILTERS_EXPORT extern const char* const anotherProcessFailed;

/// Whether an error is one that a process reports because another failed (each such message of
/// the filters starts "another process"): a program that shows one process's error shows one
/// that is not.
SHADELABFILTERS_EXPORT bool saysAnotherProcessFailed(const std::string& error);

/// What a filter's RequestData returns for its piece (a collective call): 1 where every process
/// succeeded. Where another failed, this one stops too, with anotherProcessFailed as its error
/// and its output emptied, so that no process waits for a failed one in a later collective call.
SHADELABFILTERS_EXPORT int agreedOutcome(
  vtkMultiProcessController* controller, vtkAlgorithm* filter, vtkPolyData* output, bool succeeded);

/// The extent of the whole mesh's points, from every piece's box (a collective call): the same
/// bits as meshExtentOf on the whole mesh, since the smallest and largest coordinates are.
SHADELABFILTERS_EXPORT MeshExtent wholeMeshExtent(vtkMultiProcessController* controller, vtkPolyData* piece);

/// How many distinct ids the processes' lists hold together (a collective call): a count over
/// the whole mesh of points that several pieces may hold.
SHADELABFILTERS_EXPORT std::size_t distinctIdCount(
  vtkMultiProcessController* controller, const std::vector<vtkIdType>& ids);

/// The processes' values (one per id in their lists, which must be as long) with each id once,
/// in the order of the ids (a collective call): where several pieces hold a point, its value
/// once.
SHADELABFILTERS_EXPORT std::vector<double> valuesByDistinctId(
  vtkMultiProcessController* controller, const std::vector<vtkIdType>& ids, const std::vector<double>& values);

/// Every point's values of the whole mesh (`components` per point, `points` points, in the
/// order of their global ids) from each process's values at its ids, `components` per id (a
/// collective call): where several pieces hold a point, any one's, since they hold the same.
/// A point no piece holds keeps 0.
SHADELABFILTERS_EXPORT std::vector<double> valuesAtEveryPoint(vtkMultiProcessController* controller,
  const std::vector<vtkIdType>& ids, const std::vector<double>& values, int components, vtkIdType points);
/// For each of the piece's points, whether it is its id's first copy over the processes (in
/// process order, then in the piece's order) (a collective call): counting only first copies
/// counts each point of the whole mesh once, however many pieces hold it.
SHADELABFILTERS_EXPORT std::vector<bool> firstCopies(
  vtkMultiProcessController* controller, const std::vector<vtkIdType>& ids);

/// How many points the whole mesh has: its largest global id plus 1, over every piece's ids (a
/// collective call).
SHADELABFILTERS_EXPORT vtkIdType wholePointCount(
  vtkMultiProcessController* controller, const std::vector<vtkIdType>& pieceIds);

/// The pieces of a split mesh as a filter's steps take them: the processes that hold them and
/// how this process's piece lies in the whole mesh; both nullptr for a whole mesh. A step given
/// split pieces exchanges data with the other processes (a collective call).
struct MeshPieces
{
  vtkMultiProcessController* processes = nullptr;
  const PieceLayout* layout = nullptr;

  bool split() const { return layout != nullptr; }
  /// Each point of the piece's id in the whole mesh; nullptr for a whole mesh.
  const std::vector<vtkIdType>* pointIds() const { return layout ? &layout->pieceIds : nullptr; }
  /// Whether `mine` holds on every process (on a whole mesh, `mine`).
  bool holdEverywhere(bool mine) const { return split() ? everyProcessHolds(processes, mine) : mine; }
  /// Whether `mine` holds on some process (on a whole mesh, `mine`).
  bool holdAnywhere(bool mine) const { return !holdEverywhere(!mine); }
  /// The first process's text that is not empty (on a whole mesh, `text`).
  std::string firstProblem(const std::string& text) const { return split() ? firstText(processes, text) : text; }
};
}

#endif
