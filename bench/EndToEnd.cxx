#include "EndToEnd.h"

#include "BenchmarkMeshes.h"
#include "GltfScene.h"
#include "MemoryProbe.h"
#include "MeshFiles.h"

#include "DefaultLightKit.h"
#include "SceneFile.h"
#include "vtkLocalReflectanceFilter.h"
#include "vtkShadingNormalsFilter.h"

#include "vtkCellArray.h"
#include "vtkCellData.h"
#include "vtkDataArray.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkSMPTools.h"

#include <cstdio>
#include <filesystem>
#include <iomanip>
#include <iostream>
#include <unistd.h>

namespace shadelab::app
{
namespace
{
namespace fs = std::filesystem;

std::size_t arrayBytes(vtkAbstractArray* array)
{
  return array
    ? static_cast<std::size_t>(array->GetNumberOfValues()) * static_cast<std::size_t>(array->GetDataTypeSize())
    : 0;
}

/// The bytes of the mesh's points and cells, and of its point and cell data.
std::size_t meshBytes(vtkPolyData* mesh)
{
  std::size_t bytes = arrayBytes(mesh->GetPoints() ? mesh->GetPoints()->GetData() : nullptr);
  for (vtkCellArray* cells : { mesh->GetVerts(), mesh->GetLines(), mesh->GetPolys(), mesh->GetStrips() })
  {
    bytes += arrayBytes(cells->GetOffsetsArray()) + arrayBytes(cells->GetConnectivityArray());
  }
  for (vtkFieldData* data :
    { static_cast<vtkFieldData*>(mesh->GetPointData()), static_cast<vtkFieldData*>(mesh->GetCellData()) })
  {
    for (int a = 0; a < data->GetNumberOfArrays(); ++a)
    {
      bytes += arrayBytes(data->GetAbstractArray(a));
    }
  }
  return bytes;
}

/// VTK's reader alone, or for a glTF file its importer alone (whose actors are not a mesh: an
/// empty one is returned).
vtkSmartPointer<vtkPolyData> readAlone(const std::string& file)
{
  if (isGltfFile(file))
  {
    importGltfAlone(file);
    return vtkSmartPointer<vtkPolyData>::New();
  }
  vtkSmartPointer<vtkAlgorithm> reader = vtkReaderFor(file);
  reader->Update();
  auto mesh = vtkSmartPointer<vtkPolyData>::New();
  mesh->ShallowCopy(reader->GetOutputDataObject(0));
  return mesh;
}

/// The mesh with the normals the filter computes, or only checks (with the mesh's own).
vtkSmartPointer<vtkPolyData> withNormals(vtkPolyData* mesh)
{
  vtkNew<vtkShadingNormalsFilter> normals;
  normals->SetInputData(mesh);
  normals->Update();
  auto output = vtkSmartPointer<vtkPolyData>::New();
  output->ShallowCopy(normals->GetOutput());
  return output;
}

void printStage(const char* name, double milliseconds, const char* note)
{
  std::cout << "  " << std::left << std::setw(34) << name << std::right << std::setw(9) << std::fixed
            << std::setprecision(1) << milliseconds << " ms  " << note << "\n";
}
}

void runEndToEnd(const EndToEndOptions& options)
{
  const Scene scene = options.scene.empty() ? defaultLightKit() : readSceneFile(options.scene);
  const std::string output =
    (fs::temp_directory_path() / ("shadelab-bench-" + std::to_string(::getpid()) + ".vtp")).string();
  const std::string floorOutput = output + ".floor.vtp";

  // Memory first, on a fresh read: the peak above the resident size before reading.
  resetPeakMemory();
  const std::optional<std::size_t> before = statusBytes("VmRSS");
  std::size_t inputBytes = 0, writtenBytes = 0, pointCount = 0;
  {
    vtkSmartPointer<vtkPolyData> mesh = readMesh(options.mesh);
    vtkSmartPointer<vtkPolyData> result = shaded(mesh, scene);
    writeMesh(result, output);
    inputBytes = meshBytes(mesh);
    writtenBytes = meshBytes(result) - inputBytes;
    pointCount = static_cast<std::size_t>(mesh->GetNumberOfPoints());
  }
  const std::optional<std::size_t> peak = statusBytes("VmHWM");

  vtkSmartPointer<vtkPolyData> mesh = readMesh(options.mesh);
  const bool hasNormals = mesh->GetPointData()->GetNormals() != nullptr;
  vtkSmartPointer<vtkPolyData> meshWithNormals = withNormals(mesh);
  vtkSmartPointer<vtkPolyData> result = shaded(mesh, scene);
  const std::vector<double> ms = interleavedMedianMilliseconds(
    {
      [&] { readMesh(options.mesh); },
      [&] { readAlone(options.mesh); },
      [&] { withNormals(mesh); },
      [&] { withNormals(meshWithNormals); },
      [&] { shaded(mesh, scene); },
      [&] { shaded(meshWithNormals, scene); },
      [&] { writeMesh(result, output); },
      [&] { vtkWriterFor(result, floorOutput, ".vtp", Compression::LZ4)->Update(); },
    },
    options.minRepeats, options.minRepeats);
  fs::remove(output);
  fs::remove(floorOutput);
  const double read = ms[0], readFloor = ms[1], normals = ms[2], orientation = ms[3], shade = ms[4],
               shadeGivenNormals = ms[5], write = ms[6], writeFloor = ms[7];

  std::cout << "shadelab-bench --end-to-end: " << options.mesh << ", " << pointCount << " vertices, "
            << vtkSMPTools::GetEstimatedNumberOfThreads() << " threads, float32, "
            << (options.scene.empty() ? "the default light kit" : options.scene) << "; medians of "
            << options.minRepeats << " rounds taken in turn:\n";
  printStage("read (shadelab)", read, "checks, VTK's reader in its own process, hand-over");
  printStage(isGltfFile(options.mesh) ? "  floor: VTK's importer alone" : "  floor: VTK's reader alone", readFloor,
    "in this process, no checks");
  printStage("normals", normals,
    hasNormals ? "the mesh has normals: kept, orientation checked"
               : "computed, with the winding's orientation, in one pass");
  printStage("orientation of given normals", orientation, "what a mesh with normals pays instead");
  printStage("shade stage (normals + shading)", shade, "what shadelab shade reports as 'shade'");
  printStage("  shading alone", shadeGivenNormals, "on the mesh with its normals (orientation checked)");
  printStage("write (shadelab)", write, "LZ4 .vtp through a temporary file");
  printStage("  floor: VTK's writer alone", writeFloor, "the same output, the same settings");
  const double whole = read + shade + write, floor = readFloor + writeFloor;
  std::cout << "  whole command / (read + write floors): " << std::setprecision(1) << whole << " / " << floor
            << " ms = " << std::setprecision(2) << whole / floor << " (target 1.3)\n";
  std::cout << "  shade stage: " << std::setprecision(0) << shade << " ms (target 250 ms on 2.2M vertices)\n";
  if (before && peak)
  {
    const double peakMegabytes = (static_cast<double>(*peak) - static_cast<double>(*before)) / 1e6;
    const double bytesMegabytes = static_cast<double>(inputBytes + writtenBytes) / 1e6;
    std::cout << "  peak memory above the start: " << std::setprecision(1) << peakMegabytes << " MB for "
              << bytesMegabytes << " MB of mesh (" << inputBytes / 1e6 << ") and arrays written (" << writtenBytes / 1e6
              << "): " << std::setprecision(2) << peakMegabytes / bytesMegabytes
              << " (target 1.3); the program itself held " << std::setprecision(1) << *before / 1e6
              << " MB before reading\n";
  }
}
}
