// Files that once crashed, stalled or misled `shadelab shade` (tests/hostile-inputs/README.md):
// each now ends in its one-line message with exit code 1 and nothing written, or, where the
// input is finite, in a finite result.
#include "CliFixture.h"

#include "vtkDataArray.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkXMLPolyDataReader.h"

#include <cmath>

namespace
{
using shadelab::testing::Cli;
using shadelab::testing::Result;
namespace fs = std::filesystem;

struct Hostile
{
  std::string file;    // under tests/hostile-inputs/
  std::string message; // after "shadelab: <file>: "
};

const std::string hostileFolder = shadelab::testing::sourcePath("tests/hostile-inputs/");

/// Asserts that the run failed with exactly "shadelab: <prefix><message>", wrote nothing and
/// left no temporary file behind.
void expectCleanRefusal(const Result& result, const fs::path& folder, const std::string& expected)
{
  EXPECT_EQ(result.exitCode, 1);
  EXPECT_EQ(result.err, "shadelab: " + expected + "\n");
  EXPECT_EQ(result.out, "");
  for (const fs::directory_entry& entry : fs::directory_iterator(folder))
  {
    ADD_FAILURE() << "left behind: " << entry.path();
  }
}

const std::string crashedVtk =
  "VTK's .vtk reader crashed on it (SIGSEGV): the file is damaged or not a valid .vtk file";
const std::string lyingPly = "the PLY header declares ";
const std::string cutShort = " after its header: it is cut short or its counts are wrong";

TEST_F(Cli, HostileMeshesAreRefusedInOneLine)
{
  const Hostile meshes[] = {
    // A reader's warning ("Error reading binary data!") and then a refusal: the refusal alone
    // (found by the command-line run over fuzz_mesh_vtk's corpus).
    { "meshes/fuzz_legacy_vtk_warning_then_refusal.vtk",
      "the mesh's coordinates reach 7.5e+31, beyond +-2.3e+18 where squared distances overflow float32: use double "
      "precision (shadelab shade --precision float64)" },
    { "meshes/legacy_vtk_corrupt_offsets.vtk",
      "polygon 7's points run from 188 to 6413125869375586328 in a list of 1344: the mesh is corrupt" },
    // Read by VTK without complaint, with offsets beyond the ids: refused before it is handed
    // over (found by fuzz_mesh_vtk, where reading it back asked for 2^63 bytes).
    { "meshes/fuzz_legacy_vtk_offsets_beyond_ids.vtk",
      "polygon 4's points run from 16 to 1953984351 in a list of 24: the mesh is corrupt" },
    { "meshes/obj_texture_index_out_of_range.obj",
      "line 6: face index 9 refers to texture coordinate 9, but the file lists 1 before that line" },
    { "meshes/ply_count_f2147483647.ply",
      (lyingPly + "4 vertices and 2147483647 faces, which need at least 4294967318 bytes, but the file has 56" +
        cutShort) },
    { "meshes/ply_count_f99999999.ply",
      (lyingPly + "4 vertices and 99999999 faces, which need at least 200000022 bytes, but the file has 56" +
        cutShort) },
    { "meshes/ply_count_v0.ply", "the PLY header declares 4 faces but no vertices for them to join" },
    { "meshes/ply_count_v2147483648.ply",
      "line 3 of the PLY header ('element vertex 2147483648') is not 'element NAME COUNT' with a COUNT from 0 to "
      "2147483647" },
    { "meshes/ply_count_v99999999.ply",
      (lyingPly + "99999999 vertices and 4 faces, which need at least 600000002 bytes, but the file has 56" +
        cutShort) },
    { "meshes/ply_count_vm1.ply",
      "line 3 of the PLY header ('element vertex -1') is not 'element NAME COUNT' with a COUNT from 0 to 2147483647" },
    { "meshes/polygon_with_no_vertices.ply",
      "polygon 1 has 0 points, and a polygon needs at least 3: the mesh is corrupt" },
    { "meshes/polygon_with_no_vertices.vtk",
      "polygon 1 has 0 points, and a polygon needs at least 3: the mesh is corrupt" },
    { "meshes/reader_crash_attempting_free_on_address_mesh.ply",
      (lyingPly + "35947 vertices and 69451 faces, which need at least 498372 bytes, but the file has 820" +
        cutShort) },
    { "meshes/reader_crash_bus_on_unknown_address_pcbps_vtkply_ply_close_mesh.ply",
      "line 4 of the PLY header ('properTy float x') is not a PLY header line" },
    { "meshes/reader_crash_segv_null_vtkdatareader_readstring_mesh.vtk", crashedVtk },
    { "meshes/reader_crash_segv_null_vtkplyreader_requestdata_mesh.ply",
      "line 10: 'NaN' is not a finite number (the 'vertex' property 'z')" },
    { "meshes/reader_crash_segv_vtkaosdataarraytemplate_float_gettuple_mesh.ply",
      "'face' element 0 of 448 (counting from 0): vertex index -1090885662 refers to no vertex: the header declares "
      "226, numbered from 0" },
    { "meshes/reader_crash_segv_vtkply_add_property_mesh.ply",
      "line 2 of the PLY header is not text: the file is damaged" },
    { "meshes/reader_crash_segv_vtkply_find_element_mesh.ply",
      "line 6 of the PLY header is not text: the file is damaged" },
    { "meshes/reader_crash_segv_vtkply_get_ascii_item_mesh.ply",
      (lyingPly + "35947 vertices and 69451 faces, which need at least 498372 bytes, but the file has 756" +
        cutShort) },
    { "meshes/reader_throws_std_bad_all_mesh.ply",
      (lyingPly + "2147483647 vertices and 4 faces, which need at least 12884901890 bytes, but the file has 56" +
        cutShort) },
    { "meshes/reader_throws_std_length_mesh.ply",
      "line 3 of the PLY header ('element vertex 2147483648') is not 'element NAME COUNT' with a COUNT from 0 to "
      "2147483647" },
  };
  const std::string out = (folder / "out.vtp").string();
  for (const Hostile& mesh : meshes)
  {
    SCOPED_TRACE(mesh.file);
    const std::string path = hostileFolder + mesh.file;
    expectCleanRefusal(shadelab("shade " + path + " -o " + out), folder, path + ": " + mesh.message);
    // compare reads them as shade does (exit code 2, the same message), except the one that
    // only shading refuses: its truncated block leaves values that VTK's reader never wrote,
    // which may differ between two reads, and the reader's warning says so.
    const Result compared = shadelab("compare " + path + " " + path);
    if (mesh.message.rfind("the mesh's coordinates reach", 0) == 0)
    {
      EXPECT_TRUE(compared.exitCode == 0 || compared.exitCode == 1) << compared.out << compared.err;
      EXPECT_EQ(compared.err,
        "shadelab: warning: " + path + ": Error reading binary data!\n" + "shadelab: warning: " + path +
          ": Error reading binary data!\n");
    }
    else
    {
      EXPECT_EQ(compared.exitCode, 2);
      EXPECT_EQ(compared.err, "shadelab compare: " + path + ": " + mesh.message + "\n");
    }
  }
}

TEST_F(Cli, HostileScenesAndMapsAreRefusedInOneLine)
{
  const std::string mesh = shadelab::testing::sourcePath("data/meshes/spot.obj"), out = (folder / "out.vtp").string();
  const Hostile scenes[] = {
    { "scenes/deeply_nested_100000.json",
      "nested more than 32 levels deep: a scene file has a few levels (lights, a light, its fields)" },
    // Refused by the filter for float32 once placed, and named as the scene's problem.
    { "scenes/float32_overflow_bright_sun.json",
      "/lights/0/intensity: this light alone can reach 8e+38 at a vertex (colour x intensity x k x attenuation "
      "at min_distance), beyond what float32 holds: use float64 or a smaller intensity or colour" },
    { "scenes/light_name_100000_chars.json",
      "/lights/0/name: a name of 100001 characters is too long: use at most 64" },
  };
  for (const Hostile& scene : scenes)
  {
    SCOPED_TRACE(scene.file);
    const std::string path = hostileFolder + scene.file;
    expectCleanRefusal(shadelab("shade " + mesh + " -s " + path + " -o " + out), folder, path + ": " + scene.message);
  }
  const Hostile maps[] = {
    { "envmaps/header_30000x60000_no_pixels.hdr",
      "the header declares 60000x30000 texels (21.6 GB as floats), more than ShadeLab takes (134217728 texels): it "
      "is damaged, or too large a map" },
    { "envmaps/header_int_overflow.hdr",
      "an equirectangular map must be twice as wide as it is high; this one is 2147483647x2147483647" },
  };
  for (const Hostile& map : maps)
  {
    SCOPED_TRACE(map.file);
    const std::string path = hostileFolder + map.file;
    expectCleanRefusal(
      shadelab("shade " + mesh + " --envmap " + path + " -o " + out), folder, "--envmap: " + path + ": " + map.message);
  }
}

TEST_F(Cli, AHugeFiniteNormalGivesFiniteTerms)
{
  // A normal component of 1e30 under the area lights: finite, in both precisions.
  for (const char* precision : { "float32", "float64" })
  {
    SCOPED_TRACE(precision);
    const std::string out = (folder / "out.vtp").string();
    const Result result = shadelab("shade " + hostileFolder + "meshes/normal_component_1e30.vtp -s " +
      shadelab::testing::sourcePath("data/scenes/area_lights.json") + " -a all --precision " + precision + " -o " +
      out);
    ASSERT_EQ(result.exitCode, 0) << result.err;
    vtkNew<vtkXMLPolyDataReader> reader;
    reader->SetFileName(out.c_str());
    reader->Update();
    vtkPointData* arrays = reader->GetOutput()->GetPointData();
    ASSERT_GT(arrays->GetNumberOfArrays(), 10);
    for (int a = 0; a < arrays->GetNumberOfArrays(); ++a)
    {
      vtkDataArray* array = arrays->GetArray(a);
      for (vtkIdType v = 0; v < array->GetNumberOfValues(); ++v)
      {
        ASSERT_TRUE(std::isfinite(array->GetVariantValue(v).ToDouble())) << array->GetName() << " " << v;
      }
    }
  }
}

TEST_F(Cli, StaleTemporariesOfDeadRunsAreRemoved)
{
  // A run killed while writing leaves OUT.partial-PID; the next run into the same folder
  // removes those whose process is gone, and keeps a live one's.
  const std::string out = (folder / "out.vtp").string();
  const std::string dead = out + ".partial-999999999", live = out + ".partial-1"; // pid 1 always runs
  std::ofstream(dead) << "half a file";
  std::ofstream(live) << "being written";
  const Result result = shadelab("shade " + shadelab::testing::sourcePath("data/meshes/spot.obj") + " -o " + out);
  ASSERT_EQ(result.exitCode, 0) << result.err;
  EXPECT_FALSE(fs::exists(dead));
  EXPECT_TRUE(fs::exists(live));
  EXPECT_TRUE(fs::exists(out));
}
}
