#pragma once
// An OBJ file with its MTL file, read by VTK's vtkOBJImporter as parts with materials and made
// one mesh (ShadeLabImportedParts.h). An OBJ without a material library is a mesh alone, read
// by vtkOBJReader as any other (MeshFiles.h).
#include "vtkPolyData.h"
#include "vtkSmartPointer.h"

#include <string>
#include <vector>

namespace shadelab::app
{
/// What the import needs to know of an OBJ file before it reads it.
struct ObjStatements
{
  /// The material library it names (its first "mtllib" statement), as a path beside the OBJ
  /// file; "" when it names none.
  std::string library;
  /// Its faces ("f" statements), which the importer's polygons are counted against.
  long long faces = 0;
};

/// The OBJ file's statements that say how to import it. More than one library is noted in
/// `notes` (lines for a warning about the file): vtkOBJImporter reads one.
ObjStatements objStatementsOf(const std::string& objFileName, std::vector<std::string>& notes);

/// The OBJ file's parts, each with its material from `library` and its textures from the
/// library's folder, as one mesh with a part array and the materials' arrays. What was skipped
/// (a texture missing or unusable) is added to `notes`. Throws UserError where
/// the importer fails. VTK 9.1's importer leaves out the faces without texture coordinates of a
/// file that has some: where it read fewer faces than `statements` counts, the mesh is null and
/// the reason is in `notes`.
vtkSmartPointer<vtkPolyData> importObjScene(
  const std::string& objFileName, const ObjStatements& statements, std::vector<std::string>& notes);
}
