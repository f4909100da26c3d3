#include "ObjScene.h"

#include "IsolatedWork.h"
#include "MeshFiles.h"
#include "MeshText.h"
#include "VtkErrorCapture.h"

#include "ShadeLabImportedParts.h"

#include "vtkActor.h"
#include "vtkActorCollection.h"
#include "vtkMapper.h"
#include "vtkOBJImporter.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"
#include "vtkRendererCollection.h"
#include "vtkTexture.h"

#include <cctype>
#include <filesystem>
#include <fstream>
#include <map>
#include <optional>
#include <regex>
#include <sstream>

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

/// A material as its MTL file states it: each coefficient where a statement gives it.
struct MtlMaterial
{
  std::optional<Rgb> ka, kd, ks;
  std::optional<double> ns;
  long long illum = 2;
};

/// The MTL file's materials by name (newmtl). vtkOBJImporter 9.1 reads the same file, but keeps
/// Ns only under illum 2 (as Ns / 4) and puts Kd in Ka and Ks under illum 0: the numbers are
/// read here. A Ka, Kd, Ks, Ns or illum whose numbers cannot be read (or that gives a spectral
/// or CIE XYZ colour) is noted in `notes` and left to its default.
std::map<std::string, MtlMaterial> mtlMaterials(const std::string& library, std::vector<std::string>& notes)
{
  std::ifstream file(library);
  std::stringstream text;
  text << file.rdbuf();
  const std::string all = text.str();
  TextLines lines(all);
  std::map<std::string, MtlMaterial> materials;
  MtlMaterial* current = nullptr;
  std::string_view line;
  while (lines.next(line))
  {
    std::string_view rest = line, keyword;
    if (!nextWord(rest, keyword, isSpace) || keyword.front() == '#')
    {
      continue;
    }
    if (keyword == "newmtl")
    {
      current = &materials[argumentOf(std::string(rest), 0)];
      continue;
    }
    const bool color = keyword == "Ka" || keyword == "Kd" || keyword == "Ks";
    if (!current || (!color && keyword != "Ns" && keyword != "illum"))
    {
      continue;
    }
    std::vector<double> numbers;
    std::string_view word;
    bool readable = true;
    while (readable && nextWord(rest, word, isSpace))
    {
      double value = 0;
      readable = readReal(word, value) == NumberFault::None;
      numbers.push_back(value);
    }
    if (!readable || numbers.empty() || numbers.size() > 3 || (!color && numbers.size() != 1))
    {
      notes.push_back(library + ": " +
        atLine(lines.number(),
          "'" + std::string(keyword) + "' is not given as numbers ShadeLab reads: its default is used"));
      continue;
    }
    // "Ka r" alone is a grey (the MTL format: g and b default to r).
    const Rgb rgb(
      numbers[0], numbers.size() > 1 ? numbers[1] : numbers[0], numbers.size() > 2 ? numbers[2] : numbers[0]);
    if (keyword == "Ka")
    {
      current->ka = rgb;
    }
    else if (keyword == "Kd")
    {
      current->kd = rgb;
    }
    else if (keyword == "Ks")
    {
      current->ks = rgb;
    }
    if (keyword == "Ns")
    {
      current->ns = numbers[0];
    }
    if (keyword == "illum")
    {
      current->illum = (long long)numbers[0];
    }
  }
  return materials;
}

/// The lecture's coefficients of an MTL material: Ka, Kd, Ks and Ns as they are, with VTK's
/// importer's defaults for a coefficient not given (Ka 0, Kd 1, Ks 0, Ns 0); illum 0 and 1 (no
/// highlights) have no specular term. A missing material, or a specular term without Ns, is noted.
PartMaterial lectureMaterial(
  const std::string& name, const std::map<std::string, MtlMaterial>& materials, std::vector<std::string>& notes)
{
  PartMaterial m;
  m.kd = Rgb(1.0);
  const auto found = materials.find(name);
  if (found == materials.end())
  {
    notes.push_back((name.empty() ? std::string("faces use a material") : "a part uses the material '" + name + "',") +
      " which the MTL file does not define: shaded with Kd 1, Ka and Ks 0 (VTK's importer's defaults)");
    return m;
  }
  const MtlMaterial& mtl = found->second;
  m.ka = mtl.ka.value_or(Rgb(0.0));
  m.kd = mtl.kd.value_or(Rgb(1.0));
  m.ks = mtl.illum >= 2 ? mtl.ks.value_or(Rgb(0.0)) : Rgb(0.0);
  m.shininess = mtl.ns.value_or(0.0);
  if (largestComponent(m.ks) > 0 && !mtl.ns)
  {
    notes.push_back("material '" + name + "' has Ks but no Ns: a shininess of 0, a specular term without a highlight");
  }
  return m;
}

/// The polygons of the actor's polydata: vtkOBJImporter makes a part for every material of the
/// MTL file, and one more, with those the faces use (none for the others).
vtkIdType polygonsOf(vtkActor* actor)
{
  vtkMapper* mapper = actor->GetMapper();
  auto* data = vtkPolyData::SafeDownCast(mapper ? mapper->GetInput() : nullptr);
  return data ? data->GetNumberOfPolys() : 0;
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
  std::vector<std::string> skipped; // noted once the parts are known to be whole
  const std::map<std::string, MtlMaterial> materials = mtlMaterials(library, skipped);
  std::vector<ImportedPart> parts;
  long long imported = 0; // the faces the importer kept, as polygons
  actors->InitTraversal();
  for (int i = 0; i < actors->GetNumberOfItems(); ++i)
  {
    const std::string texture = describedField(importer, i, "texture file");
    const fs::path texturePath = fs::absolute(fs::path(folderOf(library)) / texture).lexically_normal();
    vtkActor* actor = actors->GetNextActor();
    const std::string name = describedField(importer, i, "material named");
    const vtkIdType polygons = polygonsOf(actor);
    imported += polygons;
    if (polygons == 0)
    {
      continue; // a material no face uses, or the importer's default part
    }
    parts.push_back({ actor, name.empty() ? "(undefined)" : name, lectureMaterial(name, materials, skipped),
      actor->GetTexture(), texture == "none" || texture.empty() ? "" : texturePath.string() });
  }
  if (imported < statements.faces)
  {
    notes.push_back("VTK's OBJ importer read " + std::to_string(imported) + " of its " +
      std::to_string(statements.faces) +
      " faces (it leaves out faces without texture coordinates where others have them): read as one mesh "
      "without its materials");
    return nullptr;
  }
  vtkSmartPointer<vtkPolyData> mesh = meshOfParts(parts, skipped);
  notes.insert(notes.end(), skipped.begin(), skipped.end());
  return mesh;
}
}
