#include "ObjScene.h"

#include "IsolatedWork.h"
#include "MeshFiles.h"
#include "VtkErrorCapture.h"

#include "ShadeLabImportedParts.h"

#include "vtkActor.h"
#include "vtkActorCollection.h"
#include "vtkOBJImporter.h"
#include "vtkProperty.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"
#include "vtkRendererCollection.h"
#include "vtkTexture.h"

#include <cctype>
#include <filesystem>
#include <fstream>
#include <regex>

namespace fs = std::filesystem;

namespace shadelab::app
{
namespace
{
/// The statement's argument: the rest of the line without the spaces around it.
std::string argumentOf(const std::string& line, std::size_t keywordLength)
{
  const std::size_t first = line.find_first_not_of(" \t", keywordLength);
  const std::size_t last = line.find_last_not_of(" \t\r");
  return first == std::string::npos ? "" : line.substr(first, last - first + 1);
}

/// The folder a file is in: "." for a name without one.
std::string folderOf(const std::string& fileName)
{
  const fs::path folder = fs::path(fileName).parent_path();
  return folder.empty() ? "." : folder.string();
}

/// A field of vtkOBJImporter 9.1's description of output `index` ("data output 1 with material
/// named red texture file checker.png diffuse color ..."), which is how it tells an actor's
/// material and texture file; "" where the description has no such field.
std::string describedField(vtkOBJImporter* importer, int index, const char* field)
{
  static const std::regex name(" ([^ ]+)");
  const std::string description = importer->GetOutputDescription(index);
  const std::size_t at = description.find(field);
  std::smatch match;
  const std::string rest = at == std::string::npos ? "" : description.substr(at + std::string(field).size());
  return std::regex_search(rest, match, name) && match.position(0) == 0 ? match[1].str() : "";
}
}

ObjStatements objStatementsOf(const std::string& objFileName, std::vector<std::string>& notes)
{
  std::ifstream file(objFileName);
  std::string line, library;
  ObjStatements statements;
  int libraries = 0;
  auto isStatement = [&](const char* keyword, std::size_t length) {
    return line.compare(0, length, keyword) == 0 && line.size() > length && std::isspace((unsigned char)line[length]);
  };
  while (std::getline(file, line))
  {
    statements.faces += isStatement("f", 1);
    if (isStatement("mtllib", 6) && libraries++ == 0)
    {
      library = argumentOf(line, 6);
    }
  }
  if (libraries > 1)
  {
    notes.push_back("names " + std::to_string(libraries) +
      " material libraries; VTK's importer reads one, the first (" + library + ")");
  }
  statements.library = library.empty() ? "" : (fs::path(folderOf(objFileName)) / library).string();
  return statements;
}

vtkSmartPointer<vtkPolyData> importObjScene(
  const std::string& objFileName, const ObjStatements& statements, std::vector<std::string>& notes)
{
  const std::string& library = statements.library;
  vtkNew<vtkOBJImporter> importer;
  importer->SetFileName(objFileName.c_str());
  importer->SetFileNameMTL(library.c_str());
  importer->SetTexturePath(folderOf(library).c_str());
  // The importer adds its actors to a renderer of this window; nothing is drawn.
  vtkNew<vtkRenderWindow> window;
  importer->SetRenderWindow(window);
  vtkNew<VtkErrorCapture> errors;
  errors->watch(importer);
  importer->Update();
  if (errors->failed())
  {
    throw UserError(
      objFileName + ": VTK's OBJ importer could not read it with " + library + ": " + printableText(errors->message()));
  }
  vtkActorCollection* actors = window->GetRenderers()->GetFirstRenderer()->GetActors();
  std::vector<ImportedPart> parts;
  actors->InitTraversal();
  for (int i = 0; i < actors->GetNumberOfItems(); ++i)
  {
    const std::string texture = describedField(importer, i, "texture file");
    const fs::path texturePath = fs::absolute(fs::path(folderOf(library)) / texture).lexically_normal();
    vtkActor* actor = actors->GetNextActor();
    vtkProperty* property = actor->GetProperty();
    PartMaterial material;
    material.ka = Rgb(property->GetAmbientColor()[0], property->GetAmbientColor()[1], property->GetAmbientColor()[2]);
    material.kd = Rgb(property->GetDiffuseColor()[0], property->GetDiffuseColor()[1], property->GetDiffuseColor()[2]);
    material.ks =
      Rgb(property->GetSpecularColor()[0], property->GetSpecularColor()[1], property->GetSpecularColor()[2]);
    // vtkOBJImporter 9.1 sets the specular power to the MTL's Ns / 4; times 4 it is Ns exactly.
    material.shininess = 4 * property->GetSpecularPower();
    parts.push_back({ actor, describedField(importer, i, "material named"), material, actor->GetTexture(),
      texture == "none" || texture.empty() ? "" : texturePath.string() });
  }
  std::vector<std::string> skipped; // noted once the parts are known to be whole
  vtkSmartPointer<vtkPolyData> mesh = meshOfParts(parts, skipped);
  if (mesh->GetNumberOfPolys() < statements.faces)
  {
    notes.push_back("VTK's OBJ importer read " + std::to_string(mesh->GetNumberOfPolys()) + " of its " +
      std::to_string(statements.faces) +
      " faces (it leaves out faces without texture coordinates where others have them): read as one mesh "
      "without its materials");
    return nullptr;
  }
  notes.insert(notes.end(), skipped.begin(), skipped.end());
  return mesh;
}
}
