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

#include <optional>
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
/// And where the file's materials are glTF's metallic-roughness ones, as VTK's PBR shader reads
/// them (the vtk_pbr model): the base colour (linear RGB, its texture's colour included), the
/// metallic factor and the roughness.
constexpr const char* materialBaseColorArrayName = "material_base_color";
constexpr const char* materialMetallicArrayName = "material_metallic";
constexpr const char* materialRoughnessArrayName = "material_roughness";
/// The field-data array of the parts' names, indexed by the part array's values.
constexpr const char* partNamesArrayName = "part_names";
/// The field-data array that says, part by part as partNamesArrayName, which parts are shaded on
/// both sides (1) and which on the side of their normals (0).
constexpr const char* partTwoSidedArrayName = "part_two_sided";

/// A part's coefficients in the lecture model, linear, its sides, and where the file gives one,
/// its metallic-roughness material as VTK's PBR property holds it.
struct PartMaterial
{
  Rgb ka{ 0.0 }, kd{ 0.0 }, ks{ 0.0 };
  double shininess = 0;
  std::optional<MicrofacetMaterial> microfacet;
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
  /// glTF's metallic-roughness texture, as VTK's importer gives it (its ORM texture, roughness in
  /// green and metallic in blue), which multiplies the microfacet material's factors.
  vtkTexture* metallicRoughnessTexture = nullptr;
};

/// The parts' polygons, lines and vertices as one mesh (the parts with none are left out), with
/// each point's part, the parts' materials per point (kd, and the base colour where every part
/// has a metallic-roughness material, times the texture's colour averaged over the texels the
/// point stands for, sRGB-decoded where the texture is 8- or 16-bit), their
/// sides per part, their normals where every part has them, and their texture coordinates. What
/// could not be used is added to `skipped`, one line each.
SHADELABFILTERS_EXPORT vtkSmartPointer<vtkPolyData> meshOfParts(
  const std::vector<ImportedPart>& parts, std::vector<std::string>& skipped);

/// Whether a mesh carries the arrays of its own materials (meshOfParts').
SHADELABFILTERS_EXPORT bool hasOwnMaterials(vtkPolyData* mesh);

/// Whether a mesh carries the arrays of its own metallic-roughness materials as well.
SHADELABFILTERS_EXPORT bool hasOwnMicrofacetMaterials(vtkPolyData* mesh);

/// Whether the mesh is shaded with its own materials: the scene gives no material (nor does a
/// colouring by an array, colorByArray), and the mesh has the arrays of the scene's model: the
/// lecture's coefficients, or for the vtk_pbr model the metallic-roughness ones.
SHADELABFILTERS_EXPORT bool shadesWithOwnMaterials(const Scene& scene, vtkPolyData* mesh, bool colorByArray);

/// Whether every part of the mesh is shaded on both sides (partTwoSidedArrayName; false for a
/// mesh without it).
SHADELABFILTERS_EXPORT bool everyPartTwoSided(vtkPolyData* mesh);

/// The scene's material made to read those arrays. In the lecture model the MTL's Ka, Kd, Ks
/// and Ns are the lecture's ka, kd, ks and shininess; the specular model stays the scene's; the
/// surface is two-sided where every part of the mesh is (glTF's doubleSided), since a mesh is
/// shaded on one side or on both, not part by part. In the vtk_pbr model the base colour,
/// metallic factor and roughness are read, VTK's PBR property's base IOR and edge tint kept.
SHADELABFILTERS_EXPORT Material ownMaterial(const Scene& scene, vtkPolyData* mesh);
}

#endif
