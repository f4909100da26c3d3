/**
 * @class vtkTransferRelightFilter
 * @brief The irradiance under an environment map from each vertex's stored transfer vector
 * (precomputed radiance transfer), without tracing a ray: lights a mesh that
 * vtkLocalReflectanceFilter shaded with "estimator": "prt" under any other map, turned any way.
 *
 * The map is projected on the spherical harmonics of the transfer's order (9, 16 or 25
 * coefficients: orders 2, 3, 4), scaled by Color x Intensity, turned by Rotation about +y as a
 * scene's "rotation" turns it, and dotted with every vertex's transfer vector
 * (docs/formulas.md section 12.10). The result is an RGB point array named OutputArrayName,
 * float64 for a float64 transfer and float32 otherwise; every other input array passes through.
 *
 * A mesh shaded with interreflection also holds the transfer's indirect part per channel,
 * <transfer>_indirect (vtkInterreflectionFilter): with UseIndirectTransfer, the result includes
 * the light the mesh reflects onto itself under the new map, and <OutputArrayName>_indirect
 * holds that part alone.
 */
#ifndef vtkTransferRelightFilter_h
#define vtkTransferRelightFilter_h

#include "ShadeLabFiltersModule.h"
#include "vtkPolyDataAlgorithm.h"

#include <string>

class vtkDataArray;

class SHADELABFILTERS_EXPORT vtkTransferRelightFilter : public vtkPolyDataAlgorithm
{
public:
  static vtkTransferRelightFilter* New();
  vtkTypeMacro(vtkTransferRelightFilter, vtkPolyDataAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /// The equirectangular map (.hdr, .exr) to light the mesh with.
  vtkSetMacro(EnvironmentMapFileName, std::string);
  vtkGetMacro(EnvironmentMapFileName, std::string);

  /// Turns the map about +y by this many degrees, anticlockwise seen from above (default 0).
  vtkSetMacro(Rotation, double);
  vtkGetMacro(Rotation, double);

  /// Multiplies the map's radiance (default 1).
  vtkSetClampMacro(Intensity, double, 0.0, VTK_DOUBLE_MAX);
  vtkGetMacro(Intensity, double);

  /// The map's colour, RGB (default 1 1 1).
  vtkSetVector3Macro(Color, double);
  vtkGetVector3Macro(Color, double);

  /// The point array of transfer vectors (default "": the one array whose name ends in
  /// "_sh_transfer").
  vtkSetMacro(TransferArrayName, std::string);
  vtkGetMacro(TransferArrayName, std::string);

  /// Where the input has the transfer's indirect part (<transfer>_indirect), add the
  /// interreflection it carries (default on).
  vtkSetMacro(UseIndirectTransfer, bool);
  vtkGetMacro(UseIndirectTransfer, bool);
  vtkBooleanMacro(UseIndirectTransfer, bool);

  /// The name of the irradiance it writes (default "relit_irradiance"); an input array of that
  /// name is replaced (the report says so), but not the transfer array.
  vtkSetMacro(OutputArrayName, std::string);
  vtkGetMacro(OutputArrayName, std::string);

  /// What the last run did: which transfer array, of what order, under which map.
  const std::string& GetReport() const { return this->Report; }

protected:
  vtkTransferRelightFilter() = default;
  ~vtkTransferRelightFilter() override = default;

  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

private:
  vtkTransferRelightFilter(const vtkTransferRelightFilter&) = delete;
  void operator=(const vtkTransferRelightFilter&) = delete;

  /// The input's transfer array as TransferArrayName names it or, without a name, the one whose
  /// name ends in "_sh_transfer"; nullptr after reporting the error.
  vtkDataArray* FindTransfer(vtkPolyData* input);
  /// The transfer's indirect part, <transfer>_indirect, where UseIndirectTransfer asks for it and
  /// the input has it; false after reporting one of another size than 3 x the transfer's.
  bool FindIndirectTransfer(vtkPolyData* input, vtkDataArray* transfer, vtkDataArray*& indirect);

  std::string EnvironmentMapFileName;
  double Rotation = 0.0;
  double Intensity = 1.0;
  double Color[3] = { 1.0, 1.0, 1.0 };
  std::string TransferArrayName;
  bool UseIndirectTransfer = true;
  std::string OutputArrayName = "relit_irradiance";
  std::string Report;
};

#endif
