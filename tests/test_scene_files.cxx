// Meshes with their own materials (docs/guide/scene-files.md): an OBJ file read with its MTL
// file by VTK's importer, each part shaded with its own Kd against the closed form, a texture
// decoded and placed texel by texel, a scene's material winning over the file's, and what a
// missing library or texture leaves.
#include "FilterRun.h"
#include "TestFolder.h"

#include "MeshFiles.h"
#include "SceneFile.h"
#include "ShadeLabImportedParts.h"

#include "vtkDataArray.h"
#include "vtkFieldData.h"
#include "vtkImageData.h"
#include "vtkPNGWriter.h"
#include "vtkPointData.h"
#include "vtkUnsignedCharArray.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <unistd.h>

namespace
{
using namespace shadelab;
namespace fs = std::filesystem;

using SceneFiles = shadelab::testing::TestFolder;

/// The 8-bit texels of a 4 x 2 texture, row 0 first (texture v = 0).
const unsigned char texels[2][4][3] = { { { 255, 0, 0 }, { 0, 255, 0 }, { 0, 0, 255 }, { 200, 100, 50 } },
  { { 10, 20, 30 }, { 128, 128, 128 }, { 255, 255, 255 }, { 0, 0, 0 } } };

void writeTexture(const std::string& path)
{
  vtkNew<vtkImageData> image;
  image->SetDimensions(4, 2, 1);
  image->AllocateScalars(VTK_UNSIGNED_CHAR, 3);
  for (int row = 0; row < 2; ++row)
  {
    for (int column = 0; column < 4; ++column)
    {
      for (int c = 0; c < 3; ++c)
      {
        static_cast<unsigned char*>(image->GetScalarPointer(column, row, 0))[c] = texels[row][column][c];
      }
    }
  }
  vtkNew<vtkPNGWriter> writer;
  writer->SetInputData(image);
  writer->SetFileName(path.c_str());
  writer->Write();
}

/// sRGB's decoding (IEC 61966-2-1), written out here rather than called.
double decoded(unsigned char value)
{
  const double c = value / 255.0;
  return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4);
}

/// Two flat parts in the plane z = 0, normals +z: "red" a unit square at x in [-2, -1], and
/// "tex" a grid of 4 x 2 vertices, one at each texel's centre of the 4 x 2 texture, at x >= 0.
const char* const twoPartObj = R"(mtllib parts.mtl
v -2 0 0
v -1 0 0
v -1 1 0
v -2 1 0
v 0 0 0
v 1 0 0
v 2 0 0
v 3 0 0
v 0 1 0
v 1 1 0
v 2 1 0
v 3 1 0
vt 0.125 0.25
vt 0.375 0.25
vt 0.625 0.25
vt 0.875 0.25
vt 0.125 0.75
vt 0.375 0.75
vt 0.625 0.75
vt 0.875 0.75
vn 0 0 1
usemtl red
f 1/1/1 2/2/1 3/6/1
f 1/1/1 3/6/1 4/5/1
usemtl tex
f 5/1/1 6/2/1 10/6/1
f 5/1/1 10/6/1 9/5/1
f 6/2/1 7/3/1 11/7/1
f 6/2/1 11/7/1 10/6/1
f 7/3/1 8/4/1 12/8/1
f 7/3/1 12/8/1 11/7/1
)";

const char* const partsMtl = R"(newmtl red
Ka 0.1 0 0
Kd 0.7 0.2 0.1
Ks 0.5 0.5 0.5
Ns 20
newmtl tex
Ka 0 0.1 0
Kd 0.9 0.8 0.6
Ks 0.2 0.2 0.2
Ns 64
map_Kd texture.png
)";

/// One white distant light straight down onto the parts, and no material unless given.
Scene sunScene(const std::string& material = "")
{
  return parseScene(R"({ "viewer": { "position": [0, 0, 10] },)" + material +
      R"( "lights": [ { "name": "sun", "type": "distant", "direction": [0, 0, -1] } ] })",
    "scene.json");
}

TEST_F(SceneFiles, EachPartIsShadedWithItsOwnMaterialAndTexture)
{
  writeTexture((folder / "texture.png").string());
  file("parts.mtl", partsMtl);
  vtkSmartPointer<vtkPolyData> mesh = app::readMesh(file("parts.obj", twoPartObj));
  ASSERT_TRUE(hasOwnMaterials(mesh));
  auto* names = vtkStringArray::SafeDownCast(mesh->GetFieldData()->GetAbstractArray(partNamesArrayName));
  ASSERT_NE(names, nullptr);
  ASSERT_EQ(names->GetNumberOfValues(), 2);
  EXPECT_EQ(names->GetValue(0), "red");
  EXPECT_EQ(names->GetValue(1), "tex");

  vtkSmartPointer<vtkPolyData> output =
    shadelab::testing::shadeWithFilter(mesh, sunScene(), { "sun_diffuse", "sun_specular" });
  vtkDataArray* diffuse = output->GetPointData()->GetArray("sun_diffuse");
  vtkDataArray* part = output->GetPointData()->GetArray(partArrayName);
  vtkDataArray* shininess = output->GetPointData()->GetArray(materialShininessArrayName);
  vtkDataArray* uv = output->GetPointData()->GetTCoords();
  ASSERT_TRUE(diffuse && part && shininess && uv);
  int texelsSeen = 0;
  for (vtkIdType p = 0; p < output->GetNumberOfPoints(); ++p)
  {
    // n.s = 1 and the light is white of intensity 1: the diffuse term is kd itself.
    if (part->GetComponent(p, 0) == 0)
    {
      const double kd[3] = { 0.7, 0.2, 0.1 };
      for (int c = 0; c < 3; ++c)
      {
        EXPECT_EQ(diffuse->GetComponent(p, c), double(float(kd[c]))) << "vertex " << p;
      }
      EXPECT_EQ(shininess->GetComponent(p, 0), 20);
      continue;
    }
    const int column = int(std::floor(uv->GetComponent(p, 0) * 4)), row = int(std::floor(uv->GetComponent(p, 1) * 2));
    const double kd[3] = { 0.9, 0.8, 0.6 };
    for (int c = 0; c < 3; ++c)
    {
      EXPECT_NEAR(diffuse->GetComponent(p, c), float(kd[c]) * decoded(texels[row][column][c]), 1e-6)
        << "vertex " << p << ", texel " << column << ", " << row;
    }
    EXPECT_EQ(shininess->GetComponent(p, 0), 64);
    ++texelsSeen;
  }
  EXPECT_EQ(texelsSeen, 18); // the 6 triangles' corners, as the importer keeps them
}

TEST_F(SceneFiles, AScenesMaterialWinsOverTheFiles)
{
  writeTexture((folder / "texture.png").string());
  file("parts.mtl", partsMtl);
  vtkSmartPointer<vtkPolyData> mesh = app::readMesh(file("parts.obj", twoPartObj));
  const Scene scene = sunScene(R"( "material": { "kd": [0.25, 0.5, 0.75] },)");
  EXPECT_FALSE(shadesWithOwnMaterials(scene, mesh, false));
  vtkSmartPointer<vtkPolyData> output = shadelab::testing::shadeWithFilter(mesh, scene, { "sun_diffuse" });
  vtkDataArray* diffuse = output->GetPointData()->GetArray("sun_diffuse");
  for (vtkIdType p = 0; p < output->GetNumberOfPoints(); ++p)
  {
    EXPECT_EQ(diffuse->GetComponent(p, 0), 0.25);
    EXPECT_EQ(diffuse->GetComponent(p, 2), 0.75);
  }
  EXPECT_TRUE(shadesWithOwnMaterials(sunScene(), mesh, false));
  EXPECT_FALSE(shadesWithOwnMaterials(sunScene(), mesh, true)); // coloured by an array instead
}

TEST_F(SceneFiles, FacesTheImporterLeavesOutKeepTheWholeMesh)
{
  // VTK 9.1's importer drops the red faces, which have no texture coordinates where the others
  // have: the file is read whole by the mesh reader instead, without materials.
  std::string obj = twoPartObj;
  obj.replace(obj.find("f 1/1/1 2/2/1 3/6/1"), 19, "f 1//1 2//1 3//1");
  file("parts.mtl", partsMtl);
  vtkSmartPointer<vtkPolyData> mesh = app::readMesh(file("parts.obj", obj));
  EXPECT_FALSE(hasOwnMaterials(mesh));
  EXPECT_EQ(mesh->GetNumberOfPolys(), 8);
}

TEST_F(SceneFiles, AMissingLibraryLeavesTheMeshAlone)
{
  vtkSmartPointer<vtkPolyData> mesh = app::readMesh(file("parts.obj", twoPartObj));
  EXPECT_FALSE(hasOwnMaterials(mesh));
  EXPECT_EQ(mesh->GetNumberOfPolys(), 8);
}

TEST_F(SceneFiles, AMissingTextureLeavesTheDiffuseColour)
{
  file("parts.mtl", partsMtl);
  vtkSmartPointer<vtkPolyData> mesh = app::readMesh(file("parts.obj", twoPartObj));
  vtkSmartPointer<vtkPolyData> output = shadelab::testing::shadeWithFilter(mesh, sunScene(), { "sun_diffuse" });
  vtkDataArray* diffuse = output->GetPointData()->GetArray("sun_diffuse");
  vtkDataArray* part = output->GetPointData()->GetArray(partArrayName);
  for (vtkIdType p = 0; p < output->GetNumberOfPoints(); ++p)
  {
    EXPECT_EQ(diffuse->GetComponent(p, 1), double(part->GetComponent(p, 0) == 0 ? 0.2f : 0.8f));
  }
}
}
