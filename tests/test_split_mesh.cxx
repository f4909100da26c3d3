// The filters on a mesh split over MPI processes: each process's piece is shaded as its points
// are in the whole mesh, bit for bit. Run by CTest under mpiexec with 1, 2 and 4 processes;
// every process checks its own piece against the whole mesh shaded in one process (the first,
// which sends it to the others).
#include "ArrayComparison.h"
#include "FilterRun.h"
#include "MeshFiles.h"
#include "PieceFiles.h"
#include "ShadeLabImportedParts.h"
#include "ShadeLabWholeMesh.h"
#include "ShadingFlags.h"
#include "TestPaths.h"
#include "TestScenes.h"
#include "VtkErrorCapture.h"
#include "vtkInterreflectionFilter.h"
#include "vtkLocalReflectanceFilter.h"
#include "vtkMeshVisibilityFilter.h"
#include "vtkShadingNormalsFilter.h"

#include "vtkCellArray.h"
#include "vtkCellData.h"
#include "vtkDoubleArray.h"
#include "vtkFieldData.h"
#include "vtkFloatArray.h"
#include "vtkIdList.h"
#include "vtkMPICommunicator.h"
#include "vtkMPIController.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkStringArray.h"
#include "vtkUnsignedCharArray.h"
#include "vtkXMLPPolyDataReader.h"
#include "vtkXMLPPolyDataWriter.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <chrono>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <string>
#include <thread>
#include <utility>
#include <vector>

namespace
{
vtkMultiProcessController* processes()
{
  return vtkMultiProcessController::GetGlobalController();
}

std::string dataPath(const std::string& relative)
{
  return shadelab::testing::sourcePath("data/" + relative);
}

/// The piece's global point ids.
std::vector<vtkIdType> globalIdsOf(vtkPolyData* piece)
{
  vtkDataArray* ids = piece->GetPointData()->GetGlobalIds();
  std::vector<vtkIdType> values(static_cast<std::size_t>(piece->GetNumberOfPoints()));
  for (std::size_t i = 0; i < values.size(); ++i)
  {
    values[i] = static_cast<vtkIdType>(ids->GetTuple1(static_cast<vtkIdType>(i)));
  }
  return values;
}

/// Every point array of `whole` (one process's output) equals the piece's, bit for bit, at
/// the piece's points; returns how many arrays were compared.
int expectPieceOfWhole(vtkPolyData* whole, vtkPolyData* piece)
{
  const std::vector<vtkIdType> ids = globalIdsOf(piece);
  vtkPointData* expected = whole->GetPointData();
  for (int a = 0; a < expected->GetNumberOfArrays(); ++a)
  {
    const std::string name = expected->GetArrayName(a);
    shadelab::testing::expectSameBits(
      shadelab::tuplesAt(expected->GetArray(a), ids), piece->GetPointData()->GetArray(name.c_str()), name);
  }
  return expected->GetNumberOfArrays();
}

/// The filter's output for `mesh` in float64 with these arrays, through `controller`, with
/// the filter's other settings (if any) made by configure.
vtkSmartPointer<vtkPolyData> shaded(vtkPolyData* mesh, const std::string& scene, const std::vector<std::string>& arrays,
  vtkMultiProcessController* controller, double tolerance = 0,
  const std::function<void(vtkLocalReflectanceFilter*)>& configure = {})
{
  vtkNew<vtkLocalReflectanceFilter> filter;
  filter->SetController(controller);
  filter->SetInputData(mesh);
  filter->SetSceneFileName(scene.front() == '/' ? scene : dataPath("scenes/" + scene)); // or a path of its own
  filter->SetArraySelection(arrays);
  filter->SetOutputPrecision(vtkAlgorithm::DOUBLE_PRECISION);
  filter->SetTolerance(tolerance);
  filter->SetNumberOfThreads(1);
  if (configure)
  {
    configure(filter);
  }
  filter->Update();
  auto output = vtkSmartPointer<vtkPolyData>::New();
  output->ShallowCopy(filter->GetOutput());
  return output;
}

/// The whole mesh shaded in one process, as `shaded` with no controller: the first process
/// shades it and sends it to the others, rather than each process shading it again. They sleep
/// while they wait: Open MPI's own waits poll, and on 4 processes over 2 cores they took the
/// cores from the process doing the work. Every process calls it at the same point.
vtkSmartPointer<vtkPolyData> shadedWhole(vtkPolyData* mesh, const std::string& scene,
  const std::vector<std::string>& arrays, double tolerance = 0,
  const std::function<void(vtkLocalReflectanceFilter*)>& configure = {})
{
  constexpr int wholeMeshTag = 7001;
  if (processes()->GetLocalProcessId() == 0)
  {
    const vtkSmartPointer<vtkPolyData> whole = shaded(mesh, scene, arrays, nullptr, tolerance, configure);
    for (int process = 1; process < processes()->GetNumberOfProcesses(); ++process)
    {
      processes()->Send(whole, process, wholeMeshTag);
    }
    return whole;
  }
  auto* communicator = vtkMPICommunicator::SafeDownCast(processes()->GetCommunicator());
  for (int arrived = 0; communicator->Iprobe(0, wholeMeshTag, &arrived, nullptr), arrived == 0;)
  {
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  auto whole = vtkSmartPointer<vtkPolyData>::New();
  processes()->Receive(whole, 0, wholeMeshTag);
  return whole;
}

/// This process's piece of a mesh file, with a layer of ghost cells.
vtkSmartPointer<vtkPolyData> myPiece(vtkPolyData* mesh, int ghostLevels = 1)
{
  return shadelab::app::meshPiece(
    mesh, processes()->GetLocalProcessId(), processes()->GetNumberOfProcesses(), ghostLevels);
}

/// A scene file of this process's own (each process writes its copy, and CTest may run the
/// three process counts at once), in the temporary directory; its path.
std::string sceneFile(const std::string& name, const std::string& json)
{
  const std::filesystem::path path = std::filesystem::temp_directory_path() /
    ("shadelab_" + name + "_np" + std::to_string(processes()->GetNumberOfProcesses()) + "_" +
      std::to_string(processes()->GetLocalProcessId()) + ".json");
  std::ofstream(path) << json;
  return path.string();
}

/// A bundled scene with at most 8 samples a light, 16 occlusion rays and 256 of either drawn to
/// a target, written as sceneFile does (its map's path made absolute); its path. The processes trace and exchange the
/// same things as under the bundled scene, each value from fewer rays.
std::string withFewerRays(const std::string& bundled)
{
  const std::string scenes = dataPath("scenes/");
  nlohmann::json scene = nlohmann::json::parse(std::ifstream(scenes + bundled + ".json"));
  const std::function<void(nlohmann::json&)> fewer = [&](nlohmann::json& value)
  {
    for (auto& [key, field] : value.items())
    {
      if (key == "samples" && field.is_number_integer())
      {
        field = std::min(field.get<int>(), 8);
      }
      else if (key == "rays" && field.is_number_integer())
      {
        field = std::min(field.get<int>(), 16);
      }
      else if ((key == "max_samples" || key == "max_rays") && field.is_number_integer())
      {
        field = std::min(field.get<int>(), 256);
      }
      else if (key == "file" && field.is_string())
      {
        field = (std::filesystem::path(scenes) / field.get<std::string>()).lexically_normal().string();
      }
      else if (field.is_structured())
      {
        fewer(field);
      }
    }
  };
  fewer(scene);
  return sceneFile(bundled + "_fewer_rays", scene.dump());
}

struct SplitMesh : ::testing::TestWithParam<const char*>
{
  vtkSmartPointer<vtkPolyData> mesh = shadelab::app::readMesh(dataPath(std::string("meshes/") + GetParam()));
};

// Every array in float64: of studio.json (41), and of area_lights.json, whose Monte Carlo
// light's samples are seeded by each point's id in the whole mesh.
TEST_P(SplitMesh, ShadesEachPieceAsTheWholeMesh)
{
  for (const auto& [scene, arrays] :
    { std::pair{ std::string("studio.json"), 41 }, std::pair{ withFewerRays("area_lights"), 18 } })
  {
    const vtkSmartPointer<vtkPolyData> whole = shadedWhole(mesh, scene, { "all" });
    const vtkSmartPointer<vtkPolyData> piece = shaded(myPiece(mesh), scene, { "all" }, processes());
    ASSERT_GT(piece->GetNumberOfPoints(), 0);
    EXPECT_GE(expectPieceOfWhole(whole, piece), arrays) << scene;
  }
}

// A scene placed on the mesh's extent, under a tolerance that plans on it too: with float32's
// rounding measured on the same sample of points whatever the pieces.
TEST_P(SplitMesh, PlacesTheSceneOnTheWholeMesh)
{
  const vtkSmartPointer<vtkPolyData> whole = shadedWhole(mesh, "studio_mesh.json", { "totals" }, 1e-3);
  const vtkSmartPointer<vtkPolyData> piece = shaded(myPiece(mesh), "studio_mesh.json", { "totals" }, processes(), 1e-3);
  EXPECT_GT(expectPieceOfWhole(whole, piece), 3);
  ASSERT_FALSE(shadelab::testing::methodsNote(whole).empty());
  EXPECT_NE(shadelab::testing::methodsNote(whole)[0].find("measured on a sample of the points"), std::string::npos)
    << shadelab::testing::methodsNote(whole)[0];
  EXPECT_EQ(shadelab::testing::methodsNote(piece), shadelab::testing::methodsNote(whole));
}

// Soft shadows drawn to a target under a tolerance: each vertex's rounds of rays, traced against
// the whole mesh where its piece is, stop where the whole mesh's stop.
TEST_P(SplitMesh, DrawsSoftShadowsToATargetAsTheWholeMesh)
{
  const std::string scene = withFewerRays("soft_shadows_to_a_tolerance");
  const vtkSmartPointer<vtkPolyData> whole = shadedWhole(mesh, scene, { "all" }, 0.02);
  const vtkSmartPointer<vtkPolyData> piece = shaded(myPiece(mesh), scene, { "all" }, processes(), 0.02);
  ASSERT_GT(piece->GetNumberOfPoints(), 0);
  EXPECT_GE(expectPieceOfWhole(whole, piece), 13);
  // The same plan; the whole mesh's has its cost forecast too (a split mesh is shaded without one).
  std::vector<std::string> plan = shadelab::testing::methodsNote(whole);
  const auto forecast = std::find_if(
    plan.begin(), plan.end(), [](const std::string& line) { return line.rfind("forecast from ", 0) == 0; });
  ASSERT_TRUE(forecast != plan.end() && forecast + 1 != plan.end() && forecast[1].rfind("drew ", 0) == 0);
  plan.erase(forecast, forecast + 2);
  EXPECT_EQ(shadelab::testing::methodsNote(piece), plan);
}

/// The normals filter's output and report on `piece` through every process, and whether this
/// process put the whole mesh together meanwhile.
struct PieceNormalsRun
{
  vtkSmartPointer<vtkPolyData> output;
  std::string report;
  bool putTogether = false;
};

PieceNormalsRun normalsOnPiece(vtkPolyData* piece, bool keepInputNormals = true)
{
  vtkNew<vtkShadingNormalsFilter> split;
  split->SetInputData(piece);
  split->SetKeepInputNormals(keepInputNormals);
  const std::size_t before = shadelab::wholeMeshesPutTogetherHere();
  split->Update();
  PieceNormalsRun run{ split->GetOutput(), split->GetReport(), shadelab::wholeMeshesPutTogetherHere() > before };
  return run;
}

vtkSmartPointer<vtkPolyData> normalsOfWhole(vtkPolyData* mesh, bool keepInputNormals = true)
{
  vtkNew<vtkShadingNormalsFilter> whole;
  whole->SetController(nullptr);
  whole->SetKeepInputNormals(keepInputNormals);
  whole->SetInputData(mesh);
  whole->Update();
  auto output = vtkSmartPointer<vtkPolyData>::New();
  output->ShallowCopy(whole->GetOutput());
  return output;
}

std::string normalsReport(vtkPolyData* output)
{
  return vtkStringArray::SafeDownCast(output->GetFieldData()->GetAbstractArray("shadelab_normals"))->GetValue(0);
}

// The normals filter alone, computed and flipped outward on the whole mesh: piece by piece, with
// a layer of ghost cells and without, except where copies of a point at one position are welded
// (the OBJ files' seams) or windings reordered (the owl scan's), for which the first process puts
// the mesh together.
TEST_P(SplitMesh, NormalsAreTheWholeMeshs)
{
  const vtkSmartPointer<vtkPolyData> whole = normalsOfWhole(mesh);
  const std::string report = normalsReport(whole);
  const bool wholeMeshNeeded =
    report.find("positions are shared") != std::string::npos || report.find("turning round") != std::string::npos;
  for (int ghostLevels : { 1, 0 })
  {
    const PieceNormalsRun split = normalsOnPiece(myPiece(mesh, ghostLevels));
    EXPECT_EQ(split.report, report);
    EXPECT_EQ(expectPieceOfWhole(whole, split.output), whole->GetPointData()->GetNumberOfArrays());
    EXPECT_NE(split.output->GetPointData()->GetNormals(), nullptr);
    EXPECT_EQ(split.putTogether, wholeMeshNeeded && processes()->GetLocalProcessId() == 0)
      << ghostLevels << " ghost levels; " << report;
  }
}

INSTANTIATE_TEST_SUITE_P(BundledMeshes, SplitMesh,
  ::testing::Values("bunny_zipper.ply", "spot.obj", "teapot.obj", "xyzrgb_dragon_50k.ply", "owl_scan.vtp"),
  [](const auto& info)
  {
    std::string name = info.param;
    return name.substr(0, name.find('.'));
  });

vtkSmartPointer<vtkPolyData> bunny()
{
  return shadelab::app::readMesh(dataPath("meshes/bunny_zipper.ply"));
}

// A material from the mesh's arrays: the head scan's own colours, and a field through a colour
// map whose range is the whole mesh's, though each piece holds a part of the field; and the
// spectral mode.
TEST(SplitMeshMaterial, ColoursAndAFieldsRangeAreTheWholeMeshs)
{
  const vtkSmartPointer<vtkPolyData> head = shadelab::app::readMesh(dataPath("meshes/head_scan.ply"));
  vtkNew<vtkDoubleArray> height;
  height->SetName("height");
  for (vtkIdType i = 0; i < head->GetNumberOfPoints(); ++i)
  {
    height->InsertNextValue(head->GetPoint(i)[1]);
  }
  head->GetPointData()->AddArray(height);
  EXPECT_GT(expectPieceOfWhole(shadedWhole(head, "scan_colors.json", { "all" }),
              shaded(myPiece(head), "scan_colors.json", { "all" }, processes())),
    10);
  auto byHeight = [](vtkLocalReflectanceFilter* filter)
  {
    filter->SetColorByArray(true);
    filter->SetMaterialColorArray("height");
  };
  EXPECT_GT(expectPieceOfWhole(shadedWhole(head, "studio_mesh.json", { "totals" }, 0, byHeight),
              shaded(myPiece(head), "studio_mesh.json", { "totals" }, processes(), 0, byHeight)),
    5);
  // The spectral mode, with its XYZ twins and its difference from the RGB model.
  EXPECT_GT(expectPieceOfWhole(shadedWhole(head, "spectral_fluorescent.json", { "totals" }),
              shaded(myPiece(head), "spectral_fluorescent.json", { "totals" }, processes())),
    10);
}

// Shadows and ambient occlusion: each piece's rays meet the whole mesh's triangles.
TEST(SplitMeshVisibility, CastsAgainstTheWholeMesh)
{
  const vtkSmartPointer<vtkPolyData> mesh = bunny();
  const std::string occlusion = withFewerRays("shadows_occlusion");
  const vtkSmartPointer<vtkPolyData> whole = shadedWhole(mesh, occlusion, { "all" });
  const vtkSmartPointer<vtkPolyData> piece = shaded(myPiece(mesh), occlusion, { "all" }, processes());
  EXPECT_GT(expectPieceOfWhole(whole, piece), 10);
  // An area light's soft shadows: each sample's ray, seeded by the point's id in the whole mesh;
  // a map's, with every sample's ray going to infinity; and transfer vectors from the same rays,
  // 16 coefficients and their standard errors a point.
  for (const std::string bundled : { "soft_shadows", "envmap_shadows", "envmap_transfer" })
  {
    const std::string scene = withFewerRays(bundled);
    EXPECT_GT(
      expectPieceOfWhole(shadedWhole(mesh, scene, { "all" }), shaded(myPiece(mesh), scene, { "all" }, processes())), 10)
      << bundled;
  }

  // The visibility filter alone, on normals the mesh has.
  vtkNew<vtkMeshVisibilityFilter> alone, split;
  alone->SetController(nullptr);
  alone->SetInputData(whole);
  alone->SetSceneFileName(occlusion);
  alone->Update();
  split->SetInputData(myPiece(whole));
  split->SetSceneFileName(occlusion);
  split->Update();
  EXPECT_GT(expectPieceOfWhole(alone->GetOutput(), split->GetOutput()), 10);
}

// What the whole mesh buys: the same filter on each piece alone (its points' ids taken away)
// finds other normals at the pieces' edges and places the scene on the piece's extent.
TEST(SplitMeshVisibility, PiecesAloneWouldShadeOtherwise)
{
  const int count = processes()->GetNumberOfProcesses();
  if (count == 1)
  {
    GTEST_SKIP() << "one process has one piece, the whole mesh";
  }
  const vtkSmartPointer<vtkPolyData> mesh = bunny();
  const vtkSmartPointer<vtkPolyData> whole = shadedWhole(mesh, "studio_mesh.json", { "totals" });
  vtkSmartPointer<vtkPolyData> alone = myPiece(mesh, 0);
  const std::vector<vtkIdType> ids = globalIdsOf(alone);
  alone->GetPointData()->SetGlobalIds(nullptr);
  const vtkSmartPointer<vtkPolyData> shadedAlone = shaded(alone, "studio_mesh.json", { "totals" }, nullptr);
  vtkDataArray* expected = whole->GetPointData()->GetArray("total");
  vtkDataArray* actual = shadedAlone->GetPointData()->GetArray("total");
  ASSERT_NE(actual, nullptr);
  vtkIdType differing = 0;
  for (std::size_t i = 0; i < ids.size(); ++i)
  {
    for (int c = 0; c < 3; ++c)
    {
      differing += expected->GetComponent(ids[i], c) != actual->GetComponent(static_cast<vtkIdType>(i), c) ? 1 : 0;
    }
  }
  // The scene moves with the piece's extent: nearly every value changes.
  EXPECT_GT(differing, static_cast<vtkIdType>(ids.size()));
}

// More processes than pieces: the last process's piece is empty. It takes part in every
// exchange, shades nothing, and the others' pieces are still the whole mesh's, with shadows and
// occlusion (which gather the mesh on every process) and without (normals from the first), on
// a mesh without normals and on one whose own normals the others keep.
TEST(SplitMeshVisibility, AProcessWithAnEmptyPiece)
{
  const int count = processes()->GetNumberOfProcesses();
  if (count == 1)
  {
    GTEST_SKIP() << "one process holds the only piece";
  }
  const vtkSmartPointer<vtkPolyData> plain = bunny();
  const vtkSmartPointer<vtkPolyData> withNormals = normalsOfWhole(plain);
  const int rank = processes()->GetLocalProcessId();
  const bool holdsNone = rank == count - 1;
  for (vtkPolyData* mesh : { plain.Get(), withNormals.Get() })
  {
    vtkSmartPointer<vtkPolyData> piece =
      holdsNone ? vtkSmartPointer<vtkPolyData>::New() : shadelab::app::meshPiece(mesh, rank, count - 1, 1);
    for (const auto& [scene, arrays] :
      { std::pair{ withFewerRays("shadows_occlusion"), 10 }, std::pair{ std::string("studio.json"), 40 } })
    {
      const bool ownNormals = mesh->GetPointData()->GetNormals() != nullptr;
      const vtkSmartPointer<vtkPolyData> shadedPiece = shaded(piece, scene, { "all" }, processes());
      const vtkSmartPointer<vtkPolyData> whole = shadedWhole(mesh, scene, { "all" });
      if (holdsNone)
      {
        EXPECT_EQ(shadedPiece->GetNumberOfPoints(), 0) << scene;
        continue;
      }
      EXPECT_GT(expectPieceOfWhole(whole, shadedPiece), arrays)
        << scene << (ownNormals ? " with the mesh's normals" : "");
    }
  }
  // Drawn to a target, the vertices short of it are counted over the pieces, the empty one too.
  const std::string drawn = withFewerRays("soft_shadows_to_a_tolerance");
  vtkSmartPointer<vtkPolyData> piece =
    holdsNone ? vtkSmartPointer<vtkPolyData>::New() : shadelab::app::meshPiece(withNormals, rank, count - 1, 1);
  const vtkSmartPointer<vtkPolyData> shadedPiece = shaded(piece, drawn, { "totals" }, processes(), 0.02);
  const vtkSmartPointer<vtkPolyData> whole = shadedWhole(withNormals, drawn, { "totals" }, 0.02);
  if (!holdsNone)
  {
    EXPECT_GT(expectPieceOfWhole(whole, shadedPiece), 3);
  }
}

// The normals' mesh is gathered on the first process alone: the others hold only their pieces.
TEST(SplitMeshMemory, NormalsGatherOnTheFirstProcessOnly)
{
  const vtkSmartPointer<vtkPolyData> mesh = bunny();
  const vtkSmartPointer<vtkPolyData> piece = myPiece(mesh);
  const shadelab::WholeMesh whole =
    shadelab::gatherWholeMesh(processes(), piece, false, shadelab::WholeMeshOn::FirstProcess);
  EXPECT_EQ(whole.problem, "");
  EXPECT_TRUE(whole.putTogether);
  EXPECT_EQ(whole.pieceIds, globalIdsOf(piece));
  vtkIdType pieceSize = piece->GetNumberOfPoints(), piecesSize = 0;
  processes()->AllReduce(&pieceSize, &piecesSize, 1, vtkCommunicator::SUM_OP);
  if (processes()->GetLocalProcessId() == 0)
  {
    ASSERT_NE(whole.mesh, nullptr);
    EXPECT_EQ(whole.mesh->GetNumberOfPoints(), mesh->GetNumberOfPoints());
    EXPECT_EQ(whole.mesh->GetNumberOfPolys(), mesh->GetNumberOfPolys());
    EXPECT_EQ(whole.everyPieceIds.size(), static_cast<std::size_t>(piecesSize));
  }
  else
  {
    EXPECT_EQ(whole.mesh, nullptr);
    EXPECT_TRUE(whole.everyPieceIds.empty());
  }
}

// A scene without shadows is shaded with no process putting the mesh together: each holds its
// piece, and what the exchanges of the normals bring it (the points it shares, and the points
// whose edges do not pair up, with their polygons). Shadows gather it on every process.
TEST(SplitMeshMemory, NoProcessPutsTheMeshTogetherWithoutShadows)
{
  const vtkSmartPointer<vtkPolyData> mesh = bunny();
  const std::size_t before = shadelab::wholeMeshesPutTogetherHere();
  const vtkSmartPointer<vtkPolyData> piece = shaded(myPiece(mesh), "studio.json", { "all" }, processes());
  EXPECT_EQ(shadelab::wholeMeshesPutTogetherHere(), before);
  EXPECT_GT(expectPieceOfWhole(shadedWhole(mesh, "studio.json", { "all" }), piece), 40);
  shaded(myPiece(mesh), withFewerRays("shadows_occlusion"), { "totals" }, processes());
  EXPECT_GT(shadelab::wholeMeshesPutTogetherHere(), before);
}

// Windings to reorder (one polygon turned round) are reordered on the whole mesh, which the
// first process puts together; stored normals that point in are found so on the pieces, and
// flipped; computed normals replace stored ones where asked.
TEST(SplitMeshNormals, WhatOnlyTheWholeMeshSettlesAndStoredNormals)
{
  const vtkSmartPointer<vtkPolyData> turned = bunny();
  vtkNew<vtkIdList> corners;
  turned->GetPolys()->GetCellAtId(100, corners);
  std::reverse(corners->GetPointer(0), corners->GetPointer(0) + corners->GetNumberOfIds());
  turned->GetPolys()->ReplaceCellAtId(100, corners);
  const vtkSmartPointer<vtkPolyData> reordered = normalsOfWhole(turned);
  ASSERT_NE(normalsReport(reordered).find("after turning round"), std::string::npos) << normalsReport(reordered);
  const PieceNormalsRun split = normalsOnPiece(myPiece(turned));
  EXPECT_EQ(split.report, normalsReport(reordered));
  EXPECT_EQ(expectPieceOfWhole(reordered, split.output), reordered->GetPointData()->GetNumberOfArrays());
  EXPECT_EQ(split.putTogether, processes()->GetLocalProcessId() == 0);

  // Stored normals replaced on a mesh whose seams are welded on the whole mesh, which is put
  // together without them: the report says they were replaced, as one process's does.
  const vtkSmartPointer<vtkPolyData> seams = normalsOfWhole(shadelab::app::readMesh(dataPath("meshes/spot.obj")));
  const vtkSmartPointer<vtkPolyData> replaced = normalsOfWhole(seams, false);
  const PieceNormalsRun welded = normalsOnPiece(myPiece(seams), false);
  EXPECT_EQ(welded.report.rfind("Replaced the mesh's point normals", 0), 0u) << welded.report;
  EXPECT_EQ(welded.report, normalsReport(replaced));
  EXPECT_EQ(expectPieceOfWhole(replaced, welded.output), replaced->GetPointData()->GetNumberOfArrays());
  EXPECT_EQ(welded.putTogether, processes()->GetLocalProcessId() == 0);

  // The bunny's computed normals point in: stored, they are flipped, and replaced where asked.
  const vtkSmartPointer<vtkPolyData> inward = bunny();
  vtkNew<vtkShadingNormalsFilter> stored;
  stored->SetController(nullptr);
  stored->OrientOutwardOff();
  stored->SetInputData(inward);
  stored->Update();
  inward->GetPointData()->SetNormals(stored->GetOutput()->GetPointData()->GetNormals());
  for (bool keep : { true, false })
  {
    const vtkSmartPointer<vtkPolyData> whole = normalsOfWhole(inward, keep);
    ASSERT_NE(normalsReport(whole).find("flipped them outward"), std::string::npos) << normalsReport(whole);
    const PieceNormalsRun piece = normalsOnPiece(myPiece(inward), keep);
    EXPECT_EQ(piece.report, normalsReport(whole));
    EXPECT_EQ(expectPieceOfWhole(whole, piece.output), whole->GetPointData()->GetNumberOfArrays());
    EXPECT_FALSE(piece.putTogether);
  }
}

/// interreflection.json with fewer rays, written as sceneFile does; its path.
std::string bouncesUnderAMap()
{
  return sceneFile(
    "bounces_under_a_map", shadelab::testing::bouncesUnderAMapScene(dataPath("envmaps/studio_small_03_1k.hdr")));
}

// Pieces written as a .pvtp (each process its own) and read back whole in one process: the
// pieces' shared points are there once per piece, and their global ids put them back together.
TEST(SplitMeshFiles, PiecesWrittenAndReadBack)
{
  const vtkSmartPointer<vtkPolyData> mesh = bunny();
  const vtkSmartPointer<vtkPolyData> piece = shaded(myPiece(mesh, 0), "studio.json", { "default" }, processes());
  // One file per process count: CTest may run the three at once.
  const std::string file = std::filesystem::temp_directory_path() /
    ("shadelab_split_mesh_np" + std::to_string(processes()->GetNumberOfProcesses()) + ".pvtp");
  vtkNew<vtkXMLPPolyDataWriter> writer;
  writer->SetController(processes());
  writer->SetInputData(piece);
  writer->SetFileName(file.c_str());
  writer->SetNumberOfPieces(processes()->GetNumberOfProcesses());
  writer->SetStartPiece(processes()->GetLocalProcessId());
  writer->SetEndPiece(processes()->GetLocalProcessId());
  ASSERT_EQ(writer->Write(), 1);
  processes()->Barrier();
  if (processes()->GetLocalProcessId() != 0)
  {
    return;
  }
  vtkNew<vtkXMLPPolyDataReader> reader;
  reader->SetFileName(file.c_str());
  reader->Update();
  vtkPolyData* read = reader->GetOutput();
  EXPECT_EQ(read->GetNumberOfCells(), mesh->GetNumberOfCells());
  const vtkSmartPointer<vtkPolyData> whole = shaded(mesh, "studio.json", { "default" }, nullptr);
  EXPECT_GT(expectPieceOfWhole(whole, read), 2);
  // Shaded again in one process, from the pieces as read: the same bits.
  vtkNew<vtkPolyData> geometry;
  geometry->SetPoints(read->GetPoints());
  geometry->SetPolys(read->GetPolys());
  geometry->GetPointData()->SetGlobalIds(read->GetPointData()->GetGlobalIds());
  geometry->GetCellData()->SetGlobalIds(read->GetCellData()->GetGlobalIds());
  EXPECT_GT(expectPieceOfWhole(whole, shaded(geometry, "studio.json", { "default" }, nullptr)), 2);
  // And with interreflection, whose gather takes each of the points the pieces share once.
  EXPECT_GT(expectPieceOfWhole(shaded(mesh, bouncesUnderAMap(), { "all" }, nullptr),
              shaded(geometry, bouncesUnderAMap(), { "all" }, nullptr)),
    10);
}

// Pieces that cannot be put together: every process stops with the same message.
TEST(SplitMeshErrors, PiecesWithoutGlobalIds)
{
  const int count = processes()->GetNumberOfProcesses();
  if (count == 1)
  {
    GTEST_SKIP() << "one process's piece without ids is the whole mesh";
  }
  vtkSmartPointer<vtkPolyData> piece = myPiece(bunny(), 0);
  piece->GetPointData()->SetGlobalIds(nullptr);
  const shadelab::WholeMesh whole = shadelab::gatherWholeMesh(processes(), piece, true);
  EXPECT_EQ(whole.mesh, nullptr);
  EXPECT_EQ(whole.problem,
    "the mesh is in " + std::to_string(count) +
      " pieces but their points have no global ids (vtkGlobalIds), which say which points of different pieces "
      "are one: give them global ids (VTK's vtkGenerateGlobalIds), or read pieces written by shadelab, which have "
      "them");
}

TEST(SplitMeshErrors, PiecesWithoutCellIds)
{
  vtkSmartPointer<vtkPolyData> piece = myPiece(bunny(), 0);
  piece->GetCellData()->SetGlobalIds(nullptr);
  const shadelab::WholeMesh whole = shadelab::gatherWholeMesh(processes(), piece, true);
  if (processes()->GetNumberOfProcesses() == 1)
  {
    EXPECT_EQ(whole.problem, ""); // one piece's cells are in its own order
    return;
  }
  EXPECT_EQ(whole.problem,
    "the pieces' cells have no global ids (vtkGlobalIds), which put the polygons in the mesh's order: give every "
    "piece's cells global ids");
}

// Ids that do not number the points 0 to n-1 (here, each doubled): several processes cannot
// put the mesh together; one process shades its piece as it is.
TEST(SplitMeshErrors, IdsOfAnotherNumbering)
{
  const vtkSmartPointer<vtkPolyData> mesh = bunny();
  vtkSmartPointer<vtkPolyData> piece = myPiece(mesh, 0);
  vtkDataArray* ids = piece->GetPointData()->GetGlobalIds();
  for (vtkIdType i = 0; i < ids->GetNumberOfTuples(); ++i)
  {
    ids->SetTuple1(i, 2 * ids->GetTuple1(i));
  }
  const shadelab::WholeMesh whole = shadelab::gatherWholeMesh(processes(), piece, true);
  if (processes()->GetNumberOfProcesses() == 1)
  {
    EXPECT_EQ(whole.problem, "");
    EXPECT_EQ(whole.mesh, piece);
    EXPECT_TRUE(whole.pieceIds.empty());
    return;
  }
  EXPECT_EQ(whole.problem,
    "the pieces' global point ids run from 0 to " + std::to_string(2 * (mesh->GetNumberOfPoints() - 1)) +
      " but do not number the points 0 to n-1, each at least once: give the points global ids that do");
}

/// A two-sided bunny lit from below its open base, seen from the side: both sides of each
/// vertex gather, the hidden one shaded on the side of the rays too.
std::string twoSidedBounces()
{
  return sceneFile("two_sided_bounces",
    R"({ "material": { "kd": [0.8, 0.62, 0.45], "ks": [0, 0, 0], "two_sided": true },
         "viewer": { "position": [0.3, 0.1, 0.2] },
         "interreflection": { "bounces": 2, "samples": 32 },
         "lights": [ { "name": "key", "type": "point", "position": [-0.02, 0.0, 0.02], "intensity": 0.02,
                       "shadows": true } ] })");
}

// Interreflection: each process gathers at its own points against the whole mesh's triangles,
// and the processes share every bounce's values, so that each piece gets the whole mesh's
// bounces bit for bit: under a map with its shadows (bouncesUnderAMap, 3 bounces of 32
// rays), with a "prt" map's transfer carried through the bounces, and under a tolerance, whose
// bounces and gather rays are chosen from every piece's vertices alike.
TEST(SplitMeshInterreflection, GathersAgainstTheWholeMeshAndSharesEachBounce)
{
  const vtkSmartPointer<vtkPolyData> mesh = bunny();
  EXPECT_GT(expectPieceOfWhole(shadedWhole(mesh, bouncesUnderAMap(), { "all" }),
              shaded(myPiece(mesh), bouncesUnderAMap(), { "all" }, processes())),
    10);
  const std::string transfer = sceneFile("transfer_bounces",
    R"({ "material": { "kd": [0.8, 0.62, 0.45], "ks": [0, 0, 0] },
         "interreflection": { "bounces": 2, "samples": 32 },
         "lights": [ { "name": "studio", "type": "environment", "file": ")" +
      dataPath("envmaps/studio_small_03_1k.hdr") +
      R"(", "estimator": "prt", "order": 3, "samples": 32, "intensity": 0.04, "shadows": true } ] })");
  const vtkSmartPointer<vtkPolyData> whole = shadedWhole(mesh, transfer, { "all" });
  EXPECT_NE(whole->GetPointData()->GetArray("studio_sh_transfer_indirect"), nullptr); // no return before the run below
  EXPECT_GT(expectPieceOfWhole(whole, shaded(myPiece(mesh), transfer, { "all" }, processes())), 10);
  const std::string bothSides = sceneFile("transfer_bounces_two_sided",
    R"({ "material": { "kd": [0.8, 0.62, 0.45], "ks": [0, 0, 0], "two_sided": true },
         "viewer": { "position": [0.3, 0.1, 0.2] },
         "interreflection": { "bounces": 2, "samples": 16 },
         "lights": [ { "name": "studio", "type": "environment", "file": ")" +
      dataPath("envmaps/studio_small_03_1k.hdr") +
      R"(", "estimator": "prt", "order": 3, "samples": 16, "intensity": 0.04, "shadows": true } ] })");
  EXPECT_GT(expectPieceOfWhole(
              shadedWhole(mesh, bothSides, { "all" }), shaded(myPiece(mesh), bothSides, { "all" }, processes())),
    10);
  const std::string automatic = sceneFile("auto_bounces",
    R"({ "material": { "kd": [0.8, 0.62, 0.45], "ks": [0, 0, 0] },
         "interreflection": { "bounces": "auto", "samples": "auto", "max_samples": 128 },
         "lights": [ { "name": "key", "type": "point", "position": [0.25, 0.35, 0.35], "intensity": 0.22,
                       "shadows": true } ] })");
  EXPECT_GT(expectPieceOfWhole(shadedWhole(mesh, automatic, { "all" }, 0.05),
              shaded(myPiece(mesh), automatic, { "all" }, processes(), 0.05)),
    8);
  EXPECT_GT(expectPieceOfWhole(shadedWhole(mesh, twoSidedBounces(), { "all" }),
              shaded(myPiece(mesh), twoSidedBounces(), { "all" }, processes())),
    8);
}

// A mesh's own materials, every part two-sided (a glTF file's doubleSided materials), on pieces
// and an empty one, which has no parts to say so: every process shades with the own materials
// and on both sides, with the hidden sides' exchanges, as the whole mesh is shaded. (Before,
// the empty piece read no material arrays while the others did, and all waited for ever.)
TEST(SplitMeshInterreflection, OwnTwoSidedMaterialsWithAnEmptyPiece)
{
  const int count = processes()->GetNumberOfProcesses();
  if (count == 1)
  {
    GTEST_SKIP() << "one process holds the only piece";
  }
  const vtkSmartPointer<vtkPolyData> mesh = bunny();
  for (const char* name : { shadelab::materialKaArrayName, shadelab::materialKdArrayName, shadelab::materialKsArrayName,
         shadelab::materialShininessArrayName, shadelab::partArrayName })
  {
    vtkNew<vtkFloatArray> values;
    values->SetName(name);
    values->SetNumberOfComponents(
      std::string(name) == shadelab::materialShininessArrayName || std::string(name) == shadelab::partArrayName ? 1
                                                                                                                : 3);
    values->SetNumberOfTuples(mesh->GetNumberOfPoints());
    values->Fill(std::string(name) == shadelab::materialKdArrayName ? 0.7 : 0.0);
    mesh->GetPointData()->AddArray(values);
  }
  vtkNew<vtkUnsignedCharArray> twoSided;
  twoSided->SetName(shadelab::partTwoSidedArrayName);
  twoSided->InsertNextValue(1);
  mesh->GetFieldData()->AddArray(twoSided);
  const int rank = processes()->GetLocalProcessId();
  const bool holdsNone = rank == count - 1;
  vtkSmartPointer<vtkPolyData> piece =
    holdsNone ? vtkSmartPointer<vtkPolyData>::New() : shadelab::app::meshPiece(mesh, rank, count - 1, 1);
  if (!holdsNone)
  {
    piece->GetFieldData()->AddArray(twoSided);
  }
  const std::string scene = sceneFile("own_two_sided", R"({ "viewer": { "position": [0.3, 0.1, 0.2] },
    "interreflection": { "bounces": 1, "samples": 8 },
    "lights": [ { "name": "key", "type": "point", "position": [-0.02, 0.0, 0.02], "intensity": 0.02 } ] })");
  const vtkSmartPointer<vtkPolyData> shadedPiece = shaded(piece, scene, { "all" }, processes());
  const vtkSmartPointer<vtkPolyData> whole = shadedWhole(mesh, scene, { "all" });
  vtkDataArray* flags = whole->GetPointData()->GetArray("shading_flags");
  ASSERT_NE(flags, nullptr);
  vtkIdType flipped = 0;
  for (vtkIdType i = 0; i < flags->GetNumberOfTuples(); ++i)
  {
    flipped += (int(flags->GetComponent(i, 0)) & shadelab::FlagNormalFlipped) != 0 ? 1 : 0;
  }
  EXPECT_GT(flipped, whole->GetNumberOfPoints() / 10); // two-sided: the vertices facing away are turned round
  if (holdsNone)
  {
    EXPECT_EQ(shadedPiece->GetNumberOfPoints(), 0);
    return;
  }
  EXPECT_GT(expectPieceOfWhole(whole, shadedPiece), 10);
}

// More processes than pieces: the process with an empty piece takes part in every bounce's
// exchange, and the others' pieces get the whole mesh's bounces.
TEST(SplitMeshInterreflection, AProcessWithAnEmptyPiece)
{
  const int count = processes()->GetNumberOfProcesses();
  if (count == 1)
  {
    GTEST_SKIP() << "one process holds the only piece";
  }
  const vtkSmartPointer<vtkPolyData> mesh = bunny();
  const int rank = processes()->GetLocalProcessId();
  const bool holdsNone = rank == count - 1;
  vtkSmartPointer<vtkPolyData> piece =
    holdsNone ? vtkSmartPointer<vtkPolyData>::New() : shadelab::app::meshPiece(mesh, rank, count - 1, 1);
  for (const std::string& scene : { bouncesUnderAMap(), twoSidedBounces() })
  {
    const vtkSmartPointer<vtkPolyData> shadedPiece = shaded(piece, scene, { "all" }, processes());
    const vtkSmartPointer<vtkPolyData> whole = shadedWhole(mesh, scene, { "all" });
    if (holdsNone)
    {
      EXPECT_EQ(shadedPiece->GetNumberOfPoints(), 0);
      continue;
    }
    EXPECT_GT(expectPieceOfWhole(whole, shadedPiece), 10);
  }
}

/// The bunny with its normals and a radiosity that varies over it, for the interreflection
/// filter alone.
vtkSmartPointer<vtkPolyData> glowingBunny()
{
  const vtkSmartPointer<vtkPolyData> mesh = normalsOfWhole(bunny());
  vtkNew<vtkDoubleArray> glow;
  glow->SetName("glow");
  glow->SetNumberOfComponents(3);
  glow->SetNumberOfTuples(mesh->GetNumberOfPoints());
  for (vtkIdType i = 0; i < mesh->GetNumberOfPoints(); ++i)
  {
    const double* p = mesh->GetPoint(i);
    glow->SetTuple3(i, 1 + 10 * p[1], 0.5, 1 + 10 * p[0]);
  }
  mesh->GetPointData()->AddArray(glow);
  return mesh;
}

/// vtkInterreflectionFilter alone on the mesh (or a piece), 2 bounces from "glow".
vtkSmartPointer<vtkPolyData> gatheredAlone(vtkPolyData* mesh, vtkMultiProcessController* controller)
{
  vtkNew<vtkInterreflectionFilter> filter;
  filter->SetController(controller);
  filter->SetInputData(mesh);
  filter->SetRadiosityArrayName("glow");
  filter->SetBounces(2);
  filter->SetSamples(16);
  filter->SetNumberOfThreads(1);
  filter->Update();
  auto output = vtkSmartPointer<vtkPolyData>::New();
  output->ShallowCopy(filter->GetOutput());
  return output;
}

// The interreflection filter alone, as a ParaView pipeline runs it: a process whose piece is
// empty has no arrays at all (a reader's empty piece), and takes part with none; the others'
// pieces get the whole mesh's values. One process's piece without the radiosity stops every
// process, none waits for it, and a later run completes.
TEST(SplitMeshInterreflection, TheFilterAloneOnPiecesAndAnEmptyOneWithoutArrays)
{
  const int count = processes()->GetNumberOfProcesses();
  const int rank = processes()->GetLocalProcessId();
  const vtkSmartPointer<vtkPolyData> mesh = glowingBunny();
  const vtkSmartPointer<vtkPolyData> whole = gatheredAlone(mesh, nullptr);
  const bool holdsNone = count > 1 && rank == count - 1;
  const vtkSmartPointer<vtkPolyData> piece =
    holdsNone ? vtkSmartPointer<vtkPolyData>::New() : shadelab::app::meshPiece(mesh, rank, std::max(count - 1, 1), 1);
  const vtkSmartPointer<vtkPolyData> gathered = gatheredAlone(piece, processes());
  if (!holdsNone)
  {
    EXPECT_GT(expectPieceOfWhole(whole, gathered), 2);
  }
  vtkSmartPointer<vtkPolyData> broken = vtkSmartPointer<vtkPolyData>::New();
  broken->DeepCopy(piece);
  if (rank == 0)
  {
    broken->GetPointData()->RemoveArray("glow");
  }
  EXPECT_EQ(gatheredAlone(broken, processes())->GetNumberOfPoints(), 0);
  EXPECT_EQ(gatheredAlone(piece, processes())->GetNumberOfPoints(), piece->GetNumberOfPoints());
}

// One process's piece cannot be shaded (it has an array of a name the filter writes): every
// process stops, none waits for it.
TEST(SplitMeshErrors, OneProcessFailsAndAllStop)
{
  vtkSmartPointer<vtkPolyData> piece = myPiece(bunny());
  if (processes()->GetLocalProcessId() == 0)
  {
    vtkNew<vtkDoubleArray> taken;
    taken->SetName("total");
    taken->SetNumberOfTuples(piece->GetNumberOfPoints());
    taken->Fill(0);
    piece->GetPointData()->AddArray(taken);
  }
  const vtkSmartPointer<vtkPolyData> output = shaded(piece, "studio.json", { "default" }, processes());
  EXPECT_EQ(output->GetNumberOfPoints(), 0);
  // The processes are still in step: a gathering after it completes.
  EXPECT_EQ(shaded(myPiece(bunny()), "studio.json", { "default" }, processes())->GetNumberOfPoints(),
    myPiece(bunny())->GetNumberOfPoints());
}

// Splitting at sharp edges adds points: refused on a split mesh, done on pieces in one process.
TEST(SplitMeshErrors, SplittingSharpEdges)
{
  vtkNew<vtkShadingNormalsFilter> normals;
  normals->SplitSharpEdgesOn();
  normals->SetInputData(myPiece(bunny(), 0));
  normals->Update();
  const vtkIdType pieceCount = myPiece(bunny(), 0)->GetNumberOfPoints();
  if (processes()->GetNumberOfProcesses() == 1)
  {
    EXPECT_GT(normals->GetOutput()->GetNumberOfPoints(), pieceCount);
    return;
  }
  EXPECT_EQ(normals->GetOutput()->GetNumberOfPoints(), 0);
}

TEST(SplitMeshErrors, CellOnTwoPieces)
{
  vtkSmartPointer<vtkPolyData> piece = myPiece(bunny(), 1);
  piece->GetCellData()->RemoveArray(vtkDataSetAttributes::GhostArrayName()); // ghosts counted as owned
  const shadelab::WholeMesh whole = shadelab::gatherWholeMesh(processes(), piece, true);
  if (processes()->GetNumberOfProcesses() == 1)
  {
    EXPECT_EQ(whole.problem, ""); // one piece has no ghost cells
    return;
  }
  EXPECT_EQ(whole.problem.rfind("the global cell id ", 0), 0u) << whole.problem;
  EXPECT_NE(
    whole.problem.find(" is on two pieces' polygons: mark the copies as ghost cells (vtkGhostType)"), std::string::npos)
    << whole.problem;
}
}
// Pieces that give a point they share two positions, or two stored normals, are refused by the
// normals computed piece by piece, with the message the whole mesh's gathering gives; the second
// process's copy is moved by a part in a million.
TEST(SplitMeshErrors, PiecesThatDisagreeOnASharedPoint)
{
  if (processes()->GetNumberOfProcesses() == 1)
  {
    GTEST_SKIP() << "one piece shares no point";
  }
  for (const std::string what : { "positions", "normals" })
  {
    const vtkSmartPointer<vtkPolyData> mesh = what == "normals" ? normalsOfWhole(bunny()) : bunny();
    vtkSmartPointer<vtkPolyData> piece = myPiece(mesh, 0);
    if (processes()->GetLocalProcessId() == 1)
    {
      vtkDataArray* values = what == "normals" ? piece->GetPointData()->GetNormals() : piece->GetPoints()->GetData();
      vtkSmartPointer<vtkDataArray> moved = vtk::TakeSmartPointer(values->NewInstance());
      moved->DeepCopy(values);
      for (vtkIdType p = 0; p < moved->GetNumberOfTuples(); ++p)
      {
        moved->SetComponent(p, 0, moved->GetComponent(p, 0) * (1 + 1e-6) + 1e-6);
      }
      if (what == "normals")
      {
        piece->GetPointData()->SetNormals(moved);
      }
      else
      {
        piece->GetPoints()->SetData(moved);
      }
    }
    vtkNew<vtkShadingNormalsFilter> normals;
    vtkNew<shadelab::app::VtkErrorCapture> errors;
    errors->watch(normals);
    normals->SetInputData(piece);
    normals->Update();
    EXPECT_EQ(normals->GetOutput()->GetNumberOfPoints(), 0) << what;
    EXPECT_EQ(errors->message().rfind("the point with global id ", 0), 0u) << errors->message();
    EXPECT_NE(errors->message().find(" has two different " + what +
                " in two pieces: the pieces are not of one mesh, or their global ids are wrong"),
      std::string::npos)
      << errors->message();
  }
}

int main(int argc, char** argv)
{
  vtkNew<vtkMPIController> controller;
  controller->Initialize(&argc, &argv);
  vtkMultiProcessController::SetGlobalController(controller);
  ::testing::InitGoogleTest(&argc, argv);
  // Every process prints its own results; any process's failure fails the run.
  int failed = RUN_ALL_TESTS();
  int anyFailed = 0;
  controller->AllReduce(&failed, &anyFailed, 1, vtkCommunicator::MAX_OP);
  controller->Finalize();
  return anyFailed;
}
