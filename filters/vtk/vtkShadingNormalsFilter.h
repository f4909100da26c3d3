/**
 * @class vtkShadingNormalsFilter
 * @brief Point normals for shading: the mesh's own, or smooth ones computed from its
 * polygons, oriented out of the mesh.
 *
 * Without point normals in the input (or with KeepInputNormals off), computes area-weighted
 * point normals (PointNormals.h) without changing point ids or count, in one pass over the
 * polygons that also finds the points whose edges do not pair up (boundaries, seams,
 * inconsistent windings). Only those go further: points among them that share a position
 * (the same coordinates, or within WeldTolerance) share their normal unless their polygons
 * meet at an edge sharper than FeatureAngle, so a mesh split at texture seams shades smooth
 * and one split at its sharp edges keeps them; and only if polygons there are wound
 * inconsistently (a directed edge traversed twice) does vtkPolyDataNormals' consistency pass
 * reorder the polygons first. SplitSharpEdgesOn instead duplicates points at edges sharper
 * than SplitAngle (vtkPolyDataNormals' splitting): the point count changes, and point data is
 * copied to the new points.
 *
 * Normals that point into a closed or nearly closed mesh (shadelab::NormalOrientation) are
 * flipped unless OrientOutward is off; the input's own normals are then replaced by a flipped
 * copy. GetReport() says what was done, and so does the output's field data array
 * "shadelab_normals". Every other array passes through.
 *
 * A piece of a mesh split over processes (see SetController) gets the normals the whole mesh
 * has at its points, bit for bit. Each piece computes its own from its polygons and the vector
 * areas of the other pieces' polygons at the points they share (ShadeLabPieceNormals.h). Only a
 * mesh whose copies at one position must be welded, whose windings must be reordered, which
 * has strips, or which welds within a tolerance is gathered on the first process, which
 * computes its normals as one process would and sends each piece its points'
 * (ShadeLabWholeMesh.h).
 */
#ifndef vtkShadingNormalsFilter_h
#define vtkShadingNormalsFilter_h

#include "ShadeLabFiltersModule.h"
#include "vtkMultiProcessController.h" // the controller, a member
#include "vtkPolyDataAlgorithm.h"
#include "vtkSmartPointer.h"

#include <optional>
#include <string>

class SHADELABFILTERS_EXPORT vtkShadingNormalsFilter : public vtkPolyDataAlgorithm
{
public:
  static vtkShadingNormalsFilter* New();
  vtkTypeMacro(vtkShadingNormalsFilter, vtkPolyDataAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /// Use the input's point normals when it has them (default on).
  vtkSetMacro(KeepInputNormals, bool);
  vtkGetMacro(KeepInputNormals, bool);
  vtkBooleanMacro(KeepInputNormals, bool);

  /// Share normals between points at one position (default on).
  vtkSetMacro(WeldCoincidentPoints, bool);
  vtkGetMacro(WeldCoincidentPoints, bool);
  vtkBooleanMacro(WeldCoincidentPoints, bool);

  /// How close two points must be to count as one position, as a fraction of the bounding
  /// box's diagonal. Default 0: the same coordinates, which is how files that split a point
  /// store its copies (and the fastest); above 0 for files that round the copies differently.
  vtkSetClampMacro(WeldTolerance, double, 0.0, 0.1);
  vtkGetMacro(WeldTolerance, double);

  /// Points at one position whose polygons meet at an edge sharper than this many degrees
  /// keep their own normals (default 80). Higher than vtkPolyDataNormals' 30 because it only
  /// keeps apart points that the file has split already: a coarse smooth surface has edges
  /// sharper than 30 degrees that are no creases (spot.obj's sharpest is 77), while the hard
  /// edges that CAD and game exports split at are usually right angles.
  vtkSetClampMacro(FeatureAngle, double, 0.0, 180.0);
  vtkGetMacro(FeatureAngle, double);

  /// Duplicate points at edges sharper than SplitAngle, so each side gets its own normal
  /// (default off: it changes the point count). For meshes that store a sharp edge's points
  /// once, which no normal per point can shade sharp otherwise.
  vtkSetMacro(SplitSharpEdges, bool);
  vtkGetMacro(SplitSharpEdges, bool);
  vtkBooleanMacro(SplitSharpEdges, bool);

  /// The angle SplitSharpEdges splits at, in degrees (default 30, as vtkPolyDataNormals).
  vtkSetClampMacro(SplitAngle, double, 0.0, 180.0);
  vtkGetMacro(SplitAngle, double);

  /// Flip normals that point into a closed or nearly closed mesh (default on).
  vtkSetMacro(OrientOutward, bool);
  vtkGetMacro(OrientOutward, bool);
  vtkBooleanMacro(OrientOutward, bool);

  /// Check the cells' offsets and point ids before using them (default on). Off only where
  /// the caller has checked the same cells already, as vtkLocalReflectanceFilter does before
  /// it runs this filter: on a large mesh the check reads every id, a tenth of the time here.
  vtkSetMacro(CheckCells, bool);
  vtkGetMacro(CheckCells, bool);
  vtkBooleanMacro(CheckCells, bool);

  /// The name of computed normals (default "Normals").
  vtkSetMacro(NormalsName, std::string);
  vtkGetMacro(NormalsName, std::string);

  /// What the last run did, in one or a few sentences.
  const std::string& GetReport() const { return this->Report; }

  /// The processes over which the mesh may be split (default: the global controller, MPI's
  /// under pvbatch or mpirun; nullptr: this process alone). Where there are several, or the
  /// input's points have global ids, the input is taken as a piece of a mesh whose points are
  /// numbered by their global ids (ShadeLabWholeMesh.h).
  vtkSetSmartPointerMacro(Controller, vtkMultiProcessController);
  vtkGetSmartPointerMacro(Controller, vtkMultiProcessController);

protected:
  vtkShadingNormalsFilter();
  ~vtkShadingNormalsFilter() override = default;

  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  /// The normals of `input` taken as a whole mesh, in `output`. hadNormals: whether the mesh had
  /// normals of its own, where `input` was put together without them (default: whether it has).
  int ComputeNormals(vtkPolyData* input, vtkPolyData* output, std::optional<bool> hadNormals = {});
  /// What ComputeOnPieces returns where the mesh must be put together first.
  static constexpr int needsWholeMesh = -1;
  /// The normals of a piece of a split mesh computed piece by piece (ShadeLabPieceNormals.h), a
  /// collective call: 1 or 0 as RequestData, or needsWholeMesh on every process alike.
  int ComputeOnPieces(vtkPolyData* piece, vtkPolyData* output);

private:
  vtkShadingNormalsFilter(const vtkShadingNormalsFilter&) = delete;
  void operator=(const vtkShadingNormalsFilter&) = delete;

  bool KeepInputNormals = true;
  bool WeldCoincidentPoints = true;
  double WeldTolerance = 0.0;
  double FeatureAngle = 80.0;
  bool SplitSharpEdges = false;
  double SplitAngle = 30.0;
  bool OrientOutward = true;
  bool CheckCells = true;
  std::string NormalsName = "Normals";
  std::string Report;
  vtkSmartPointer<vtkMultiProcessController> Controller;
};

#endif
