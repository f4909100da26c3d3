/**
 * A material from the mesh's own arrays (shadelab::MaterialArrays): each vertex's ka, kd, ks or
 * shininess read from point data, fields mapped through VTK's own colour maps as its mapper and
 * ParaView draw them, and decoded to linear coefficients (docs/formulas.md section 7.1).
 */
#ifndef ShadeLabMaterialArrays_h
#define ShadeLabMaterialArrays_h

#include "ShadeLabFiltersModule.h"
#include "vtkScalarsToColors.h" // namedColorMap returns one
#include "vtkSmartPointer.h"
#include "vtkType.h"

#include "Scene.h"

#include <array>
#include <string>
#include <vector>

class vtkMultiProcessController;
class vtkPolyData;

namespace shadelab
{
/// The vertices' coefficients, or why they cannot be read.
struct MaterialReading
{
  VertexMaterial material;
  std::string problem; // "" where every coefficient was read
};

/// Reads the scene's material arrays from the piece's point data: each vertex's coefficients in
/// the storage precision (VertexMaterial's values, or floatValues for float32), or the first
/// problem (a missing array, one of another length or type, a wrong number of components, a
/// value that cannot be used, naming the vertex by its id in vertexIds where given). A colour
/// map without a range spans the array's finite values over every process (a collective call
/// where processes has several; nullptr: this process alone).
SHADELABFILTERS_EXPORT MaterialReading readVertexMaterial(vtkPolyData* piece, const Scene& scene, Precision storage,
  vtkMultiProcessController* processes, const std::vector<vtkIdType>* vertexIds);

/// The colour map of colorMapNames() called name, as VTK builds it, its ends at range.
SHADELABFILTERS_EXPORT vtkSmartPointer<vtkScalarsToColors> namedColorMap(
  const std::string& name, const std::array<double, 2>& range);

/// The scene with its diffuse colour from the array `name`, and its ambient colour too (the
/// lecture model's ka follows kd; VTK's mapper colours both): the array's own colours (3 or 4
/// components), or a 1-component field through the colour map `colorMap`. In the vtk model the
/// scene's kd and ka, as greys (their largest components), scale the colour, as a vtkProperty's
/// Diffuse and Ambient do. ParaView's panel and Python's property choose the array this way.
SHADELABFILTERS_EXPORT void colorMaterialBy(Scene& scene, const std::string& name, const std::string& colorMap);

/// The name of the array that marks, per vertex, which coefficients were clamped (bit c for
/// MaterialCoefficient c), written where a coefficient asks to clamp.
SHADELABFILTERS_EXPORT std::string materialClampedArrayName(const std::string& prefix);
}

#endif
