#pragma once
// A glTF 2.0 file (.gltf, .glb) read by VTK's vtkGLTFImporter: its meshes as one mesh whose
// points know their part and carry its material (ShadeLabImportedParts.h), and its
// KHR_lights_punctual lights as a ShadeLab scene, kept in the mesh's field data.
#include "vtkPolyData.h"
#include "vtkSmartPointer.h"

#include <cstdint>
#include <string>
#include <vector>

namespace shadelab::app
{
/// The field-data array that holds a scene file's lights as the JSON text of a ShadeLab scene
/// ({"lights": [...]}), for a run without --scene to shade with.
constexpr const char* fileLightsArrayName = "file_lights";

/// The glTF file's parts, each with its material (docs/formulas.md section 7.3) and base colour
/// texture, as one mesh; its lights as fileLightsArrayName where it has any. What was skipped
/// is added to `notes`. Throws UserError where the importer fails or the file has no geometry.
vtkSmartPointer<vtkPolyData> importGltfScene(const std::string& fileName, std::vector<std::string>& notes);

/// Whether the file is glTF, by its extension (.gltf, .glb in any case).
bool isGltfFile(const std::string& fileName);

/// VTK's importer alone on the file, in this process, its scene then dropped: what reading it
/// costs without ShadeLab's parts, materials, lights and process (the benchmark's floor).
void importGltfAlone(const std::string& fileName);

/// The bytes the file and the buffers and images it names beside it hold: what its reading is
/// bounded by, for a .gltf whose data lie in files of their own.
std::uintmax_t gltfBytes(const std::string& fileName);

/// The scene text that importGltfScene kept in the mesh, or "" where it has none.
std::string fileLightsOf(vtkPolyData* mesh);
}
