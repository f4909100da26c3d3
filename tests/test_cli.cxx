// The shadelab command as a user runs it: exit codes and the exact message for each kind of
// bad input, and no partial or spoilt output file after a failure.
#include "CliFixture.h"

#include "vtkCellArray.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkIntArray.h"
#include "vtkNew.h"
#include "vtkPNGReader.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkUnsignedCharArray.h"
#include "vtkXMLPolyDataReader.h"
#include "vtkXMLPolyDataWriter.h"

#include <glm/gtc/type_ptr.hpp>
#include <glm/vec3.hpp>

#include <cmath>
#include <fstream>
#include <iterator>
#include <limits>
#include <map>
#include <regex>
#include <set>

#include <nlohmann/json.hpp>

namespace
{
using shadelab::testing::Cli;
using shadelab::testing::Result;
namespace fs = std::filesystem;

TEST_F(Cli, MissingOrUnreadableMesh)
{
  const std::string scene = goodScene(), out = (folder / "out.vtp").string();
  const std::string missing = (folder / "nope.ply").string();
  expectError("shade " + missing + " -s " + scene + " -o " + out, missing + ": no such file");
  fs::create_directories(folder / "dir.ply");
  const std::string directory = (folder / "dir.ply").string();
  expectError(
    "shade " + directory + " -s " + scene + " -o " + out, directory + ": cannot be read (is it a readable file?)");
  const std::string garbage = file("garbage.ply", "not a mesh\n");
  expectError("shade " + garbage + " -s " + scene + " -o " + out,
    garbage + ": not a PLY file (it does not start with a PLY header)");
  const std::string unknown = file("mesh.xyz", "1 2 3\n");
  expectError("shade " + unknown + " -s " + scene + " -o " + out,
    unknown + ": unknown mesh format '.xyz'; ShadeLab reads .vtp, .pvtp, .vtk, .ply, .obj, .stl, .gltf, .glb");
}

TEST_F(Cli, EmptyMeshAndMeshWithoutPolygons)
{
  const std::string scene = goodScene(), out = (folder / "out.vtp").string();
  const std::string empty =
    file("empty.vtk", "# vtk DataFile Version 3.0\nempty\nASCII\nDATASET POLYDATA\nPOINTS 0 float\n");
  expectError("shade " + empty + " -s " + scene + " -o " + out, empty + ": the mesh has no points");
  const std::string points = file("points.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\np 1 2 3\n");
  expectError("shade " + points + " -s " + scene + " -o " + out,
    points + ": the mesh has no polygons (1 vertex or line cells): surface shading needs a surface");
}

TEST_F(Cli, BadScenes)
{
  const std::string mesh = goodMesh(), out = (folder / "out.vtp").string();
  const std::string malformed = file("malformed.json", "{ \"lights\": [\n  { \"type\": \"distant\" \n");
  expectError("shade " + mesh + " -s " + malformed + " -o " + out,
    malformed +
      ": not valid JSON: parse error at line 3, column 1: syntax error while parsing "
      "object - unexpected end of input; expected '}'");
  const std::string laser = file("laser.json", R"({ "lights": [ { "type": "laser" } ] })");
  expectError("shade " + mesh + " -s " + laser + " -o " + out,
    laser +
      ": /lights/0/type: \"laser\" is not one of \"distant\", \"headlight\", \"point\", \"spot\", \"ambient\", "
      "\"polygon\", \"rectangle\", \"disk\", \"sphere\", \"environment\"");
  const std::string negative =
    file("negative.json", R"({ "lights": [ { "type": "point", "position": [0, 0, 1], "intensity": -3 } ] })");
  expectError(
    "shade " + mesh + " -s " + negative + " -o " + out, negative + ": /lights/0/intensity: must be a number >= 0");
  const std::string missing = file("missing.json", R"({ "lights": [ { "type": "spot", "direction": [0, 0, -1] } ] })");
  expectError("shade " + mesh + " -s " + missing + " -o " + out, missing + ": /lights/0/position: missing");
  const std::string huge = file("huge.json", R"({ "lights": [ { "type": "ambient", "intensity": 1e400 } ] })");
  expectError(
    "shade " + mesh + " -s " + huge + " -o " + out, huge + ": not valid JSON: number overflow parsing '1e400'");
  const std::string absent = (folder / "absent.json").string();
  expectError("shade " + mesh + " -s " + absent + " -o " + out,
    absent + ": cannot open the scene file (does it exist, and is it readable?)");
}

TEST_F(Cli, MisspeltOptionsAndSceneKeysGetTheNearestName)
{
  const std::string mesh = goodMesh(), out = (folder / "out.vtp").string();
  const Result option = shadelab("shade " + mesh + " --tolerence 0.02 -o " + out);
  EXPECT_EQ(option.exitCode, 2);
  EXPECT_EQ(option.err,
    "shadelab shade: unknown option --tolerence: did you mean --tolerance?\n"
    "Run with --help for more information.\n");
  const Result twoOptions =
    shadelab("render " + mesh + " --arary total --frobnicate -o " + (folder / "o.png").string());
  EXPECT_EQ(twoOptions.exitCode, 2);
  EXPECT_EQ(twoOptions.err,
    "shadelab render: unknown option --arary: did you mean --array?; unknown option "
    "--frobnicate\nRun with --help for more information.\n");
  // A light's misspelt field is matched against its own type's fields.
  const std::string intensity =
    file("intensity.json", R"({ "lights": [ { "type": "point", "position": [0, 0, 1], "intesity": 2 } ] })");
  expectError("shade " + mesh + " -s " + intensity + " -o " + out,
    intensity +
      ": /lights/0/intesity: unknown field; did you mean \"intensity\"? allowed here: name, type, color, "
      "spectrum, intensity, shadows, position, attenuation, min_distance");
}

TEST_F(Cli, CorruptAndTruncatedFiles)
{
  const std::string scene = goodScene(), out = (folder / "out.vtp").string();
  const std::string header =
    "# vtk DataFile Version 3.0\nt\nASCII\nDATASET POLYDATA\nPOINTS 3 float\n0 0 0 1 0 0 0 1 0\n";
  const std::string corrupt = file("corrupt.vtk", header + "POLYGONS 1 4\n3 0 1 2000000\n");
  expectError("shade " + corrupt + " -s " + scene + " -o " + out,
    corrupt + ": the mesh's cells use point id 2000000, but it has 3 points: the mesh is corrupt");
  // A NORMALS block cut short: the reader only warns, and so does shadelab, naming the file.
  const std::string truncated =
    file("truncated.vtk", header + "POLYGONS 1 4\n3 0 1 2\nPOINT_DATA 3\nNORMALS Normals float\n0 0 1 0 0\n");
  const Result result = shadelab("shade " + truncated + " -s " + scene + " -o " + out);
  EXPECT_EQ(result.exitCode, 0);
  EXPECT_EQ(result.err,
    "shadelab: warning: " + truncated +
      ": Error reading ascii data. Possible mismatch of datasize with declaration.\n");
}

TEST_F(Cli, UnknownArrayNameAndBadOutput)
{
  const std::string mesh = goodMesh(), scene = goodScene();
  const Result unknown =
    shadelab("shade " + mesh + " -s " + scene + " -o " + (folder / "o.vtp").string() + " --arrays total,sun_glare");
  EXPECT_EQ(unknown.exitCode, 1);
  EXPECT_EQ(unknown.err,
    "shadelab: --arrays: unknown array 'sun_glare'; this scene has: default, totals, all, "
    "*_to_light, *_distance, *_attenuation, *_spot_factor, *_cos_incidence, *_incidence_angle, "
    "*_reflection, *_r_dot_v, *_half_vector, *_n_dot_h, *_diffuse, *_specular, *_irradiance, "
    "*_irradiance_std_error, *_specular_std_error, *_visibility, *_visibility_std_error, *_short_of_target, "
    "*_sh_transfer, *_sh_transfer_std_error, "
    "ambient, diffuse, specular, total, shading_flags, sun_to_light, sun_attenuation, sun_spot_factor, "
    "sun_cos_incidence, sun_incidence_angle, sun_reflection, sun_r_dot_v, sun_half_vector, "
    "sun_n_dot_h, sun_diffuse, sun_specular\n");
  const std::string png = (folder / "out.png").string();
  expectError(
    "shade " + mesh + " -s " + scene + " -o " + png, png + ": cannot write '.png' files here; use .vtp, .pvtp, .vtk");
  expectError("shade " + mesh + " -s " + scene + " -o " + (folder / "o.vtp").string() + " --arrays ,",
    "--arrays: no arrays selected; this scene has: default, totals, all, *_to_light, *_distance, "
    "*_attenuation, *_spot_factor, *_cos_incidence, *_incidence_angle, *_reflection, *_r_dot_v, "
    "*_half_vector, *_n_dot_h, *_diffuse, *_specular, *_irradiance, *_irradiance_std_error, "
    "*_specular_std_error, *_visibility, *_visibility_std_error, *_short_of_target, *_sh_transfer, "
    "*_sh_transfer_std_error, ambient, diffuse, specular, total, shading_flags, sun_to_light, sun_attenuation, "
    "sun_spot_factor, sun_cos_incidence, "
    "sun_incidence_angle, sun_reflection, sun_r_dot_v, sun_half_vector, sun_n_dot_h, sun_diffuse, "
    "sun_specular");
  const std::string nowhere = (folder / "no" / "such" / "out.vtp").string();
  expectError("shade " + mesh + " -s " + scene + " -o " + nowhere,
    nowhere + ": the folder " + (folder / "no" / "such").string() + " does not exist");
}

TEST_F(Cli, FailedWriteLeavesNothingBehind)
{
  // The target is a directory: the data are written to a temporary file, the final rename
  // fails, and the temporary file must be gone.
  const fs::path target = folder / "taken.vtp";
  fs::create_directories(target);
  const Result result = shadelab("shade " + goodMesh() + " -s " + goodScene() + " -o " + target.string());
  EXPECT_EQ(result.exitCode, 1);
  EXPECT_EQ(result.err, "shadelab: " + target.string() + ": cannot be written: Is a directory\n");
  std::vector<std::string> left;
  for (const auto& entry : fs::directory_iterator(folder))
  {
    left.push_back(entry.path().filename().string());
  }
  std::sort(left.begin(), left.end());
  EXPECT_EQ(left, (std::vector<std::string>{ "scene.json", "taken.vtp" }));
}

TEST_F(Cli, FailedRunKeepsTheExistingOutput)
{
  const std::string out = file("out.vtp", "an earlier good result");
  const std::string bad = file("bad.json", R"({ "lights": [ { "type": "distant" } ] })");
  EXPECT_EQ(shadelab("shade " + goodMesh() + " -s " + bad + " -o " + out).exitCode, 1);
  EXPECT_EQ(slurp(out), "an earlier good result");
}

TEST_F(Cli, ShadesAndSummarises)
{
  const std::string out = file("out.vtp", "an earlier result, to be replaced");
  const Result result = shadelab("shade " + goodMesh() + " -s " + goodScene() + " -o " + out +
    " --arrays default,sun_cos_incidence --precision float64 --threads 1");
  EXPECT_EQ(result.exitCode, 0) << result.err;
  EXPECT_EQ(result.err, "");
  EXPECT_NE(result.out.find("  mesh: 35947 vertices, 69451 polygons and strips\n"), std::string::npos) << result.out;
  EXPECT_NE(result.out.find("    sun_cos_incidence            1     "), std::string::npos) << result.out;
  EXPECT_NE(result.out.find("(1 thread, float64)"), std::string::npos) << result.out;
  EXPECT_NE(result.out.find("flipped them outward."), std::string::npos) << result.out;
  // Replaced by a VTK XML file whose arrays hold their own data, which Debian 12's ParaView reads.
  const std::string written = slurp(out);
  EXPECT_EQ(written.rfind("<?xml version=\"1.0\"?>\n<VTKFile type=\"PolyData\"", 0), 0u);
  EXPECT_EQ(written.find("<AppendedData"), std::string::npos);
  EXPECT_NE(written.find("format=\"binary\""), std::string::npos);
  // --raw-appended: the data raw in one block at the end.
  ASSERT_EQ(shadelab("shade " + goodMesh() + " -o " + out + " --raw-appended").exitCode, 0);
  EXPECT_NE(slurp(out).find("<AppendedData encoding=\"raw\">"), std::string::npos);
}

TEST_F(Cli, ShadowsAndAmbientOcclusion)
{
  // --shadows gives every light that can cast shadows its visibility; --ambient-occlusion the
  // occlusion arrays, in the default selection, and the rays' report.
  const std::string out = (folder / "shadows.vtp").string();
  const Result result = shadelab("shade " + goodMesh() + " -o " + out + " --shadows --ambient-occlusion 16");
  EXPECT_EQ(result.exitCode, 0) << result.err;
  for (const char* line : { "    ambient_occlusion            1 ", "    ambient_occlusion_std_error  1 ",
         "    key_visibility               1             0            1\n", "  visibility: Cast up to " })
  {
    EXPECT_NE(result.out.find(line), std::string::npos) << line << "\n" << result.out;
  }
  EXPECT_EQ(result.out.find("sky_view_factor"), std::string::npos) << "only on request";
  EXPECT_NE(result.out.find(
              "with a shadowed light's ray meeting its own triangles first, 0 with a shadowed light hidden inside "
              "the mesh\n"),
    std::string::npos)
    << result.out;
  // A tolerance covers hard shadows (their visibility is exact: 0 or 1) and ambient occlusion:
  // a fixed count of rays must fit the share left to it, "auto" draws what it needs.
  const Result shadows = shadelab("shade " + goodMesh() + " -o " + out + " --shadows --tolerance 1e-3");
  EXPECT_EQ(shadows.exitCode, 0) << shadows.err;
  EXPECT_NE(shadows.out.find("    key_visibility               1             0            1\n"), std::string::npos)
    << shadows.out;
  const Result fixed = shadelab("shade " + goodMesh() + " -o " + out + " --ambient-occlusion 16 --tolerance 0.05");
  EXPECT_EQ(fixed.exitCode, 1);
  EXPECT_EQ(fixed.err,
    "shadelab: --ambient-occlusion 16: ambient occlusion's 16 rays per vertex can err by up to 0.25 "
    "(95%), more than the 0.05 the tolerance leaves it: give \"rays\": \"auto\" "
    "(--ambient-occlusion auto) to draw as many as the tolerance needs, or a larger tolerance\n");
  const Result untargeted = shadelab("shade " + goodMesh() + " -o " + out + " --ambient-occlusion auto");
  EXPECT_EQ(untargeted.exitCode, 1);
  EXPECT_EQ(untargeted.err,
    "shadelab: --ambient-occlusion auto: \"auto\" takes its count of rays from a tolerance: "
    "give one (shadelab shade --tolerance, the filter's Tolerance), or a number of rays\n");
  const Result adaptive = shadelab("shade " + goodMesh() + " -o " + out + " --ambient-occlusion auto --tolerance 0.05");
  EXPECT_EQ(adaptive.exitCode, 0) << adaptive.err;
  // Before the run, the plan and its forecast from a pilot; after it, what the rays drew. The
  // names' column is as wide as ambient_occlusion_short_of_target's.
  for (const char* line :
    { "    ambient_occlusion_rays             1 ",
      "    ambient occlusion: rays auto, within 0.05 at 95% "
      "(standard error at most 0.025), 64 to 4096 rays per vertex\n    forecast from 279 of the 35947 vertices: about ",
      "  methods: as printed before shading, then\n    drew " })
  {
    EXPECT_NE(adaptive.out.find(line), std::string::npos) << line << "\n" << adaptive.out;
  }
  const Result rays = shadelab("shade " + goodMesh() + " -o " + out + " --ambient-occlusion 1");
  EXPECT_EQ(rays.exitCode, 2);
  EXPECT_NE(rays.err.find("--ambient-occlusion"), std::string::npos) << rays.err;
}

TEST_F(Cli, BouncesAddTheLightTheMeshReflectsOntoItself)
{
  // --bounces adds interreflection: its arrays in the default selection, the step's report and
  // the ambient term set against it; diffuse and total include it.
  const std::string out = (folder / "bounces.vtp").string();
  const Result result = shadelab("shade " + goodMesh() + " -o " + out + " --bounces 2");
  EXPECT_EQ(result.exitCode, 0) << result.err;
  for (const char* line :
    { "  interreflection: 2 bounces from 'diffuse', 64 gather rays per vertex (16 for the later bounces); ",
      "    the constant ambient term nearest the indirect light (least squares over the vertices): (",
      "; the scene's ambient term, on average: (", "    indirect_irradiance            3             0 ",
      "    indirect_irradiance_std_error  3             0 ", "    indirect                       3             0 " })
  {
    EXPECT_NE(result.out.find(line), std::string::npos) << line << "\n" << result.out;
  }
  const Result plain = shadelab("shade " + goodMesh() + " -o " + out + " --bounces 0");
  EXPECT_EQ(plain.exitCode, 0) << plain.err;
  EXPECT_EQ(plain.out.find("indirect"), std::string::npos) << plain.out;
  const Result tolerance = shadelab("shade " + goodMesh() + " -o " + out + " --bounces 1 --tolerance 0.05");
  EXPECT_EQ(tolerance.exitCode, 1);
  EXPECT_EQ(tolerance.err,
    "shadelab: --bounces 1: a tolerance cannot bound what the bounces past a fixed 1 leave out: give \"bounces\": "
    "\"auto\" (--bounces auto), which takes as many as the tolerance needs; or shade without a tolerance\n");
  const Result untargeted = shadelab("shade " + goodMesh() + " -o " + out + " --bounces auto");
  EXPECT_EQ(untargeted.exitCode, 1);
  EXPECT_EQ(untargeted.err,
    "shadelab: --bounces auto: \"auto\" takes interreflection's count of bounces from a tolerance: give one "
    "(shadelab shade --tolerance, the filter's Tolerance), or a number of bounces\n");
  // --bounces auto under a tolerance: half of it for interreflection, the bounces and the gather's
  // rays chosen in the run and printed with the methods.
  const Result automatic = shadelab("shade " + goodMesh() + " -o " + out + " --bounces auto --tolerance 0.05");
  EXPECT_EQ(automatic.exitCode, 0) << automatic.err;
  for (const char* line :
    { "    interreflection: a share of 0.025 (0.0025 for the bounces left out, 0.023 for the gather at 95%); kd up to "
      "0.8, so the direct terms' errors count 5 times\n",
      "\n    interreflection chose ", "\n    after the bounces: an error of about " })
  {
    EXPECT_NE(automatic.out.find(line), std::string::npos) << line << "\n" << automatic.out;
  }
  const Result tooMany = shadelab("shade " + goodMesh() + " -o " + out + " --bounces 65");
  EXPECT_EQ(tooMany.exitCode, 2);
  EXPECT_NE(tooMany.err.find("--bounces: (Value 65 not in range 0 to 64) OR (65 not in {auto})"), std::string::npos)
    << tooMany.err;
}

TEST_F(Cli, SelfShadowingFollowsTheSmoothSurfaceUnlessToldFacets)
{
  // The dragon under the sun with shadows: the vertices whose shadow ray meets one of their
  // own facets first (flag 64) are all dark with --self-shadowing facets, and by default some
  // of them are lit, where nothing beyond their own facets hides the sun.
  const std::string mesh = shadelab::testing::sourcePath("data/meshes/xyzrgb_dragon_50k.ply");
  const std::string scene = shadelab::testing::sourcePath("data/scenes/sun.json");
  auto flaggedAndLit = [&](const std::string& option)
  {
    const std::string out = (folder / "dragon.vtp").string();
    const Result run = shadelab("shade " + mesh + " -s " + scene + " --shadows -a all -o " + out + option);
    EXPECT_EQ(run.exitCode, 0) << run.err;
    vtkNew<vtkXMLPolyDataReader> reader;
    reader->SetFileName(out.c_str());
    reader->Update();
    vtkDataArray* flags = reader->GetOutput()->GetPointData()->GetArray("shading_flags");
    vtkDataArray* visibility = reader->GetOutput()->GetPointData()->GetArray("sun_visibility");
    std::pair<int, int> counts{ 0, 0 };
    for (vtkIdType i = 0; flags && visibility && i < flags->GetNumberOfTuples(); ++i)
    {
      const bool flagged = (int(flags->GetComponent(i, 0)) & 64) != 0;
      counts.first += flagged;
      counts.second += flagged && visibility->GetComponent(i, 0) == 1;
    }
    return counts;
  };
  const auto [flaggedFacets, litFacets] = flaggedAndLit(" --self-shadowing facets");
  const auto [flaggedSmooth, litSmooth] = flaggedAndLit("");
  EXPECT_EQ(flaggedFacets, flaggedSmooth);
  EXPECT_GT(flaggedFacets, 1000);
  EXPECT_EQ(litFacets, 0);
  EXPECT_GT(litSmooth, flaggedSmooth / 4);
  const Result wrong = shadelab("shade " + mesh + " --self-shadowing soft -o " + (folder / "x.vtp").string());
  EXPECT_EQ(wrong.exitCode, 2);
  EXPECT_NE(wrong.err.find("--self-shadowing: soft not in {smooth,facets}"), std::string::npos) << wrong.err;
}

TEST_F(Cli, ToleranceChoosesAndReportsMethods)
{
  const std::string scene = shadelab::testing::sourcePath("data/scenes/three_lights.json");
  const std::string out = (folder / "tolerance.vtp").string();
  const Result result = shadelab("shade " + goodMesh() + " -s " + scene + " -o " + out + " --tolerance 1e-2");
  EXPECT_EQ(result.exitCode, 0) << result.err;
  // The plan is printed as soon as it is chosen, before the run's report.
  EXPECT_EQ(
    result.out.rfind(
      "shadelab shade: methods for the tolerance, chosen before shading:\n    arithmetic float32 (rounding ", 0),
    0u)
    << result.out;
  EXPECT_NE(result.out.find("  methods: as printed before shading, then\n"), std::string::npos) << result.out;
  EXPECT_NE(
    result.out.find(") and the methods below, chosen so that their predicted errors, 0.0052 in all, stay within "
                    "the tolerance 0.01\n"),
    std::string::npos)
    << result.out;
  EXPECT_NE(result.out.find("    key: Schlick pow, predicted error 0.0052"), std::string::npos) << result.out;

  const Result both =
    shadelab("shade " + goodMesh() + " -s " + scene + " -o " + out + " --tolerance 1e-2 --precision float64");
  EXPECT_EQ(both.exitCode, 2);
  EXPECT_EQ(both.err, "--precision excludes --tolerance\nRun with --help for more information.\n");
  expectError("shade " + goodMesh() + " -s " + scene + " -o " + out + " --tolerance 1e-30",
    goodMesh() +
      ": tolerance 1e-30 is below the predicted float64 rounding error of this scene on this mesh, "
      "2.9e-15: give a larger tolerance, or none for the exact methods");
}

TEST_F(Cli, SaysWhichStatementsOfAnObjItDidNotRead)
{
  // OBJ lets a reader skip object names and smoothing groups; the run says it did, and a mesh
  // without them says nothing.
  const std::string named = file("named.obj",
    "o tetra\ns 1\ns off\nv 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\n"
    "f 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n");
  const Result result = shadelab("shade " + named + " -o " + (folder / "named.vtp").string());
  EXPECT_EQ(result.exitCode, 0) << result.err;
  EXPECT_NE(result.out.find("  mesh: 4 vertices, 4 polygons and strips\n  ignored: 1 'o', 2 's' statements (object "
                            "names and smoothing groups are not read)\n"),
    std::string::npos)
    << result.out;
  const Result plain = shadelab("shade " + goodMesh() + " -o " + (folder / "plain.vtp").string());
  EXPECT_EQ(plain.out.find("ignored:"), std::string::npos) << plain.out;
}

TEST_F(Cli, ReadsObjAndStlAndWritesLegacyVtk)
{
  // A tetrahedron in both formats: 4 vertices (OBJ) and 12 unshared corners (STL, which
  // vtkSTLReader merges back to 4).
  const std::string obj = file("tetra.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n");
  std::string stl = "solid tetra\n";
  for (const char* facet :
    { "0 0 0  0 1 0  1 0 0", "0 0 0  1 0 0  0 0 1", "0 0 0  0 0 1  0 1 0", "1 0 0  0 1 0  0 0 1" })
  {
    std::istringstream corners(facet);
    stl += "facet normal 0 0 0\nouter loop\n";
    for (int c = 0; c < 3; ++c)
    {
      double x, y, z;
      corners >> x >> y >> z;
      stl += "vertex " + std::to_string(x) + " " + std::to_string(y) + " " + std::to_string(z) + "\n";
    }
    stl += "endloop\nendfacet\n";
  }
  const std::string stlFile = file("tetra.stl", stl + "endsolid tetra\n");
  for (const std::string& mesh : { obj, stlFile })
  {
    const fs::path out = folder / "tetra.vtk";
    fs::remove(out);
    const Result result = shadelab("shade " + mesh + " -s " + goodScene() + " -o " + out.string());
    EXPECT_EQ(result.exitCode, 0) << result.err;
    EXPECT_NE(result.out.find("  mesh: 4 vertices, 4 polygons and strips\n"), std::string::npos) << result.out;
    EXPECT_EQ(slurp(out).rfind("# vtk DataFile Version", 0), 0u) << mesh;
  }
}

TEST_F(Cli, RendersArraysToPng)
{
  // The golden bunny's ambient term is the constant ka La = (0.8, 0.62, 0.45) x 0.08. Drawn as
  // RGB with VTK's lighting off, every bunny pixel must be round(255 x that) = (16, 13, 9),
  // and every other pixel the background: nothing of VTK's own shading may creep in.
  if (std::string(XVFB_RUN).empty())
  {
    GTEST_SKIP() << NO_XVFB_REASON;
  }
  const std::string golden = shadelab::testing::sourcePath("data/golden/bunny_studio.vtp");
  const std::string png = (folder / "ambient.png").string();
  const std::string xvfb = std::string(XVFB_RUN) + " --auto-servernum ";
  const Result result = shadelab("render " + golden + " --array ambient --size 320x240 -s " +
      shadelab::testing::sourcePath("data/scenes/studio.json") + " -o " + png,
    xvfb);
  ASSERT_EQ(result.exitCode, 0) << result.err;
  EXPECT_EQ(result.out, "shadelab render: ambient of " + golden + " -> " + png + " (320x240)\n");
  vtkNew<vtkPNGReader> reader;
  reader->SetFileName(png.c_str());
  reader->Update();
  vtkImageData* image = reader->GetOutput();
  ASSERT_EQ(image->GetDimensions()[0], 320);
  ASSERT_EQ(image->GetDimensions()[1], 240);
  auto pixel = [&](int x, int y)
  {
    std::array<int, 3> rgb;
    for (int c = 0; c < 3; ++c)
    {
      rgb[c] = int(image->GetScalarComponentAsDouble(x, y, 0, c));
    }
    return rgb;
  };
  const std::array<int, 3> background = pixel(0, 0), ambient{ 16, 13, 9 };
  int bunnyPixels = 0;
  std::set<std::array<int, 3>> others;
  for (int y = 0; y < 240; ++y)
  {
    for (int x = 0; x < 320; ++x)
    {
      const auto rgb = pixel(x, y);
      bunnyPixels += rgb == ambient;
      if (rgb != ambient && rgb != background)
      {
        others.insert(rgb);
      }
    }
  }
  EXPECT_GT(bunnyPixels, 320 * 240 / 10);
  EXPECT_TRUE(others.empty()) << others.size() << " other colours";

  // A 1-component array through the colour map: a smooth ramp of many colours.
  const Result mapped = shadelab("render " + golden + " -a key_cos_incidence --size 320x240 -o " + png, xvfb);
  EXPECT_EQ(mapped.exitCode, 0) << mapped.err;
  reader->Modified();
  reader->Update();
  std::set<std::array<int, 3>> colours;
  for (int y = 0; y < 240; ++y)
  {
    for (int x = 0; x < 320; ++x)
    {
      colours.insert(pixel(x, y));
    }
  }
  EXPECT_GT(colours.size(), 200u);
}

TEST_F(Cli, RenderErrors)
{
  const std::string golden = shadelab::testing::sourcePath("data/golden/bunny_studio.vtp");
  const std::string png = (folder / "out.png").string();
  expectError("render " + golden + " -o " + png + " --size 10x10",
    "--size: '10x10' is not WIDTHxHEIGHT with each from 16 to 8192");
  expectError("render " + golden + " -o " + (folder / "out.jpg").string(),
    (folder / "out.jpg").string() + ": cannot write '.jpg' files here; use .png");
  const std::string nowhere = (folder / "no" / "out.png").string();
  expectError(
    "render " + golden + " -o " + nowhere, nowhere + ": the folder " + (folder / "no").string() + " does not exist");
  const Result noDisplay = shadelab("render " + golden + " -o " + png, "env -u DISPLAY ");
  EXPECT_EQ(noDisplay.exitCode, 1);
  EXPECT_EQ(noDisplay.err, "shadelab: no X display to render with: run the command under xvfb-run -a (package xvfb)\n");
  if (std::string(XVFB_RUN).empty())
  {
    GTEST_SKIP() << NO_XVFB_REASON << " (the errors that need a display)";
  }
  const Result unknown = shadelab("render " + golden + " -a glare -o " + png, std::string(XVFB_RUN) + " -a ");
  EXPECT_EQ(unknown.exitCode, 1);
  EXPECT_EQ(unknown.err,
    "shadelab: " + golden +
      ": has no point array 'glare'; it has: Normals, ambient, "
      "diffuse, specular, total, shading_flags, key_distance, key_cos_incidence, fill_cos_incidence, "
      "rim_spot_factor, rim_cos_incidence\n");
  EXPECT_FALSE(fs::exists(png));
}

/// Four unit squares in a 2 x 2 grid in the plane z = 0, each with four corners of its own,
/// with an array of these values at the corners (square by square, a tuple per corner).
template<typename Array>
void writeFourSquares(const std::string& file, const char* arrayName, int components, const std::vector<double>& values)
{
  vtkNew<vtkPolyData> squares;
  vtkNew<vtkPoints> points;
  vtkNew<vtkCellArray> quads;
  for (int square = 0; square < 4; ++square)
  {
    const double x = 1.2 * (square % 2), y = 1.2 * (square / 2);
    const vtkIdType first = points->GetNumberOfPoints();
    const vtkIdType corners[4] = { first, first + 1, first + 2, first + 3 };
    points->InsertNextPoint(x, y, 0);
    points->InsertNextPoint(x + 1, y, 0);
    points->InsertNextPoint(x + 1, y + 1, 0);
    points->InsertNextPoint(x, y + 1, 0);
    quads->InsertNextCell(4, corners);
  }
  vtkNew<Array> array;
  array->SetName(arrayName);
  array->SetNumberOfComponents(components);
  for (double value : values)
  {
    array->InsertNextValue(value);
  }
  squares->SetPoints(points);
  squares->SetPolys(quads);
  squares->GetPointData()->AddArray(array);
  vtkNew<vtkXMLPolyDataWriter> writer;
  writer->SetInputData(squares);
  writer->SetFileName(file.c_str());
  ASSERT_EQ(writer->Write(), 1) << file;
}

/// A tuple per square (of `components` values each) given to each of its four corners.
std::vector<double> atEachCorner(const std::vector<double>& squareValues, int components)
{
  std::vector<double> values;
  for (std::size_t square = 0; square < 4; ++square)
  {
    for (int corner = 0; corner < 4; ++corner)
    {
      values.insert(values.end(), squareValues.begin() + static_cast<long>(square) * components,
        squareValues.begin() + static_cast<long>(square + 1) * components);
    }
  }
  return values;
}

/// How many pixels of a PNG have each colour.
std::map<std::array<int, 3>, int> colourCounts(const std::string& png)
{
  vtkNew<vtkPNGReader> reader;
  reader->SetFileName(png.c_str());
  reader->Update();
  vtkImageData* image = reader->GetOutput();
  std::map<std::array<int, 3>, int> counts;
  for (int y = 0; y < image->GetDimensions()[1]; ++y)
  {
    for (int x = 0; x < image->GetDimensions()[0]; ++x)
    {
      std::array<int, 3> rgb;
      for (int c = 0; c < 3; ++c)
      {
        rgb[c] = int(image->GetScalarComponentAsDouble(x, y, 0, c));
      }
      ++counts[rgb];
    }
  }
  return counts;
}

TEST_F(Cli, RendersFlagsAsNamedCategories)
{
  // Each square's flags in a colour of Okabe and Ito's palette, in the order of the values:
  // 0 sky blue, 4 orange, 5 bluish green, 64 yellow; never as the grey levels (v, v, v) that
  // VTK draws an 8-bit array as by default.
  if (std::string(XVFB_RUN).empty())
  {
    GTEST_SKIP() << NO_XVFB_REASON;
  }
  const std::string mesh = (folder / "flags.vtp").string(), png = (folder / "flags.png").string();
  writeFourSquares<vtkUnsignedCharArray>(mesh, "sl_shading_flags", 1, atEachCorner({ 0, 4, 5, 64 }, 1));
  const Result result = shadelab(
    "render " + mesh + " -a sl_shading_flags --size 400x300 -o " + png, std::string(XVFB_RUN) + " --auto-servernum ");
  ASSERT_EQ(result.exitCode, 0) << result.err;
  EXPECT_EQ(result.out, "shadelab render: sl_shading_flags of " + mesh + " -> " + png + " (400x300)\n");
  const std::map<std::array<int, 3>, int> counts = colourCounts(png);
  const std::array<std::array<int, 3>, 4> palette{ { { 86, 180, 233 }, { 230, 159, 0 }, { 0, 158, 115 },
    { 240, 228, 66 } } };
  std::vector<int> areas;
  for (const std::array<int, 3>& colour : palette)
  {
    areas.push_back(counts.count(colour) ? counts.at(colour) : 0);
  }
  // Each square, a quarter of the mesh's part of the picture: the same area to a few pixels
  // (its swatch in the legend), and more than 2,000 pixels.
  for (int area : areas)
  {
    EXPECT_GT(area, 2000);
    EXPECT_NEAR(area, areas[0], 300);
  }
  for (int value : { 0, 4, 5, 64 })
  {
    EXPECT_EQ(counts.count({ value, value, value }), 0u) << value;
  }
  // Integers of a few values other than flags: categories too, named by their values.
  const std::string labels = (folder / "labels.vtp").string();
  writeFourSquares<vtkIntArray>(labels, "region", 1, atEachCorner({ 40, 30, 20, 10 }, 1));
  const Result regions =
    shadelab("render " + labels + " -a region --size 400x300 -o " + png, std::string(XVFB_RUN) + " --auto-servernum ");
  ASSERT_EQ(regions.exitCode, 0) << regions.err;
  const std::map<std::array<int, 3>, int> regionCounts = colourCounts(png);
  // Square 0 holds the largest value, 40, the palette's fourth colour; square 3 the first. The
  // legend is narrower than the flags', so the squares are larger; alike still.
  const int regionArea = regionCounts.count(palette[3]) ? regionCounts.at(palette[3]) : 0;
  EXPECT_GT(regionArea, 2000);
  for (std::size_t square = 1; square < 4; ++square)
  {
    const std::array<int, 3>& colour = palette[3 - square];
    EXPECT_NEAR(regionCounts.count(colour) ? regionCounts.at(colour) : 0, regionArea, 300) << square;
  }
}

TEST_F(Cli, RendersFlagValuesBeyondThePaletteInGrey)
{
  // Nine flag values, more than the palette's seven colours: the seven most frequent keep one
  // each, the other two share grey. Its colours are checked here (its words are text, which
  // only a reader can judge).
  if (std::string(XVFB_RUN).empty())
  {
    GTEST_SKIP() << NO_XVFB_REASON;
  }
  const std::string mesh = (folder / "many.vtp").string(), png = (folder / "many.png").string();
  // 9 values at the 16 corners; the least frequent, 200 and 201, are the ones left over.
  writeFourSquares<vtkUnsignedCharArray>(
    mesh, "shading_flags", 1, { 1, 1, 1, 1, 2, 2, 2, 8, 4, 4, 16, 16, 32, 64, 200, 201 });
  const Result result = shadelab(
    "render " + mesh + " --size 400x300 -o " + png + " -a shading_flags", std::string(XVFB_RUN) + " --auto-servernum ");
  ASSERT_EQ(result.exitCode, 0) << result.err;
  const std::map<std::array<int, 3>, int> counts = colourCounts(png);
  // Every palette colour is used (a swatch at least), and the grey of the other values.
  for (const std::array<int, 3>& colour : std::vector<std::array<int, 3>>{ { 86, 180, 233 }, { 230, 159, 0 },
         { 0, 158, 115 }, { 240, 228, 66 }, { 0, 114, 178 }, { 213, 94, 0 }, { 204, 121, 167 }, { 150, 150, 150 } })
  {
    EXPECT_GT(counts.count(colour) ? counts.at(colour) : 0, 20) << colour[0] << " " << colour[1] << " " << colour[2];
  }
  // Square 0 is all flag 1, the first colour.
  EXPECT_GT(counts.at({ 86, 180, 233 }), 2000);
}

TEST_F(Cli, RenderCountsTheVerticesDrawnClipped)
{
  // Squares of (0.5, 0.5, 0.5), (2, 0, 0), (0, 4.5, 0) and (NaN, 0, 0), four vertices each: 8
  // vertices above 1, the largest 4.5, so the exposure that brings them into range is 1/4.5 =
  // 0.22 to one digit, rounded down: 0.2.
  if (std::string(XVFB_RUN).empty())
  {
    GTEST_SKIP() << NO_XVFB_REASON;
  }
  const std::string mesh = (folder / "bright.vtp").string(), png = (folder / "bright.png").string();
  const double nan = std::numeric_limits<double>::quiet_NaN();
  writeFourSquares<vtkFloatArray>(mesh, "total", 3, atEachCorner({ 0.5, 0.5, 0.5, 2, 0, 0, 0, 4.5, 0, nan, 0, 0 }, 3));
  const std::string xvfb = std::string(XVFB_RUN) + " --auto-servernum ";
  const std::string head = "shadelab render: total of " + mesh + " -> " + png + " (400x300)\n";
  const std::string nonFinite = "  total: 4 of 16 vertices have a non-finite value, drawn black\n";
  const Result clipped = shadelab("render " + mesh + " --size 400x300 -o " + png, xvfb);
  ASSERT_EQ(clipped.exitCode, 0) << clipped.err;
  EXPECT_EQ(clipped.out,
    head +
      "  total: 8 of 16 vertices have a value above 1, drawn clipped; --exposure 0.2 scales them into range "
      "(and --srgb encodes linear values for the screen, as a renderer does)\n" +
      nonFinite);
  std::map<std::array<int, 3>, int> counts = colourCounts(png);
  using Colours = std::vector<std::array<int, 3>>;
  for (const std::array<int, 3>& square : Colours{ { 128, 128, 128 }, { 255, 0, 0 }, { 0, 255, 0 }, { 0, 0, 0 } })
  {
    EXPECT_GT(counts[square], 2000);
  }
  // At 0.2: round(255 x 0.1) = 26, round(255 x 0.4) = 102, round(255 x 0.9) = 230; nothing clipped.
  const Result exposed = shadelab("render " + mesh + " --size 400x300 --exposure 0.2 -o " + png, xvfb);
  ASSERT_EQ(exposed.exitCode, 0) << exposed.err;
  EXPECT_EQ(exposed.out, head + nonFinite);
  counts = colourCounts(png);
  for (const std::array<int, 3>& square : Colours{ { 26, 26, 26 }, { 102, 0, 0 }, { 0, 230, 0 } })
  {
    EXPECT_GT(counts[square], 2000);
  }
  // With --srgb, the count without the advice to use it.
  const Result encoded = shadelab("render " + mesh + " --size 400x300 --srgb -o " + png, xvfb);
  EXPECT_EQ(encoded.out,
    head + "  total: 8 of 16 vertices have a value above 1, drawn clipped; --exposure 0.2 scales them into range\n" +
      nonFinite);
}

TEST_F(Cli, RendersEightBitColoursAsTheyAre)
{
  // An 8-bit RGB array (a scan's colours) is fractions of 255: drawn as its bytes, nothing
  // clipped; at --exposure 2, every square with a component of 128 or more (2 x 128 / 255 > 1)
  // is, and the largest value, 255/255 = 1, gives back an exposure of 1.
  if (std::string(XVFB_RUN).empty())
  {
    GTEST_SKIP() << NO_XVFB_REASON;
  }
  const std::string mesh = (folder / "rgb.vtp").string(), png = (folder / "rgb.png").string();
  writeFourSquares<vtkUnsignedCharArray>(
    mesh, "RGB", 3, atEachCorner({ 255, 0, 0, 0, 128, 0, 10, 20, 30, 255, 255, 255 }, 3));
  const std::string xvfb = std::string(XVFB_RUN) + " --auto-servernum ";
  const std::string head = "shadelab render: RGB of " + mesh + " -> " + png + " (400x300)\n";
  const Result asTheyAre = shadelab("render " + mesh + " -a RGB --size 400x300 -o " + png, xvfb);
  ASSERT_EQ(asTheyAre.exitCode, 0) << asTheyAre.err;
  EXPECT_EQ(asTheyAre.out, head);
  std::map<std::array<int, 3>, int> counts = colourCounts(png);
  using Colours = std::vector<std::array<int, 3>>;
  for (const std::array<int, 3>& square : Colours{ { 255, 0, 0 }, { 0, 128, 0 }, { 10, 20, 30 }, { 255, 255, 255 } })
  {
    EXPECT_GT(counts[square], 2000);
  }
  const Result doubled = shadelab("render " + mesh + " -a RGB --exposure 2 --srgb --size 400x300 -o " + png, xvfb);
  EXPECT_EQ(doubled.out,
    head + "  RGB: 12 of 16 vertices have a value above 1, drawn clipped; --exposure 1 scales them into range\n");
}

TEST_F(Cli, RenderCountsTheGoldenBunnysBrightVertices)
{
  // The studio's total goes above 1 where the key light's highlight is: counted here from the
  // file. Its largest component, 1.2691 (the README's Python example prints it), gives 1/1.2691 =
  // 0.79, so 0.7; at that exposure nothing is clipped.
  if (std::string(XVFB_RUN).empty())
  {
    GTEST_SKIP() << NO_XVFB_REASON;
  }
  const std::string golden = shadelab::testing::sourcePath("data/golden/bunny_studio.vtp");
  vtkNew<vtkXMLPolyDataReader> reader;
  reader->SetFileName(golden.c_str());
  reader->Update();
  vtkDataArray* total = reader->GetOutput()->GetPointData()->GetArray("total");
  int above = 0;
  double largest = 0;
  for (vtkIdType i = 0; i < total->GetNumberOfTuples(); ++i)
  {
    const double* rgb = total->GetTuple3(i);
    above += std::max({ rgb[0], rgb[1], rgb[2] }) > 1;
    largest = std::max({ largest, rgb[0], rgb[1], rgb[2] });
  }
  ASSERT_GT(above, 0);
  ASSERT_NEAR(largest, 1.2691, 1e-4);
  const std::string png = (folder / "total.png").string(), xvfb = std::string(XVFB_RUN) + " --auto-servernum ";
  const std::string head = "shadelab render: total of " + golden + " -> " + png + " (320x240)\n";
  const Result clipped = shadelab("render " + golden + " --size 320x240 -o " + png, xvfb);
  EXPECT_EQ(clipped.out,
    head + "  total: " + std::to_string(above) +
      " of 35947 vertices have a value above 1, "
      "drawn clipped; --exposure 0.7 scales them into range (and --srgb encodes linear values for the screen, as a "
      "renderer does)\n");
  const Result exposed = shadelab("render " + golden + " --size 320x240 --exposure 0.7 -o " + png, xvfb);
  EXPECT_EQ(exposed.exitCode, 0) << exposed.err;
  EXPECT_EQ(exposed.out, head);
}

TEST_F(Cli, RenderExposureErrors)
{
  const std::string golden = shadelab::testing::sourcePath("data/golden/bunny_studio.vtp");
  const std::string png = (folder / "out.png").string();
  for (const char* exposure : { "0", "-1", "inf", "nan", "bright" })
  {
    const Result result = shadelab("render " + golden + " -o " + png + " --exposure " + exposure);
    EXPECT_EQ(result.exitCode, 2) << exposure;
    EXPECT_EQ(result.err,
      "--exposure: '" + std::string(exposure) +
        "' is not a finite number > 0\n"
        "Run with --help for more information.\n");
  }
  if (std::string(XVFB_RUN).empty())
  {
    GTEST_SKIP() << NO_XVFB_REASON << " (the errors that need a display)";
  }
  const Result mapped = shadelab(
    "render " + golden + " -a key_cos_incidence --exposure 2 -o " + png, std::string(XVFB_RUN) + " --auto-servernum ");
  EXPECT_EQ(mapped.exitCode, 1);
  EXPECT_EQ(mapped.err,
    "shadelab: --exposure scales an array drawn as RGB colours; 'key_cos_incidence' has 1 "
    "component, drawn through a colour map that spans its values\n");
  EXPECT_FALSE(fs::exists(png));
}

TEST_F(Cli, RenderKeepsItsLegendInsideThePicture)
{
  // Labels as long as "-4.66e5": at the default size and at the smallest sensible one, the
  // picture's edge (3 pixels wide) is the background all round, so no label runs off it.
  if (std::string(XVFB_RUN).empty())
  {
    GTEST_SKIP() << NO_XVFB_REASON;
  }
  const std::string mesh = (folder / "big.vtp").string(), png = (folder / "big.png").string();
  writeFourSquares<vtkFloatArray>(mesh, "big", 1, atEachCorner({ -466000, 1000, 31900, 466000 }, 1));
  for (const std::string& size : { "800x600", "320x240", "160x120" })
  {
    const Result result = shadelab(
      "render " + mesh + " -a big --size " + size + " -o " + png, std::string(XVFB_RUN) + " --auto-servernum ");
    ASSERT_EQ(result.exitCode, 0) << result.err;
    vtkNew<vtkPNGReader> reader;
    reader->SetFileName(png.c_str());
    reader->Update();
    vtkImageData* image = reader->GetOutput();
    const int width = image->GetDimensions()[0], height = image->GetDimensions()[1];
    auto pixel = [&](int x, int y)
    {
      std::array<int, 3> rgb;
      for (int c = 0; c < 3; ++c)
      {
        rgb[c] = int(image->GetScalarComponentAsDouble(x, y, 0, c));
      }
      return rgb;
    };
    const std::array<int, 3> background = pixel(0, 0);
    EXPECT_NEAR(background[0], 0.16 * 255, 1); // the renderer's background
    int notBackground = 0;
    for (int y = 0; y < height; ++y)
    {
      for (int x = 0; x < width; ++x)
      {
        const bool edge = x < 3 || y < 3 || x >= width - 3 || y >= height - 3;
        notBackground += edge && pixel(x, y) != background;
      }
    }
    EXPECT_EQ(notBackground, 0) << size;
  }
}

TEST_F(Cli, BenchmarkSetsInterreflectionAgainstAmbientOcclusion)
{
  // Both runs in one process, and their ratios, the quotients of the rows printed (to the
  // rows' two decimals); the scene option names what it belongs to.
  const std::string studio = shadelab::testing::sourcePath("data/scenes/studio.json");
  const Result result =
    run(shadelab::testing::benchExecutable(), "--interreflection " + goodMesh() + " -s " + studio + " --repeats 1");
  ASSERT_EQ(result.exitCode, 0) << result.err;
  const std::regex row("  (ambient occlusion, 64 rays per vertex|interreflection, 3 bounces of 64 gather rays) +"
                       "([0-9.]+) s +([0-9.]+) GB peak\n");
  std::vector<double> seconds, peaks;
  for (auto match = std::sregex_iterator(result.out.begin(), result.out.end(), row); match != std::sregex_iterator();
       ++match)
  {
    seconds.push_back(std::stod((*match)[2]));
    peaks.push_back(std::stod((*match)[3]));
  }
  ASSERT_EQ(seconds.size(), 2u) << result.out;
  std::smatch ratios;
  ASSERT_TRUE(std::regex_search(result.out, ratios,
    std::regex("time ([0-9.]+) \\(target at most 2\\), peak memory ([0-9.]+) \\(target at most 1.5\\)")))
    << result.out;
  const double half = 0.005; // the rows' rounding
  EXPECT_GE(std::stod(ratios[1]) + half, (seconds[1] - half) / (seconds[0] + half)) << result.out;
  EXPECT_LE(std::stod(ratios[1]) - half, (seconds[1] + half) / (seconds[0] - half)) << result.out;
  EXPECT_GE(std::stod(ratios[2]) + half, (peaks[1] - half) / (peaks[0] + half)) << result.out;
  EXPECT_LE(std::stod(ratios[2]) - half, (peaks[1] + half) / (peaks[0] - half)) << result.out;
  const Result alone = run(shadelab::testing::benchExecutable(), "-s " + studio);
  EXPECT_EQ(alone.exitCode, 1);
  EXPECT_EQ(alone.err, "shadelab-bench: --scene is the scene of --end-to-end or --interreflection: give one of them\n");
}

TEST_F(Cli, BenchmarkTableAgreesWithItsBaseline)
{
  // A small run: the table's rows, and vtkArrayCalculator's result for the same expression
  // equal to ShadeLab's within float32 rounding in every case that has one.
  const fs::path csv = folder / "bench.csv";
  const Result result =
    run(shadelab::testing::benchExecutable(), "--sizes 3k --no-bunny --repeats 1 --csv " + csv.string());
  ASSERT_EQ(result.exitCode, 0) << result.err;
  std::istringstream lines(slurp(csv));
  std::string header;
  std::getline(lines, header);
  EXPECT_EQ(header,
    "vertices,mesh,case,first ms,ms,Mvertices/s,x floor,floor ms,calculator ms,"
    "x faster,max |diff|,peak MB,arrays MB");
  int rows = 0, compared = 0;
  for (std::string line; std::getline(lines, line); ++rows)
  {
    // Fields: the case name is quoted when it has a comma.
    std::vector<std::string> fields;
    for (std::size_t at = 0; at < line.size();)
    {
      const bool quoted = line[at] == '"';
      const std::size_t end = quoted ? line.find('"', at + 1) + 1 : line.find(',', at);
      fields.push_back(line.substr(at, end == std::string::npos ? std::string::npos : end - at));
      at = end == std::string::npos ? line.size() : end + 1;
    }
    ASSERT_EQ(fields.size(), 13u) << line;
    EXPECT_EQ(fields[0], "3027"); // a UV sphere of 55 meridians, 55 rings and 2 poles
    EXPECT_GT(std::stod(fields[4]), 0.0);
    if (!fields[10].empty()) // cases without a calculator expression leave it empty
    {
      EXPECT_LT(std::stod(fields[10]), 1e-5) << line;
      ++compared;
    }
  }
  EXPECT_EQ(rows, 9);
  // Including the row shaded with the methods a tolerance of 1e-4 chose; not the material from
  // arrays, which vtkArrayCalculator's expression does not have.
  EXPECT_EQ(compared, 7);
}

TEST_F(Cli, AnObjIsShadedWithItsOwnMaterialsAndSaysSo)
{
  const std::string folderOfScene = shadelab::testing::sourcePath("data/scenes/still_life/");
  const Result own = shadelab("shade " + folderOfScene + "still_life.obj --scene " + folderOfScene +
    "still_life.json -o " + (folder / "own.vtp").string());
  ASSERT_EQ(own.exitCode, 0) << own.err;
  EXPECT_NE(own.out.find("  material: the mesh's own, part by part (3 parts: floor, ball, box)\n"), std::string::npos)
    << own.out;
  EXPECT_EQ(own.err, "");

  // The same parts beside an MTL whose texture is missing, under a scene with a material.
  fs::copy_file(folderOfScene + "still_life.obj", folder / "still_life.obj");
  fs::copy_file(folderOfScene + "still_life.mtl", folder / "still_life.mtl");
  const std::string scene =
    file("grey.json", R"({ "material": { "kd": 0.5 }, "lights": [ { "type": "distant", "direction": [0, -1, 0] } ] })");
  const Result grey = shadelab("shade still_life.obj --scene grey.json -o grey.vtp", "cd " + folder.string() + " && ");
  ASSERT_EQ(grey.exitCode, 0) << grey.err;
  EXPECT_NE(grey.out.find("  material: the scene's, in place of the mesh's own (3 parts: floor, ball, box)\n"),
    std::string::npos)
    << grey.out;
  EXPECT_EQ(grey.err,
    "shadelab: warning: still_life.obj: material 'floor' names the texture " + (folder / "checker.png").string() +
      ", which neither VTK nor OpenImageIO could read (no such file): shaded with its diffuse colour alone\n");
}

// An OpenEXR map read before the mesh (the scene is read first) and an OpenEXR texture read
// with the mesh, in the reader's forked child: the child has none of the parent's threads, and
// when the map's read had started OpenEXR's thread pool, the texture's read waited for them
// until the reader's limit (130 s). The bundled map serves as the texture too; its texels above
// 1 are clamped, with a warning.
TEST_F(Cli, AnEnvironmentMapInOpenExrBeforeAnExrTexture)
{
  const std::string folderOfScene = shadelab::testing::sourcePath("data/scenes/still_life/");
  const std::string map = shadelab::testing::sourcePath("data/envmaps/venice_sunset_1k.exr");
  fs::copy_file(folderOfScene + "still_life.obj", folder / "still_life.obj");
  fs::copy_file(map, folder / "texture.exr");
  std::string mtl = slurp(folderOfScene + "still_life.mtl");
  mtl.replace(mtl.find("checker.png"), 11, "texture.exr");
  file("still_life.mtl", mtl);
  file("map.json",
    R"({ "material": { "kd": 0.5, "ks": 0 }, "lights": [ { "type": "environment", "file": ")" + map +
      R"(", "estimator": "sh" } ] })");
  const Result run = shadelab("shade still_life.obj -s map.json -o out.vtp", "cd " + folder.string() + " && ");
  ASSERT_EQ(run.exitCode, 0) << run.err;
  const std::string clamped = "shadelab: warning: still_life.obj: part 'floor': its texture has ";
  EXPECT_EQ(run.err.substr(0, clamped.size()), clamped) << run.err;
  EXPECT_NE(run.err.find(" outside [0, 1] (as high as "), std::string::npos) << run.err;
}

// The guide's open box: one layer of walls whose normals point out, two-sided, lit by a lamp
// that lights no point of the ceiling. Both sides are shaded and gather: the ceiling's light is
// the walls' alone, and the white back wall is redder beside the red wall than beside the green.
TEST_F(Cli, TheOpenBoxIsLitInsideByItsOwnWalls)
{
  const std::string box = shadelab::testing::sourcePath("data/scenes/open_box/");
  const std::string out = (folder / "open_box.vtp").string();
  const Result run =
    shadelab("shade " + box + "open_box.vtp -s " + box + "open_box.json -a diffuse,indirect -o " + out);
  ASSERT_EQ(run.exitCode, 0) << run.err;
  EXPECT_NE(run.out.find("  interreflection: both sides shaded (front_diffuse: the diffuse term on the side the "
                         "normals point to): 4 bounces from 'front_diffuse' and 'back_diffuse', 256 gather rays per "
                         "vertex on each side"),
    std::string::npos)
    << run.out;
  vtkNew<vtkXMLPolyDataReader> reader;
  reader->SetFileName(out.c_str());
  reader->Update();
  vtkPolyData* shaded = reader->GetOutput();
  vtkDataArray* diffuse = shaded->GetPointData()->GetArray("diffuse");
  vtkDataArray* indirect = shaded->GetPointData()->GetArray("indirect");
  vtkDataArray* normals = shaded->GetPointData()->GetArray("Normals");
  int ceiling = 0;
  glm::dvec3 besideRed(0.0), besideGreen(0.0);
  for (vtkIdType i = 0; i < shaded->GetNumberOfPoints(); ++i)
  {
    const double* p = shaded->GetPoint(i);
    if (p[1] == 1.0 && normals->GetComponent(i, 1) == 1.0) // the ceiling (its normals point out of the box)
    {
      ++ceiling;
      ASSERT_EQ(diffuse->GetComponent(i, 0), indirect->GetComponent(i, 0)) << i;
      ASSERT_GT(indirect->GetComponent(i, 1), 0.01) << i;
    }
    const bool backWall = normals->GetComponent(i, 2) == -1.0;
    if (backWall && p[1] > 0.5 && (p[0] < 0.1 || p[0] > 0.9)) // its upper corners
    {
      (p[0] < 0.1 ? besideRed : besideGreen) += glm::make_vec3(indirect->GetTuple3(i));
    }
  }
  EXPECT_EQ(ceiling, 33 * 33);
  EXPECT_GT(besideRed.r / besideRed.g, 1.5 * besideGreen.r / besideGreen.g);
}

TEST_F(Cli, AGltfFilesMaterialsShadeTheVtkPbrModelPartByPart)
{
  const std::string scene = file("pbr.json", R"({ "model": "vtk_pbr",
    "viewer": { "position": [0.5, 1.3, 1.8], "focal_point": [0, 0.5, 0] },
    "lights": [ { "name": "bulb", "type": "point", "position": [-1.2, 1.6, 0.8], "intensity": 4,
      "attenuation": { "model": "vtk", "constant": 1, "linear": 0, "quadratic": 0 } } ] })");
  const std::string output = (folder / "lamps.vtp").string();
  const Result lamps = shadelab("shade " + shadelab::testing::sourcePath("data/scenes/lamps/lamps.gltf") + " -s " +
    scene + " -o " + output + " --arrays all");
  ASSERT_EQ(lamps.exitCode, 0) << lamps.err;
  EXPECT_NE(lamps.out.find("  material: the mesh's own, part by part (2 parts: ball, floor)\n"), std::string::npos)
    << lamps.out;
  // Each vertex's D is GGX's at its own part's roughness (the ball's 0.35, the floor's 0.9).
  vtkNew<vtkXMLPolyDataReader> reader;
  reader->SetFileName(output.c_str());
  reader->Update();
  vtkPointData* arrays = reader->GetOutput()->GetPointData();
  vtkDataArray* roughness = arrays->GetArray("material_roughness");
  vtkDataArray* d = arrays->GetArray("bulb_ggx_d");
  vtkDataArray* nDotH = arrays->GetArray("bulb_n_dot_h");
  ASSERT_TRUE(roughness && d && nDotH);
  std::set<float> seen;
  for (vtkIdType i = 0; i < d->GetNumberOfTuples(); ++i)
  {
    const double r = roughness->GetComponent(i, 0), alpha2 = std::pow(r, 4.0);
    const double cosine = std::clamp(nDotH->GetComponent(i, 0), 1e-5, 1.0);
    const double denominator = cosine * cosine * (alpha2 - 1) + 1;
    EXPECT_NEAR(d->GetComponent(i, 0), alpha2 / (M_PI * denominator * denominator), 1e-3 * d->GetComponent(i, 0))
      << "vertex " << i;
    seen.insert(float(r));
  }
  EXPECT_EQ(seen, (std::set<float>{ 0.35f, 0.9f }));

  // A ball of roughness 0 and a floor with a normal texture: both said as the file is read, and
  // the roughness refused by the vtk_pbr model, as the mesh's own material.
  for (const char* resource : { "lamps.bin", "checker.png" })
  {
    fs::copy_file(shadelab::testing::sourcePath(std::string("data/scenes/lamps/") + resource), folder / resource);
  }
  nlohmann::json gltf = nlohmann::json::parse(slurp(shadelab::testing::sourcePath("data/scenes/lamps/lamps.gltf")));
  gltf["materials"][1]["pbrMetallicRoughness"]["roughnessFactor"] = 0;
  gltf["materials"][0]["normalTexture"] = { { "index", 0 } };
  gltf["materials"][0]["emissiveTexture"] = { { "index", 0 } };
  const std::string mirror = file("mirror.gltf", gltf.dump(1));
  const Result refused = shadelab("shade " + mirror + " -s " + scene + " -o " + (folder / "mirror.vtp").string());
  EXPECT_EQ(refused.exitCode, 1);
  EXPECT_EQ(refused.err,
    "shadelab: " + mirror +
      ": the mesh's own materials, part 'ball': array 'material_roughness', vertex 0: it is 0, outside (0, 1] (at 0, "
      "VTK's GGX distribution is 0/0 in the mirror direction)\n");
  EXPECT_FALSE(fs::exists(folder / "mirror.vtp"));
  // In the lecture model it shades, and the file's reading says what the other model refuses.
  const Result lecture = shadelab("shade " + mirror + " -o " + (folder / "lecture.vtp").string());
  ASSERT_EQ(lecture.exitCode, 0) << lecture.err;
  EXPECT_EQ(lecture.err,
    "shadelab: warning: " + mirror +
      ": material 'floor' has normalTexture and emissiveTexture, which ShadeLab does not read: shaded without them\n"
      "shadelab: warning: " +
      mirror +
      ": material 'ball' has roughnessFactor 0, which the vtk_pbr model would refuse (VTK's GGX distribution is 0/0 "
      "in the mirror direction): a vtk_pbr scene needs a material of its own for this file\n");

  // An OBJ's materials are the lecture model's: the vtk_pbr model shades it with its defaults, and says so.
  const std::string stillLife = shadelab::testing::sourcePath("data/scenes/still_life/still_life.obj");
  const Result obj = shadelab("shade " + stillLife + " -s " + scene + " -o " + (folder / "obj.vtp").string());
  ASSERT_EQ(obj.exitCode, 0) << obj.err;
  EXPECT_NE(obj.out.find("  material: the vtk_pbr model's defaults (the file's materials are not metallic-roughness "
                         "ones: an MTL file's are the lecture model's), in place of the mesh's own (3 parts: floor, "
                         "ball, box)\n"),
    std::string::npos)
    << obj.out;
}

TEST_F(Cli, AGltfIsLitByItsOwnLightsAndABrokenOneIsRefused)
{
  const Result lamps = shadelab("shade " + shadelab::testing::sourcePath("data/scenes/lamps/lamps.gltf") + " -o " +
    (folder / "lamps.vtp").string() + " --arrays '*_cos_incidence'");
  ASSERT_EQ(lamps.exitCode, 0) << lamps.err;
  EXPECT_NE(lamps.out.find("  scene: the file's own lights (lecture model, 3 lights)\n"), std::string::npos)
    << lamps.out;
  for (const char* light : { "bulb", "spot", "sky" })
  {
    EXPECT_NE(lamps.out.find(std::string("    ") + light + "_cos_incidence"), std::string::npos) << light;
  }
  // A --scene's lights win over the file's.
  const Result scene = shadelab("shade " + shadelab::testing::sourcePath("data/scenes/lamps/lamps.gltf") + " -s " +
    goodScene() + " -o " + (folder / "sun.vtp").string() + " --arrays sun_diffuse");
  ASSERT_EQ(scene.exitCode, 0) << scene.err;
  EXPECT_NE(
    scene.out.find("  scene: " + (folder / "scene.json").string() + " (lecture model, 1 light)\n"), std::string::npos)
    << scene.out;

  // An extension that changes the look, which ShadeLab does not read, is said.
  fs::copy_file(shadelab::testing::sourcePath("data/scenes/lamps/lamps.bin"), folder / "lamps.bin");
  fs::copy_file(shadelab::testing::sourcePath("data/scenes/lamps/checker.png"), folder / "checker.png");
  std::string gltf = slurp(shadelab::testing::sourcePath("data/scenes/lamps/lamps.gltf"));
  gltf.replace(gltf.find("\"extensionsUsed\": ["), 19,
    "\"extensionsRequired\": [\"KHR_texture_transform\"], \"extensionsUsed\": [\"KHR_texture_transform\", ");
  const std::string transformed = file("transformed.gltf", gltf);
  const Result extension = shadelab("shade " + transformed + " -o " + (folder / "t.vtp").string());
  ASSERT_EQ(extension.exitCode, 0) << extension.err;
  EXPECT_EQ(extension.err,
    "shadelab: warning: " + transformed +
      ": requires the extension KHR_texture_transform, which ShadeLab does not read: what it changes is not shaded\n");

  // Double-sided materials: both sides where every part's is, and one side, said, where some are.
  std::string doubleSided = slurp(shadelab::testing::sourcePath("data/scenes/lamps/lamps.gltf"));
  const std::size_t materials = doubleSided.find("\"materials\"");
  for (const char* name : { "\"name\": \"ball\"", "\"name\": \"floor\"" })
  {
    doubleSided.insert(doubleSided.find(name, materials), "\"doubleSided\": true, ");
  }
  const Result bothSides =
    shadelab("shade " + file("both_sides.gltf", doubleSided) + " -o " + (folder / "b.vtp").string());
  ASSERT_EQ(bothSides.exitCode, 0) << bothSides.err;
  EXPECT_NE(bothSides.out.find("  material: the mesh's own, part by part (2 parts: ball, floor), two-sided (every part "
                               "is)\n"),
    std::string::npos)
    << bothSides.out;
  doubleSided.erase(doubleSided.find("\"doubleSided\": true, "), 21);
  const std::string mixed = file("mixed_sides.gltf", doubleSided);
  const Result oneSide = shadelab("shade " + mixed + " -o " + (folder / "m.vtp").string());
  ASSERT_EQ(oneSide.exitCode, 0) << oneSide.err;
  EXPECT_EQ(oneSide.err,
    "shadelab: warning: " + mixed +
      ": part 'ball' is double-sided and the others are not: a mesh is shaded on one side or on both, not part by "
      "part, so its own materials shade every part on the side of its normals (a scene's material with "
      "\"two_sided\": true shades all on both, in its own colours; the vtk_pbr model shades all on both, as VTK's PBR "
      "shader does)\n");
  EXPECT_NE(oneSide.out.find("  material: the mesh's own, part by part (2 parts: ball, floor)\n"), std::string::npos)
    << oneSide.out;
  // A doubleSided that is not a boolean, which VTK's importer takes for false, is said.
  doubleSided.replace(doubleSided.find("\"doubleSided\": true"), 19, "\"doubleSided\": \"yes\"");
  const std::string yes = file("yes_sided.gltf", doubleSided);
  const Result notBoolean = shadelab("shade " + yes + " -o " + (folder / "y.vtp").string());
  ASSERT_EQ(notBoolean.exitCode, 0) << notBoolean.err;
  EXPECT_EQ(notBoolean.err,
    "shadelab: warning: " + yes +
      ": material 'ball' gives doubleSided as \"yes\", not true or false: VTK's importer reads it as false, so its "
      "parts are one-sided\n");

  const std::string output = (folder / "out.vtp").string();
  const std::string empty =
    file("empty.gltf", R"({ "asset": { "version": "2.0" }, "scene": 0, "scenes": [ { "nodes": [] } ] })");
  expectError("shade " + empty + " -o " + output,
    empty + ": the glTF file has no geometry that VTK's importer reads (no mesh primitives)");
  const std::string broken = file("broken.gltf", "not json");
  expectError("shade " + broken + " -o " + output,
    broken + ": VTK's glTF importer could not read it: Error loading model metadata");
  EXPECT_FALSE(fs::exists(output));
}

TEST_F(Cli, HelpAndUsageErrors)
{
  const Result help = shadelab("shade --help");
  EXPECT_EQ(help.exitCode, 0);
  EXPECT_NE(help.out.find("--arrays"), std::string::npos);
  EXPECT_NE(help.out.find("Reads .vtp, .pvtp, .vtk, .ply, .stl, .obj (with its MTL file's materials and textures), "
                          ".gltf and .glb"),
    std::string::npos);
  const Result featureAngle = shadelab("shade " + goodMesh() + " -o out.vtp --feature-angle 200");
  EXPECT_EQ(featureAngle.exitCode, 2);
  EXPECT_EQ(
    featureAngle.err, "--feature-angle: Value 200 not in range 0 to 180\nRun with --help for more information.\n");
  const Result threads = shadelab("shade " + goodMesh() + " -s " + goodScene() + " -o out.vtp --threads 1000");
  EXPECT_EQ(threads.exitCode, 2);
  EXPECT_EQ(threads.err, "--threads: Value 1000 not in range 0 to 256\nRun with --help for more information.\n");
  const Result arrays = shadelab("arrays --scene " + goodScene());
  EXPECT_EQ(arrays.exitCode, 0);
  EXPECT_NE(arrays.out.find("  sun_r_dot_v                  1  light 'sun': r.v"), std::string::npos) << arrays.out;
}
}

namespace
{
// Images are read by OpenImageIO in a module loaded at the first image (ImageFile.h): a command
// without one runs without the module, and one that needs it says why it cannot have it.
TEST_F(Cli, TheImageModuleIsLoadedOnlyToReadAnImage)
{
  const std::string mesh = goodMesh(), out = (folder / "out.vtp").string();
  const std::string map = shadelab::testing::sourcePath("data/envmaps/venice_sunset_1k.hdr");
  const std::string nowhere = (folder / "nowhere" / "libshadelab_images.so").string();
  const Result plain =
    shadelab("shade " + mesh + " -s " + goodScene() + " -o " + out, "SHADELAB_IMAGE_MODULE=" + nowhere + " ");
  EXPECT_EQ(plain.exitCode, 0) << plain.err;
  const Result missing =
    shadelab("shade " + mesh + " --envmap " + map + " -o " + out, "SHADELAB_IMAGE_MODULE=" + nowhere + " ");
  EXPECT_EQ(missing.exitCode, 1);
  EXPECT_EQ(missing.err,
    "shadelab: --envmap: SHADELAB_IMAGE_MODULE names " + nowhere +
      ", which does not exist: give the path of ShadeLab's libshadelab_images.so, or unset it\n");
  const std::string notAModule = file("text.so", "not a module\n");
  const Result unloadable =
    shadelab("shade " + mesh + " --envmap " + map + " -o " + out, "SHADELAB_IMAGE_MODULE=" + notAModule + " ");
  EXPECT_EQ(unloadable.exitCode, 1);
  EXPECT_EQ(unloadable.err.substr(0, 120),
    ("shadelab: --envmap: ShadeLab's image module " + notAModule + " does not load (").substr(0, 120));
  EXPECT_NE(
    unloadable.err.find(
      "): is it ShadeLab's libshadelab_images.so, and is OpenImageIO installed (Debian 12: libopenimageio2.4)?\n"),
    std::string::npos)
    << unloadable.err;
}

TEST_F(Cli, EnvironmentMapOption)
{
  const std::string mesh = goodMesh(), out = (folder / "out.vtp").string();
  const std::string missing = (folder / "none.hdr").string();
  expectError("shade " + mesh + " --envmap " + missing + " -o " + out, "--envmap: " + missing + ": no such file");
  const std::string square = file("square.ppm", "P3\n3 2\n255\n0 0 0 1 1 1 2 2 2\n3 3 3 4 4 4 5 5 5\n");
  expectError("shade " + mesh + " --envmap " + square + " -o " + out,
    "--envmap: " + square + ": an equirectangular map must be twice as wide as it is high; this one is 3x2");
  EXPECT_FALSE(fs::exists(out));
  const Result noMap = shadelab("shade " + mesh + " --envmap-rotation 30 -s " + goodScene() + " -o " + out);
  EXPECT_EQ(noMap.exitCode, 2);
  EXPECT_EQ(noMap.err, "--envmap-rotation requires --envmap\nRun with --help for more information.\n");
  const std::string named = file("named.json", R"({ "lights": [ { "name": "envmap", "type": "ambient" } ] })");
  expectError("shade " + mesh + " -s " + named + " --envmap " +
      shadelab::testing::sourcePath("data/envmaps/venice_sunset_1k.hdr") + " -o " + out,
    "--envmap: " + named + " already has a light named 'envmap', the name --envmap gives its light: rename that light");

  // The map alone lights the bunny; its arrays are listed in the summary.
  const Result shaded =
    shadelab("shade " + mesh + " --envmap " + shadelab::testing::sourcePath("data/envmaps/venice_sunset_1k.hdr") +
      " --envmap-estimator monte_carlo --envmap-samples 16 -a all -o " + out);
  EXPECT_EQ(shaded.exitCode, 0) << shaded.err;
  EXPECT_NE(shaded.out.find("scene: default material and viewer + --envmap "), std::string::npos) << shaded.out;
  EXPECT_NE(shaded.out.find("envmap_irradiance_std_error"), std::string::npos) << shaded.out;
  EXPECT_TRUE(fs::exists(out));

  // With --shadows the map casts the mesh's shadows, its rays drawn as --envmap-directions says.
  const Result shadowed =
    shadelab("shade " + mesh + " --envmap " + shadelab::testing::sourcePath("data/envmaps/venice_sunset_1k.hdr") +
      " --envmap-directions mis --envmap-samples 16 --shadows -o " + out);
  EXPECT_EQ(shadowed.exitCode, 0) << shadowed.err;
  EXPECT_NE(shadowed.out.find("    envmap_visibility            1 "), std::string::npos) << shadowed.out;
  EXPECT_NE(shadowed.out.find("    envmap_visibility_std_error  1 "), std::string::npos) << shadowed.out;
  EXPECT_NE(shadowed.out.find("rays (16 per vertex)"), std::string::npos) << shadowed.out;
  // --envmap-samples auto takes the count from --tolerance, which must be given.
  expectError("shade " + mesh + " --envmap " + shadelab::testing::sourcePath("data/envmaps/venice_sunset_1k.hdr") +
      " --envmap-samples auto -o " + out,
    "--envmap " + shadelab::testing::sourcePath("data/envmaps/venice_sunset_1k.hdr") +
      ": /lights/0/samples: \"auto\" takes the count "
      "of light 'envmap' from a tolerance: give one (shadelab shade --tolerance, the filter's Tolerance), or a number "
      "of "
      "samples");
  const Result badDirections = shadelab("shade " + mesh + " --envmap " +
    shadelab::testing::sourcePath("data/envmaps/venice_sunset_1k.hdr") + " --envmap-directions sun -o " + out);
  EXPECT_EQ(badDirections.exitCode, 2);
  EXPECT_EQ(badDirections.err,
    "--envmap-directions: sun not in {luminance,cosine,mis}\nRun with --help for more information.\n");
}
}

namespace
{
TEST_F(Cli, ColorByTakesTheMaterialsColourFromAnArray)
{
  // The head scan's own colours by --color-by are the scene's "kd": {"array": "RGB"}, bit for bit.
  const std::string head = shadelab::testing::sourcePath("data/meshes/head_scan.ply");
  const std::string scene = shadelab::testing::sourcePath("data/scenes/scan_colors.json");
  const std::string byScene = (folder / "by_scene.vtp").string(), byOption = (folder / "by_option.vtp").string();
  ASSERT_EQ(shadelab("shade " + head + " -s " + scene + " -o " + byScene).exitCode, 0);
  std::ifstream sceneFile(scene);
  std::string text((std::istreambuf_iterator<char>(sceneFile)), std::istreambuf_iterator<char>());
  const std::string named = R"("kd": { "array": "RGB" })";
  ASSERT_NE(text.find(named), std::string::npos);
  text.replace(text.find(named), named.size(), R"("kd": 0.5)");
  const std::string uniform = (folder / "uniform.json").string();
  std::ofstream(uniform) << text;
  const Result colored = shadelab("shade " + head + " -s " + uniform + " --color-by RGB -o " + byOption);
  ASSERT_EQ(colored.exitCode, 0) << colored.err;
  EXPECT_EQ(shadelab("compare " + byScene + " " + byOption + " --atol 0 --rtol 0").exitCode, 0);
  ASSERT_EQ(shadelab("shade " + head + " -s " + uniform + " -o " + byOption).exitCode, 0);
  EXPECT_EQ(shadelab("compare " + byScene + " " + byOption + " --atol 0 --rtol 0").exitCode, 1); // not its grey
  // The errors: an array the mesh lacks, a colour map alone.
  const Result missing = shadelab("shade " + goodMesh() + " --color-by RGB -o " + byOption);
  EXPECT_EQ(missing.exitCode, 1);
  EXPECT_EQ(missing.err,
    "shadelab: " + goodMesh() +
      ": the material's colour array (MaterialColorArray, --color-by): the mesh has no numeric point-data array "
      "'RGB' (its point arrays: none)\n");
  const Result alone = shadelab("shade " + goodMesh() + " --colormap rainbow -o " + byOption);
  EXPECT_EQ(alone.exitCode, 2);
  EXPECT_NE(alone.err.find("--colormap requires --color-by"), std::string::npos) << alone.err;
}

TEST_F(Cli, PrecomputedTransferRelightsWithoutRays)
{
  // The bunny shaded by "prt" of order 4 under the studio map turned 90 degrees, and again
  // unturned; the unturned transfer relit under the map turned 90 degrees is the turned shading's
  // irradiance, to float32's rounding of the transfer (what `compare` takes by default, and
  // 1e-5 where the sum cancels to near 0).
  const std::string mesh = goodMesh(), map = shadelab::testing::sourcePath("data/envmaps/studio_small_03_1k.hdr");
  const std::string turned = (folder / "turned.vtp").string(), unturned = (folder / "unturned.vtp").string();
  const std::string relit = (folder / "relit.vtp").string();
  const std::string prt = " --envmap " + map + " --envmap-estimator prt --envmap-order 4 ";
  ASSERT_EQ(shadelab("shade " + mesh + prt + "--envmap-rotation 90 -a envmap_irradiance -o " + turned).exitCode, 0);
  const Result shaded = shadelab("shade " + mesh + prt + "-a envmap_irradiance,envmap_sh_transfer -o " + unturned);
  ASSERT_EQ(shaded.exitCode, 0) << shaded.err;
  EXPECT_NE(shaded.out.find("    envmap_sh_transfer          25 "), std::string::npos) << shaded.out;
  const Result relighting =
    shadelab("relight " + unturned + " --envmap " + map + " --rotation 90 --name envmap_irradiance -o " + relit);
  ASSERT_EQ(relighting.exitCode, 0) << relighting.err;
  EXPECT_NE(relighting.out.find("'envmap_irradiance' from 'envmap_sh_transfer' (order 4, 25 coefficients) under " +
              map + "; it replaces the input's array of that name"),
    std::string::npos)
    << relighting.out;
  const Result compared = shadelab("compare " + turned + " " + relit + " --arrays envmap_irradiance --atol 1e-5");
  EXPECT_EQ(compared.exitCode, 0) << compared.out;
  // Relit 90 degrees the wrong way, it differs.
  ASSERT_EQ(
    shadelab("relight " + unturned + " --envmap " + map + " --rotation -90 --name envmap_irradiance -o " + relit)
      .exitCode,
    0);
  EXPECT_EQ(shadelab("compare " + turned + " " + relit + " --arrays envmap_irradiance --atol 1e-5").exitCode, 1);

  // Shadowed, the transfer has its standard errors; --envmap-order and directions are prt's alone.
  // By default, as what "prt" is chosen for.
  const Result shadowed = shadelab("shade " + mesh + prt + "--shadows --envmap-samples 16 -o " + turned);
  ASSERT_EQ(shadowed.exitCode, 0) << shadowed.err;
  EXPECT_NE(shadowed.out.find("    envmap_sh_transfer           25 "), std::string::npos) << shadowed.out;
  EXPECT_NE(shadowed.out.find("    envmap_sh_transfer_std_error 25 "), std::string::npos) << shadowed.out;
  expectError("shade " + mesh + " --envmap " + map + " --envmap-order 3 -o " + relit,
    "--envmap-order: only --envmap-estimator prt has an order");
  expectError("shade " + mesh + prt + "--envmap-directions mis -o " + relit,
    "--envmap-directions mis: prt draws its shadow rays by the cosine, the density its transfer vectors are "
    "estimated for: leave --envmap-directions out");
  // Under a tolerance the shadowed transfer's fixed count is refused, saying what to use.
  const Result bounded = shadelab("shade " + mesh + prt + "--shadows --tolerance 0.05 -o " + relit);
  EXPECT_EQ(bounded.exitCode, 1);
  EXPECT_EQ(bounded.err,
    "shadelab: --envmap " + map +
      ": /lights/0/estimator: a tolerance cannot bound light 'envmap' of type \"environment\": its shadowed transfer "
      "vectors can "
      "err by up to 95 through their bands alone, and are estimated from a fixed \"samples\" count, which "
      "no target stops: use \"estimator\": \"monte_carlo\" (--envmap-estimator monte_carlo) with \"samples\": "
      "\"auto\" (--envmap-samples auto); or shade without a tolerance\n")
    << bounded.err;

  // A mesh without transfer vectors, or with two, is refused, saying what to do.
  expectError("relight " + mesh + " --envmap " + map + " -o " + relit,
    mesh +
      ": the input has no point array whose name ends in '_sh_transfer': shade the mesh with \"estimator\": "
      "\"prt\" (shadelab shade --envmap-estimator prt) first");
  expectError("relight " + unturned + " --envmap " + map + " --transfer key_sh_transfer -o " + relit,
    unturned + ": the input has no point array 'key_sh_transfer'");
  expectError("relight " + unturned + " --envmap " + (folder / "none.hdr").string() + " -o " + relit,
    unturned + ": " + (folder / "none.hdr").string() + ": no such file");
  expectError("relight " + unturned + " --envmap " + map + " --name envmap_sh_transfer -o " + relit,
    unturned +
      ": OutputArrayName is the transfer array's name, 'envmap_sh_transfer': choose another name for the "
      "irradiance");
  expectError("relight " + unturned + " --envmap " + map + " --transfer envmap_irradiance -o " + relit,
    unturned +
      ": point array 'envmap_irradiance' is not a transfer vector: it must have 9, 16 or 25 components "
      "(orders 2, 3, 4), not 3");
}

TEST_F(Cli, AnyMeshWithoutASceneUnderTheDefaultLightKit)
{
  // spot.obj as vtkOBJReader splits it: one point set per triangle, welded for its normals.
  const std::string out = (folder / "spot.vtp").string();
  const Result spot = shadelab("shade " + shadelab::testing::sourcePath("data/meshes/spot.obj") + " -o " + out);
  EXPECT_EQ(spot.exitCode, 0) << spot.err;
  EXPECT_NE(spot.out.find("  mesh: 17568 vertices, 5856 polygons and strips\n"), std::string::npos) << spot.out;
  EXPECT_NE(
    spot.out.find("  scene: the default light kit, placed on the mesh (lecture model, 5 lights)\n"), std::string::npos)
    << spot.out;
  EXPECT_NE(spot.out.find("2930 positions are shared by several points: averaged 17568 points with their copies."),
    std::string::npos)
    << spot.out;
  EXPECT_TRUE(fs::exists(out));
  const Result faceted =
    shadelab("shade " + shadelab::testing::sourcePath("data/meshes/spot.obj") + " --no-weld -o " + out);
  EXPECT_EQ(faceted.exitCode, 0) << faceted.err;
  EXPECT_EQ(faceted.out.find("positions are shared"), std::string::npos) << faceted.out;

  // A cube stored with one point per corner gets one normal per face only when split.
  const std::string cube = file("cube.vtk",
    "# vtk DataFile Version 3.0\ncube\nASCII\nDATASET POLYDATA\nPOINTS 8 float\n"
    "0 0 0 1 0 0 1 1 0 0 1 0 0 0 1 1 0 1 1 1 1 0 1 1\n"
    "POLYGONS 6 30\n4 0 3 2 1\n4 4 5 6 7\n4 0 1 5 4\n4 2 3 7 6\n4 1 2 6 5\n4 0 4 7 3\n");
  const Result rounded = shadelab("shade " + cube + " -o " + out);
  EXPECT_NE(rounded.out.find("  mesh: 8 vertices, 6 polygons and strips\n"), std::string::npos) << rounded.out;
  const Result split = shadelab("shade " + cube + " --split-sharp-edges 30 -o " + out);
  EXPECT_EQ(split.exitCode, 0) << split.err;
  EXPECT_NE(split.out.find("  mesh: 24 vertices, 6 polygons and strips\n"), std::string::npos) << split.out;
  EXPECT_NE(split.out.find("Split the mesh at edges sharper than 30 degrees (vtkPolyDataNormals): 8 points became 24"),
    std::string::npos)
    << split.out;
}
}

namespace
{
TEST_F(Cli, TheVtkPbrModelShadesAndSaysWhatItCannotDo)
{
  const std::string scene = (folder / "pbr.json").string();
  std::ofstream(scene) << R"({ "model": "vtk_pbr", "viewer": { "position": [0, 0.1, 0.4], "focal_point": [0, 0.1, 0] },
    "material": { "base_color": [0.9, 0.6, 0.2], "metallic": 1.0, "roughness": 0.3 },
    "lights": [ { "name": "key", "type": "distant", "direction": [-1, -1, -1], "intensity": 3 } ] })";
  const std::string out = (folder / "pbr.vtp").string();
  const Result shaded = shadelab("shade " + goodMesh() + " -s " + scene + " -o " + out);
  ASSERT_EQ(shaded.exitCode, 0) << shaded.err;
  EXPECT_NE(shaded.out.find("(vtk_pbr model, 1 light)"), std::string::npos) << shaded.out;
  const Result listed = shadelab("arrays --scene " + scene);
  EXPECT_NE(listed.out.find("key_ggx_d"), std::string::npos);
  EXPECT_NE(listed.out.find("key_smith_v"), std::string::npos);
  EXPECT_NE(listed.out.find("key_schlick_f"), std::string::npos);

  const Result tolerance = shadelab("shade " + goodMesh() + " -s " + scene + " --tolerance 1e-3 -o " + out);
  EXPECT_EQ(tolerance.exitCode, 1);
  EXPECT_EQ(tolerance.err,
    "shadelab: --tolerance 0.001: the vtk_pbr model has no tolerance plan yet (its bounds are the lecture model's): "
    "use --precision\n");
  // --color-by: each vertex's colour times the base colour's grey (0.9) is its base colour, which
  // for a metal is F0: F = F0 + (F90 - F0)(1 - h.s)^5 with F90 the edge tint (white).
  const std::string head = shadelab::testing::sourcePath("data/meshes/head_scan.ply");
  const Result colored = shadelab("shade " + head + " -s " + scene + " --color-by RGB -a all -o " + out);
  ASSERT_EQ(colored.exitCode, 0) << colored.err;
  vtkNew<vtkXMLPolyDataReader> reader;
  reader->SetFileName(out.c_str());
  reader->Update();
  vtkPointData* data = reader->GetOutput()->GetPointData();
  vtkDataArray *rgb = data->GetArray("RGB"), *fresnel = data->GetArray("key_schlick_f");
  vtkDataArray *half = data->GetArray("key_half_vector"), *toLight = data->GetArray("key_to_light");
  ASSERT_TRUE(rgb && fresnel && half && toLight);
  double largestSpread = 0;
  for (vtkIdType i = 0; i < reader->GetOutput()->GetNumberOfPoints(); i += 97)
  {
    double h[3], s[3];
    half->GetTuple(i, h);
    toLight->GetTuple(i, s);
    const double hDotS = std::clamp(h[0] * s[0] + h[1] * s[1] + h[2] * s[2], 1e-5, 1.0);
    for (int c = 0; c < 3; ++c)
    {
      const double f0 = 0.9 * rgb->GetComponent(i, c) / 255.0;
      EXPECT_NEAR(fresnel->GetComponent(i, c), f0 + (1.0 - f0) * std::pow(1.0 - hDotS, 5.0), 2e-6)
        << "vertex " << i << " channel " << c;
    }
    largestSpread = std::max(largestSpread, std::abs(fresnel->GetComponent(i, 0) - fresnel->GetComponent(i, 2)));
  }
  EXPECT_GT(largestSpread, 0.05); // the colours really differ by channel
  const Result occlusion = shadelab("shade " + goodMesh() + " -s " + scene + " --ambient-occlusion 16 -o " + out);
  EXPECT_EQ(occlusion.exitCode, 1);
  EXPECT_EQ(occlusion.err,
    "shadelab: --ambient-occlusion 16: VTK's PBR shader has no ambient term for the occlusion to darken: use the vtk "
    "or lecture model\n");
}
}
