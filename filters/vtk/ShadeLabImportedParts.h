/**
 * A scene file's parts as one mesh (docs/guide/scene-files.md, "Meshes with their own
 * materials"): the actors that one of VTK's importers (vtkOBJImporter, vtkGLTFImporter) made of
 * the file, their polygons in one polydata whose points know their part and carry their part's material as
 * point arrays, which the scene's material then reads (shadelab::MaterialArrays).
 */
#ifndef ShadeLabImportedParts_h
#define ShadeLabImportedParts_h

#include "ShadeLabFiltersModule.h"
#include "vtkSmartPointer.h"

#include "Scene.h"

#include <string>
#include <vector>

class vtkActor;
class vtkPolyData;
class vtkRenderer;
class vtkTexture;

namespace shadelab
{
/// The point arrays of a mesh's own materials: the part's index, and its coefficients, linear,
/// as floats (RGB, and 1 component for the shininess, the MTL file's Ns).
constexpr const char* partArrayName = "part";
constexpr const char* materialKaArrayName = "material_ka";
constexpr const char* materialKdArrayName = "material_kd";
constexpr const char* materialKsArrayName = "material_ks";
constexpr const char* materialShininessArrayName = "material_shininess";
/// The field-data array of the parts' names, indexed by the part array's values.
constexpr const char* partNamesArrayName = "part_names";
/// The field-data array that says, part by part as partNamesArrayName, which parts are shaded on
/// both sides (1) and which on the side of their normals (0).
constexpr const char* partTwoSidedArrayName = "part_two_sided";

/// A part's coefficients in the lecture model, linear, and its sides.
struct PartMaterial
{
  Rgb ka{ 0.0 }, kd{ 0.0 }, ks{ 0.0 };
  double shininess = 0;
  /// glTF's doubleSided (an MTL file has no such statement: one-sided).
  bool twoSided = false;
};

/// One part as an importer made it: its actor (its mapper's polydata, placed by the actor's
/// matrix), a name for it, its material, and the texture that multiplies its kd: kdTexture, or
/// where that is null and textureFile names one, a texture that could not be read.
struct ImportedPart
{
  vtkActor* actor;
  std::string name;
  PartMaterial material;
  vtkTexture* kdTexture = nullptr;
  std::string textureFile;
};

/// The parts' polygons, lines and vertices as one mesh (the parts with none are left out), with
/// each point's part, the parts' materials per point (kd times the texture's colour averaged
/// over the texels the point stands for, sRGB-decoded where the texture is 8- or 16-bit), their
/// sides per part, their normals where every part has them, and their texture coordinates. What
/// could not be used is added to `skipped`, one line each.
SHADELABFILTERS_EXPORT vtkSmartPointer<vtkPolyData> meshOfParts(
  const std::vector<ImportedPart>& parts, std::vector<std::string>& skipped);

/// Whether a mesh carries the arrays of its own materials (meshOfParts').
SHADELABFILTERS_EXPORT bool hasOwnMaterials(vtkPolyData* mesh);

/// Whether the mesh is shaded with its own materials: it has their arrays, and the scene, in the
/// lecture model, gives no material (nor does a colouring by an array, colorByArray).
SHADELABFILTERS_EXPORT bool shadesWithOwnMaterials(const Scene& scene, vtkPolyData* mesh, bool colorByArray);

/// Whether every part of the mesh is shaded on both sides (partTwoSidedArrayName; false for a
/// mesh without it).
SHADELABFILTERS_EXPORT bool everyPartTwoSided(vtkPolyData* mesh);

/// The scene's material made to read those arrays: the MTL's Ka, Kd, Ks and Ns are the lecture's
/// ka, kd, ks and shininess. The specular model stays the scene's; the surface is two-sided
/// where every part of the mesh is (glTF's doubleSided), since a mesh is shaded on one side or
/// on both, not part by part.
SHADELABFILTERS_EXPORT Material ownMaterial(const Material& scenes, vtkPolyData* mesh);
}

#endif
