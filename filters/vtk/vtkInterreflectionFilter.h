/**
 * @class vtkInterreflectionFilter
 * @brief The light a mesh reflects onto itself: from each vertex's direct diffuse term, the
 * irradiance that reaches it after 1 .. Bounces diffuse reflections on the mesh's own surfaces.
 *
 * Each vertex gathers along Samples cosine-weighted rays about its point normal; a ray's value
 * is the radiosity (RadiosityArrayName, the direct diffuse term kd E, RGB) interpolated at its
 * first hit, and each further bounce gathers kd times what the last one gathered, on the same
 * hits (docs/formulas.md section 23). kd, the albedo, is Albedo or, per vertex, the RGB array
 * AlbedoArrayName (values in [0, 1]). Writes <ArrayPrefix>indirect_irradiance and its standard
 * error, and with KeepBounces each bounce's own irradiance, <ArrayPrefix>indirect_bounce_<n>;
 * float64 for a float64 radiosity, float32 otherwise. Transfer vectors named with
 * AddTransferArrayName are carried through the same bounces (interreflected transfer). Every
 * input array passes through. The results are the same bits on any number of threads.
 *
 * A two-sided surface (BackRadiosityArrayName set) sends light out from both sides: each vertex
 * also gathers about its reversed normal, a ray that meets a triangle's back reads the backs'
 * radiosity (and transfer, from <name>_back), and the backs' arrays are written too, named with
 * "_back" after the fronts'.
 *
 * vtkLocalReflectanceFilter runs it for a scene's "interreflection", and adds kd times the
 * indirect irradiance to its diffuse and total terms.
 */
#ifndef vtkInterreflectionFilter_h
#define vtkInterreflectionFilter_h

#include "ShadeLabFiltersModule.h"
#include "vtkMultiProcessController.h" // the controller, a member
#include "vtkPolyDataAlgorithm.h"
#include "vtkSmartPointer.h"

#include <string>
#include <vector>

class vtkDataArray;
class vtkDoubleArray;
namespace shadelab
{
struct IndirectIrradiance;
struct SplitVertices;
}

class SHADELABFILTERS_EXPORT vtkInterreflectionFilter : public vtkPolyDataAlgorithm
{
public:
  static vtkInterreflectionFilter* New();
  vtkTypeMacro(vtkInterreflectionFilter, vtkPolyDataAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /// The point array of the direct radiosity B0, RGB: the direct diffuse term (default
  /// "diffuse").
  vtkSetMacro(RadiosityArrayName, std::string);
  vtkGetMacro(RadiosityArrayName, std::string);

  /// The point array of the direct radiosity of each vertex's back, the side opposite its
  /// normal, RGB, for a surface shaded on both sides (default "": the backs send out nothing,
  /// and a ray that meets one carries nothing). Each transfer array to carry then has its
  /// backs' in <name>_back.
  vtkSetMacro(BackRadiosityArrayName, std::string);
  vtkGetMacro(BackRadiosityArrayName, std::string);

  /// The albedo kd of every vertex, RGB in [0, 1] (default 0.8 0.8 0.8), where AlbedoArrayName
  /// is empty.
  vtkSetVector3Macro(Albedo, double);
  vtkGetVector3Macro(Albedo, double);

  /// A point array of each vertex's albedo, RGB in [0, 1] (default "": Albedo everywhere).
  vtkSetMacro(AlbedoArrayName, std::string);
  vtkGetMacro(AlbedoArrayName, std::string);

  /// How many reflections the light makes (default 1; 0 writes zeros).
  vtkSetClampMacro(Bounces, int, 0, 64);
  vtkGetMacro(Bounces, int);

  /// Gather rays per vertex (default 64).
  vtkSetClampMacro(Samples, int, 2, 1 << 20);
  vtkGetMacro(Samples, int);

  /// Stratified gather rays (default on).
  vtkSetMacro(Stratified, bool);
  vtkGetMacro(Stratified, bool);
  vtkBooleanMacro(Stratified, bool);

  /// With a value above 0, the fewest bounces, at most Bounces, after which what the rest can add
  /// to a diffuse term is within it (docs/formulas.md section 23.5; the albedo must be below 1).
  /// Default 0: Bounces bounces.
  vtkSetClampMacro(BounceTolerance, double, 0, VTK_DOUBLE_MAX);
  vtkGetMacro(BounceTolerance, double);

  /// Also each bounce's own irradiance (default off).
  vtkSetMacro(KeepBounces, bool);
  vtkGetMacro(KeepBounces, bool);
  vtkBooleanMacro(KeepBounces, bool);

  /// A point array of transfer vectors ("estimator": "prt": 9, 16 or 25 spherical-harmonic
  /// coefficients) to carry through the same bounces (Sloan, Kautz and Snyder 2002, section 5:
  /// interreflected transfer). For each, it writes <ArrayPrefix><name>_indirect, 3 times as many
  /// components, what the bounces add to the vector per channel (component 3 k + c: coefficient
  /// k, channel c; float64 for a float64 transfer, float32 otherwise): its dot product with a
  /// map's coefficients, channel by channel, is the indirect irradiance under that map. With
  /// BackRadiosityArrayName, the backs' vectors are <name>_back, as many coefficients, and the
  /// backs' result <name>_indirect_back. Default none.
  void AddTransferArrayName(const std::string& name);
  void RemoveAllTransferArrayNames();
  int GetNumberOfTransferArrayNames() const { return static_cast<int>(this->TransferArrayNames.size()); }

  /// Prepended to the names of the arrays it writes (default "").
  vtkSetMacro(ArrayPrefix, std::string);
  vtkGetMacro(ArrayPrefix, std::string);

  /// The processes a split mesh's pieces are on (default: the global controller). A piece of a
  /// mesh split over them (its points and cells with global ids, as for the other filters)
  /// gathers at its own points against the whole mesh's triangles, and the processes share
  /// each bounce's values: every piece gets its points' values of the whole mesh, bit for bit.
  vtkSetSmartPointerMacro(Controller, vtkMultiProcessController);
  vtkGetSmartPointerMacro(Controller, vtkMultiProcessController);

  /// Threads for the rays and the sweeps (default 0: as vtkSMPTools is set).
  vtkSetClampMacro(NumberOfThreads, int, 0, VTK_INT_MAX);
  vtkGetMacro(NumberOfThreads, int);

  /// What the last run did: the rays, how many met a triangle's back, the bounces.
  const std::string& GetReport() const { return this->Report; }
  /// Of the last run's gather rays, how many met the back of a triangle (and carried nothing,
  /// or with BackRadiosityArrayName the backs' radiosity).
  long long GetBackHits() const { return this->BackHits; }
  /// The last run's bounces, and the most that the bounces past them add to a diffuse term
  /// (infinite where the albedo reaches 1).
  int GetBounceCount() const { return this->BounceCount; }
  double GetRestBound() const { return this->RestBound; }

protected:
  vtkInterreflectionFilter();
  ~vtkInterreflectionFilter() override = default;

  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

private:
  vtkInterreflectionFilter(const vtkInterreflectionFilter&) = delete;
  void operator=(const vtkInterreflectionFilter&) = delete;

  /// The input gathered at, whole or as a piece of a split mesh.
  int InterreflectPiece(vtkPolyData* input, vtkPolyData* output);
  /// On the whole mesh gathered from the pieces: the piece's arrays made whole, its points
  /// gathered at, and their values (at pieceIds) into result.
  int InterreflectWhole(
    vtkPolyData* whole, vtkPolyData* result, const std::vector<vtkIdType>& pieceIds, vtkPolyData* givenPiece);
  /// Onto an empty piece, empty arrays for those it lacks, of the sizes the other processes'
  /// have (a collective call where transfers are carried).
  void AddArraysAnEmptyPieceLacks(vtkPolyData* piece);
  /// The mesh gathered at, every point or split's own.
  int Interreflect(vtkPolyData* input, vtkPolyData* output, const shadelab::SplitVertices* split);
  /// The input's array of that name if it is numeric with 3 components; nullptr after
  /// reporting why not.
  vtkDataArray* RgbArray(vtkPolyData* input, const std::string& name, const char* role);
  /// Checks the albedo, and sets perVertex to the albedo array's values in float64 (nullptr
  /// where the uniform Albedo is every vertex's); false after reporting what is wrong.
  bool AlbedoOf(vtkPolyData* input, vtkSmartPointer<vtkDoubleArray>& perVertex);
  /// The transfer arrays TransferArrayNames names, each with `suffix` (the backs': "_back"), into
  /// `arrays`; false after reporting the first that is missing or has a count of components no
  /// order has.
  bool TransferArrays(vtkPolyData* input, std::vector<vtkDataArray*>& arrays, const std::string& suffix = "");
  /// Traces every vertex's gather rays (on both sides where backRadiosity is not null), then
  /// bounces the light and the transfer vectors (the fronts', then the backs'; the core's
  /// BounceGather).
  shadelab::IndirectIrradiance GatherBounces(vtkPolyData* input, vtkDataArray* normals, vtkDataArray* radiosity,
    vtkDataArray* backRadiosity, vtkDoubleArray* albedo, const std::vector<vtkDataArray*>& transfers,
    const std::vector<vtkDataArray*>& backTransfers, const shadelab::SplitVertices* split);
  /// Where BackRadiosityArrayName names one, the back radiosity's array and the backs' transfer
  /// arrays, each as many coefficients as its front in `transfers`; false after reporting why
  /// they cannot be used.
  bool BackArrays(vtkPolyData* input, const std::vector<vtkDataArray*>& transfers, vtkDataArray*& backRadiosity,
    std::vector<vtkDataArray*>& backTransfers);
  void AddIndirectArrays(vtkPolyData* output, const shadelab::IndirectIrradiance& indirect, bool float64,
    const std::vector<vtkDataArray*>& transfers);
  /// The run's report: its bounces, rays, the rays that met a triangle's back, the bound on the
  /// bounces left out, and the transfers carried.
  std::string ReportOf(const std::vector<vtkDataArray*>& transfers) const;

  std::string RadiosityArrayName = "diffuse";
  std::string BackRadiosityArrayName;
  double Albedo[3] = { 0.8, 0.8, 0.8 };
  std::string AlbedoArrayName;
  int Bounces = 1;
  double BounceTolerance = 0;
  int Samples = 64;
  bool Stratified = true;
  bool KeepBounces = false;
  std::vector<std::string> TransferArrayNames;
  std::string ArrayPrefix;
  int NumberOfThreads = 0;
  vtkSmartPointer<vtkMultiProcessController> Controller;
  std::string Report;
  long long BackHits = 0;
  long long GatherRays = 0; // the last run's, every process's
  int LaterRays = 0;
  int BounceCount = 0;
  double RestBound = 0;
};

#endif
