// The guards around reading and writing mesh files: work isolated in a child process ends in
// an outcome whatever it does, a PLY header's or OBJ's claims are checked against the file,
// and a temporary output does not outlive a run that is killed.
#include "IsolatedWork.h"
#include "MeshFileChecks.h"
#include "MeshFiles.h"
#include "MeshHandOver.h"

#include "vtkCellArray.h"
#include "vtkCellData.h"
#include "vtkDoubleArray.h"
#include "vtkFieldData.h"
#include "vtkFloatArray.h"
#include "vtkIntArray.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkStringArray.h"

#include <gtest/gtest.h>

#include <atomic>
#include <cerrno>
#include <chrono>
#include <csignal>
#include <filesystem>
#include <fstream>
#include <future>
#include <iterator>
#include <sys/stat.h>
#include <sys/wait.h>
#include <thread>
#include <unistd.h>
#include <vector>

// Whether AddressSanitizer is on: GCC defines __SANITIZE_ADDRESS__, clang has __has_feature.
#if defined(__SANITIZE_ADDRESS__)
#define SHADELAB_ADDRESS_SANITIZER 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define SHADELAB_ADDRESS_SANITIZER 1
#endif
#endif
#ifndef SHADELAB_ADDRESS_SANITIZER
#define SHADELAB_ADDRESS_SANITIZER 0
#endif

namespace
{
using namespace shadelab::app;
namespace fs = std::filesystem;

TEST(IsolatedWork, EveryEndingIsReported)
{
  IsolationLimits limits;
  limits.cpuSeconds = 1;
  limits.memoryBytes = std::size_t(256) << 20;

  const std::string bytes("bytes\0with a zero", 17);
  IsolatedOutcome done = runIsolated(
    [&](ChildChannel& channel)
    {
      channel.warning("a warning");
      std::ofstream(channel.resultPath(), std::ios::binary) << bytes;
      channel.finished();
    },
    limits);
  EXPECT_EQ(done.end, IsolatedOutcome::End::Finished);
  std::ifstream result(done.resultPath, std::ios::binary);
  EXPECT_EQ(std::string(std::istreambuf_iterator<char>(result), {}), bytes);
  EXPECT_EQ(done.warnings, std::vector<std::string>{ "a warning" });

  IsolatedOutcome failed = runIsolated([](ChildChannel&) { throw std::runtime_error("no such thing"); }, limits);
  EXPECT_EQ(failed.end, IsolatedOutcome::End::Failed);
  EXPECT_EQ(failed.error, "no such thing");

  IsolatedOutcome greedy = runIsolated(
    [](ChildChannel& channel)
    {
      std::vector<char> tooMuch(std::size_t(1) << 30, 1); // 1 GB against a 256 MB limit
      channel.warning(std::string(1, tooMuch[12345]));
    },
    limits);
#if SHADELAB_ADDRESS_SANITIZER
  // AddressSanitizer's allocator does not throw std::bad_alloc at an address-space limit: the
  // child dies of the failed allocation instead, which is still no result.
  EXPECT_TRUE(greedy.end == IsolatedOutcome::End::OutOfMemory || greedy.end == IsolatedOutcome::End::Crashed);
#else
  EXPECT_EQ(greedy.end, IsolatedOutcome::End::OutOfMemory);
#endif

  IsolatedOutcome crashed = runIsolated([](ChildChannel&) { std::raise(SIGSEGV); }, limits);
  EXPECT_EQ(crashed.end, IsolatedOutcome::End::Crashed);
  EXPECT_EQ(crashed.signalName, "SIGSEGV");

  IsolatedOutcome endless = runIsolated(
    [](ChildChannel&)
    {
      for (volatile unsigned long i = 0;; i = i + 1)
      {
      }
    },
    limits);
  EXPECT_EQ(endless.end, IsolatedOutcome::End::TimedOut);

  // A child that waits uses no processor time: the clock stops it.
  limits.wallSeconds = 1;
  IsolatedOutcome waiting = runIsolated([](ChildChannel&) { ::pause(); }, limits);
  EXPECT_EQ(waiting.end, IsolatedOutcome::End::Stalled);

  IsolatedOutcome silent = runIsolated([](ChildChannel&) {}, limits);
  EXPECT_EQ(silent.end, IsolatedOutcome::End::Crashed); // it ended without a word
  EXPECT_EQ(silent.signalName, "exit code 0");

  // What this process checks meanwhile stops the child when it finds a problem: an endless one
  // here, which its processor time (60 s) or the clock (an hour) would stop much later.
  limits.cpuSeconds = 60;
  limits.wallSeconds = 3600;
  IsolatedOutcome stopped = runIsolated(
    [](ChildChannel&)
    {
      for (volatile unsigned long i = 0;; i = i + 1)
      {
      }
    },
    limits, [] { return false; });
  EXPECT_EQ(stopped.end, IsolatedOutcome::End::Stopped);
  // A check that throws stops the child too, before its error goes on: no child is left.
  EXPECT_THROW(runIsolated(
                 [](ChildChannel&)
                 {
                   for (volatile unsigned long i = 0;; i = i + 1)
                   {
                   }
                 },
                 limits, []() -> bool { throw std::runtime_error("the check failed"); }),
    std::runtime_error);
  EXPECT_EQ(::waitpid(-1, nullptr, WNOHANG), -1);
  EXPECT_EQ(errno, ECHILD);
  bool checked = false;
  IsolatedOutcome kept = runIsolated([](ChildChannel& channel) { channel.finished(); }, limits,
    [&]
    {
      checked = true;
      return true;
    });
  EXPECT_TRUE(checked);
  EXPECT_EQ(kept.end, IsolatedOutcome::End::Finished);
}

// A thread still running when the child is forked may hold a lock the child needs (the
// allocator's, under AddressSanitizer): the child is forked once the other threads wait. Here
// one runs for 300 ms and then waits; the child sees what it did before waiting.
TEST(IsolatedWork, TheChildIsForkedOnceTheOtherThreadsWait)
{
  std::atomic<bool> started{ false }, ranToItsEnd{ false };
  std::promise<void> release;
  std::thread running(
    [&, waited = release.get_future()]
    {
      started = true;
      const auto end = std::chrono::steady_clock::now() + std::chrono::milliseconds(300);
      while (std::chrono::steady_clock::now() < end)
      {
      }
      ranToItsEnd = true;
      waited.wait();
    });
  while (!started)
  {
  }
  IsolatedOutcome outcome = runIsolated(
    [&](ChildChannel& channel)
    {
      std::ofstream(channel.resultPath()) << (ranToItsEnd ? "after" : "while it ran");
      channel.finished();
    },
    IsolationLimits());
  release.set_value();
  running.join();
  ASSERT_EQ(outcome.end, IsolatedOutcome::End::Finished);
  std::ifstream result(outcome.resultPath);
  EXPECT_EQ(std::string(std::istreambuf_iterator<char>(result), {}), "after");
}

/// A mesh with one of each kind of cell and arrays of several types, names and roles.
vtkSmartPointer<vtkPolyData> meshOfEveryPart()
{
  auto mesh = vtkSmartPointer<vtkPolyData>::New();
  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  for (int i = 0; i < 6; ++i)
  {
    points->InsertNextPoint(i, i * i, -i);
  }
  mesh->SetPoints(points);
  vtkNew<vtkCellArray> verts, lines, polys, strips;
  verts->InsertNextCell({ 0 });
  lines->InsertNextCell({ 0, 1 });
  polys->InsertNextCell({ 0, 1, 2 });
  polys->InsertNextCell({ 2, 3, 4, 5 });
  strips->InsertNextCell({ 1, 2, 3, 4 });
  mesh->SetVerts(verts);
  mesh->SetLines(lines);
  mesh->SetPolys(polys);
  mesh->SetStrips(strips);
  vtkNew<vtkFloatArray> normals;
  normals->SetName("my \"normals\" <&>");
  normals->SetNumberOfComponents(3);
  normals->SetComponentName(1, "why");
  for (int i = 0; i < 6; ++i)
  {
    normals->InsertNextTuple3(0, 0, i);
  }
  mesh->GetPointData()->SetNormals(normals);
  vtkNew<vtkIntArray> label;
  label->SetName("label");
  for (int c = 0; c < mesh->GetNumberOfCells(); ++c)
  {
    label->InsertNextValue(100 + c);
  }
  mesh->GetCellData()->SetScalars(label);
  vtkNew<vtkDoubleArray> time;
  time->SetName("time");
  time->InsertNextValue(2.5);
  mesh->GetFieldData()->AddArray(time);
  return mesh;
}

void expectSameMesh(vtkPolyData* a, vtkPolyData* b)
{
  ASSERT_EQ(a->GetNumberOfPoints(), b->GetNumberOfPoints());
  for (vtkIdType i = 0; i < a->GetNumberOfPoints(); ++i)
  {
    EXPECT_EQ(a->GetPoint(i)[1], b->GetPoint(i)[1]);
  }
  EXPECT_EQ(a->GetPoints()->GetDataType(), b->GetPoints()->GetDataType());
  for (const auto& [cellsA, cellsB] :
    { std::make_pair(a->GetVerts(), b->GetVerts()), std::make_pair(a->GetLines(), b->GetLines()),
      std::make_pair(a->GetPolys(), b->GetPolys()), std::make_pair(a->GetStrips(), b->GetStrips()) })
  {
    ASSERT_EQ(cellsA->GetNumberOfCells(), cellsB->GetNumberOfCells());
    ASSERT_EQ(cellsA->GetNumberOfConnectivityIds(), cellsB->GetNumberOfConnectivityIds());
    for (vtkIdType k = 0; k < cellsA->GetNumberOfConnectivityIds(); ++k)
    {
      EXPECT_EQ(cellsA->GetConnectivityArray()->GetComponent(k, 0), cellsB->GetConnectivityArray()->GetComponent(k, 0));
    }
  }
  vtkDataArray* normals = b->GetPointData()->GetNormals();
  ASSERT_NE(normals, nullptr);
  EXPECT_STREQ(normals->GetName(), "my \"normals\" <&>");
  EXPECT_STREQ(normals->GetComponentName(1), "why");
  EXPECT_EQ(normals->GetComponent(5, 2), 5.0);
  ASSERT_NE(b->GetCellData()->GetScalars(), nullptr);
  EXPECT_EQ(b->GetCellData()->GetScalars()->GetDataType(), VTK_INT);
  EXPECT_EQ(b->GetCellData()->GetScalars()->GetComponent(4, 0), 104.0);
  ASSERT_NE(b->GetFieldData()->GetArray("time"), nullptr);
  EXPECT_EQ(b->GetFieldData()->GetArray("time")->GetComponent(0, 0), 2.5);
}

TEST(MeshHandOver, EveryPartOfAMeshCrossesAsItWas)
{
  const fs::path file = fs::temp_directory_path() / ("shadelab-handover-" + std::to_string(::getpid()));
  vtkSmartPointer<vtkPolyData> mesh = meshOfEveryPart();
  std::ofstream(file.string()).close();
  handOverMesh(mesh, file.string());
  expectSameMesh(mesh, takeOverMesh(file.string()));

  // A string array cannot go as raw bytes: the whole mesh goes as XML, names and all.
  vtkNew<vtkStringArray> note;
  note->SetName("note");
  note->InsertNextValue("a string");
  mesh->GetFieldData()->AddArray(note);
  std::ofstream(file.string(), std::ios::trunc).close();
  handOverMesh(mesh, file.string());
  vtkSmartPointer<vtkPolyData> throughXml = takeOverMesh(file.string());
  expectSameMesh(mesh, throughXml);
  EXPECT_EQ(
    vtkStringArray::SafeDownCast(throughXml->GetFieldData()->GetAbstractArray("note"))->GetValue(0), "a string");
  fs::remove(file);
}

TEST(MeshHandOver, ADamagedTableIsRefused)
{
  const fs::path file = fs::temp_directory_path() / ("shadelab-handover-" + std::to_string(::getpid()));
  std::ofstream(file.string()).close();
  handOverMesh(meshOfEveryPart(), file.string());
  {
    // An array said to lie beyond the end of the file: the first entry's offset, after the
    // magic, the table's length, the count and four 4-byte and one 8-byte fields.
    std::fstream damage(file.string(), std::ios::in | std::ios::out | std::ios::binary);
    damage.seekp(8 + 8 + 8 + 16 + 8);
    const std::uint64_t farAway = std::uint64_t(1) << 40;
    damage.write(reinterpret_cast<const char*>(&farAway), sizeof farAway);
  }
  try
  {
    takeOverMesh(file.string());
    ADD_FAILURE() << "a damaged table was taken over";
  }
  catch (const std::runtime_error& error)
  {
    EXPECT_STREQ(error.what(), "the reading process handed over a damaged mesh");
  }
  fs::remove(file);
}

TEST(ReadMesh, APipeIsRefusedBeforeAnythingWaitsOnIt)
{
  const fs::path pipe = fs::temp_directory_path() / ("shadelab-pipe-" + std::to_string(::getpid()) + ".ply");
  ASSERT_EQ(::mkfifo(pipe.c_str(), 0600), 0);
  try
  {
    readMesh(pipe.string());
    ADD_FAILURE() << "a pipe was read";
  }
  catch (const UserError& error)
  {
    EXPECT_EQ(std::string(error.what()),
      pipe.string() + ": not a regular file (a pipe or a device?): save the mesh to a file first");
  }
  fs::remove(pipe);
}

TEST(IsolatedWork, PrintableTextHidesBinaryBytes)
{
  EXPECT_EQ(printableText(std::string("ok \x01\xff\n end", 10)), "ok ??? end");
  EXPECT_EQ(printableText(std::string(300, 'a'), 5), "aaaaa...");
}

TEST(MeshFileChecks, PlyHeaderCountsAgainstTheFileSize)
{
  const std::string header = "ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\n"
                             "property float y\nproperty float z\nelement face 1\n"
                             "property list uchar int vertex_indices\nend_header\n";
  // 3 vertices of 12 bytes and a face of at least 1 byte: 37 bytes after the header.
  EXPECT_EQ(plyHeaderProblem(header, header.size() + 37), "");
  EXPECT_EQ(plyHeaderProblem(header, header.size() + 35),
    "the PLY header declares 3 vertices and 1 faces, which need at least 37 bytes, but the file has 35 after its "
    "header: it is cut short or its counts are wrong");
  const std::string ascii =
    "ply\r\nformat ascii 1.0\r\ncomment made by hand\r\nelement vertex 1\r\nproperty double x\r\n"
    "property double y\r\nproperty double z\r\nend_header\r\n";
  EXPECT_EQ(plyHeaderProblem(ascii, ascii.size() + 5), ""); // "0 0 0": 2 bytes a value, the last without a separator
  EXPECT_EQ(
    plyHeaderProblem("ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\nend_header\n", 100),
    "the PLY header's vertex element has no x, y and z properties");
  EXPECT_EQ(plyHeaderProblem("ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float x\n", 100),
    "line 5 of the PLY header ('property float x') repeats the property 'x' of element 'vertex'");
  EXPECT_EQ(plyHeaderProblem("ply\nformat ascii 1.0\nelement vertex 1\n", 100),
    "the PLY header has no end_header line (a damaged file, or the header is longer than 1 MB)");
  EXPECT_EQ(plyHeaderProblem("solid cube\n", 100), "not a PLY file (it does not start with a PLY header)");
}

TEST(MeshFileChecks, ObjFaceIndicesReferToListedVertices)
{
  const std::string triangle = "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\n";
  EXPECT_EQ(objFileCheck(triangle + "f 1/1 2/1 3/1\n").problem, "");
  EXPECT_EQ(objFileCheck(triangle + "f -3 -2 -1\n").problem, ""); // relative to the last vertex
  EXPECT_EQ(objFileCheck(triangle + "f 1 2 4\n").problem,
    "line 5: face index 4 refers to vertex 4, but the file lists 3 before that line");
  EXPECT_EQ(objFileCheck(triangle + "f 1//1 2//1 3//1\n").problem,
    "line 5: face index 1 refers to normal 1, but the file lists 0 before that line");
  EXPECT_EQ(objFileCheck(triangle + "f 0 1 2\n").problem,
    "line 5: face index 0 refers to no vertex: OBJ indices start at 1 (and negative ones count back from the last "
    "listed, -1 for the last)");
  EXPECT_EQ(objFileCheck(triangle + "f 1 2 x\n").problem, "line 5: 'x' is not an OBJ face corner");
}

TEST(WriteMesh, ArrayNamesAVtpCannotHoldAreRefused)
{
  // VTK 9.1 writes array names into XML attributes unescaped: a quote would make a file no
  // reader opens. Legacy .vtk encodes names, so it takes them.
  const fs::path folder = fs::temp_directory_path() / "shadelab_unsafe_names";
  fs::remove_all(folder);
  fs::create_directories(folder);
  vtkNew<vtkPolyData> mesh;
  vtkNew<vtkPoints> points;
  points->InsertNextPoint(0, 0, 0);
  mesh->SetPoints(points);
  vtkNew<vtkFloatArray> quoted;
  quoted->SetName("temperature \"K\"");
  quoted->InsertNextValue(1);
  mesh->GetPointData()->AddArray(quoted);
  const std::string vtp = (folder / "out.vtp").string();
  try
  {
    writeMesh(mesh, vtp);
    ADD_FAILURE() << "no error";
  }
  catch (const UserError& error)
  {
    EXPECT_EQ(std::string(error.what()),
      vtp +
        ": the point array 'temperature \"K\"' has a name that a .vtp file "
        "cannot hold (VTK 9.1 writes it unescaped, and no reader could open the file): rename it in the input, or "
        "write legacy .vtk");
  }
  EXPECT_TRUE(fs::is_empty(folder));
  const std::string vtk = (folder / "out.vtk").string();
  writeMesh(mesh, vtk);
  EXPECT_EQ(readMesh(vtk)->GetPointData()->GetArray(0)->GetName(), std::string("temperature \"K\""));
  fs::remove_all(folder);
}

TEST(WriteThroughTemporary, AKilledRunLeavesNoTemporary)
{
  const fs::path folder = fs::temp_directory_path() / "shadelab_killed_write";
  fs::remove_all(folder);
  fs::create_directories(folder);
  const std::string target = (folder / "out.vtp").string();
  const pid_t child = ::fork();
  if (child == 0)
  {
    writeThroughTemporary(target,
      [](const std::string& temporary)
      {
        std::ofstream(temporary) << "half a file";
        std::raise(SIGTERM); // killed while writing
        return std::string();
      });
    ::_exit(0);
  }
  int status = 0;
  ::waitpid(child, &status, 0);
  ASSERT_TRUE(WIFSIGNALED(status));
  EXPECT_EQ(WTERMSIG(status), SIGTERM); // the signal still ends the run, after the clean-up
  EXPECT_TRUE(fs::is_empty(folder));
  fs::remove_all(folder);
}

TEST(WriteThroughTemporary, AnExceptionLeavesNoTemporary)
{
  const fs::path folder = fs::temp_directory_path() / "shadelab_failed_write";
  fs::remove_all(folder);
  fs::create_directories(folder);
  const std::string target = (folder / "out.vtp").string();
  try
  {
    writeThroughTemporary(target,
      [](const std::string& temporary) -> std::string
      {
        std::ofstream(temporary) << "half a file";
        throw std::bad_alloc();
      });
    ADD_FAILURE() << "no error";
  }
  catch (const UserError& error)
  {
    EXPECT_EQ(std::string(error.what()), target + ": cannot be written: not enough memory to write it");
  }
  EXPECT_TRUE(fs::is_empty(folder));
  fs::remove_all(folder);
}
}
