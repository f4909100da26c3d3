#include "Benchmark.h"

#include "CalculatorBaseline.h"
#include "MemoryProbe.h"
#include "MeshFiles.h"

#include "vtkLocalReflectanceFilter.h"

#include "vtkArrayCalculator.h"
#include "vtkCleanPolyData.h"
#include "vtkDataArray.h"
#include "vtkLoopSubdivisionFilter.h"
#include "vtkPointData.h"
#include "vtkDataSet.h"
#include "vtkFieldData.h"
#include "vtkSMPTools.h"
#include "vtkSphereSource.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>
#include <malloc.h>
#include <fstream>
#include <functional>
#include <iomanip>
#include <iostream>
#include <sstream>

namespace shadelab::app
{
namespace
{
using Clock = std::chrono::steady_clock;

struct Mesh
{
  std::string name;
  vtkSmartPointer<vtkPolyData> data;
};

struct Case
{
  std::string name;
  Scene scene;
  std::vector<std::string> arrays;
  /// What vtkArrayCalculator computes as the same thing: "diffuse", "total" or nothing.
  std::string calculatorArray;
};

/// Median time in milliseconds of run(), repeated until maxRepeats runs or about a second.
double medianMilliseconds(const std::function<void()>& run, int maxRepeats)
{
  std::vector<double> times;
  const Clock::time_point start = Clock::now();
  do
  {
    const Clock::time_point begin = Clock::now();
    run();
    times.push_back(std::chrono::duration<double, std::milli>(Clock::now() - begin).count());
  } while (static_cast<int>(times.size()) < maxRepeats &&
    std::chrono::duration<double>(Clock::now() - start).count() < 1.0);
  std::sort(times.begin(), times.end());
  return times[times.size() / 2];
}

/// The mesh with the normals ShadeLab itself would compute and orient outward (the bunny's
/// point inward), so that the calculator baseline sees the same normals as the filter.
vtkSmartPointer<vtkPolyData> withOutwardNormals(vtkPolyData* mesh)
{
  Scene scene;
  scene.lights = { { "sun", DistantLight{} } };
  vtkNew<vtkLocalReflectanceFilter> prepare;
  prepare->SetInputData(mesh);
  prepare->SetScene(scene);
  prepare->SetArraySelection({ "shading_flags" });
  prepare->Update();
  if (!prepare->GetOutput()->GetPointData()->GetNormals())
  {
    throw UserError("the benchmark's mesh could not be given normals");
  }
  auto prepared = vtkSmartPointer<vtkPolyData>::New();
  prepared->ShallowCopy(prepare->GetOutput());
  prepared->GetPointData()->RemoveArray("shading_flags");
  prepared->GetFieldData()->Initialize();
  return prepared;
}

/// A UV sphere with about `points` vertices and exact unit normals.
Mesh sphereOfAbout(long long points)
{
  const int resolution = std::max(3, static_cast<int>(std::lround(std::sqrt(static_cast<double>(points)))));
  vtkNew<vtkSphereSource> sphere;
  sphere->SetThetaResolution(resolution);
  sphere->SetPhiResolution(resolution + 2);
  sphere->Update();
  return { "sphere", sphere->GetOutput() };
}

/// The Stanford bunny Loop-subdivided until it has the number of vertices closest to
/// `points` (35,947 x about 4 per level), or nothing if no level is within a factor 2.5.
std::optional<Mesh> bunnyOfAbout(const std::string& file, long long points)
{
  // vtkLoopSubdivisionFilter gives nothing for a mesh with unused points (the bunny has
  // 1,113): merged and compacted first.
  vtkNew<vtkCleanPolyData> clean;
  clean->SetInputData(readMesh(file));
  clean->Update();
  vtkSmartPointer<vtkPolyData> bunny = clean->GetOutput();
  int levels = 0;
  double estimate = bunny->GetNumberOfPoints();
  while (std::abs(std::log(estimate * 4 / points)) < std::abs(std::log(estimate / points)))
  {
    estimate *= 4;
    ++levels;
  }
  if (std::abs(std::log(estimate / points)) > std::log(2.5))
  {
    return std::nullopt;
  }
  if (levels > 0)
  {
    vtkNew<vtkLoopSubdivisionFilter> subdivide;
    subdivide->SetInputData(bunny);
    subdivide->SetNumberOfSubdivisions(levels);
    subdivide->Update();
    bunny = subdivide->GetOutput();
    if (bunny->GetNumberOfPoints() == 0)
    {
      throw UserError(file + ": vtkLoopSubdivisionFilter could not subdivide it");
    }
  }
  return Mesh{ "bunny x" + std::to_string(1 << (2 * levels)), withOutwardNormals(bunny) };
}

/// The lighting cases, with lights placed around a mesh of this centre and radius.
std::vector<Case> casesAround(const glm::dvec3& centre, double radius)
{
  auto at = [&](double x, double y, double z) { return centre + radius * glm::dvec3(x, y, z); };
  auto point = [&](const char* name, glm::dvec3 position, double intensity)
  {
    PointLight light;
    light.position = position;
    light.intensity = intensity * radius * radius; // about 1 at the mesh
    return NamedLight{ name, light };
  };
  auto distant = [](const char* name, glm::dvec3 direction, double intensity)
  { return NamedLight{ name, DistantLight{ direction, Rgb(1.0), intensity, false } }; };

  Scene base;
  base.viewer.position = at(0, 0, 4);
  base.material = { Rgb(0.8, 0.6, 0.4), Rgb(0.8, 0.6, 0.4), Rgb(0.3), 30.0, SpecularModel::BlinnPhong, false };
  const NamedLight room{ "room", AmbientLight{ Rgb(1.0), 0.1 } };

  Scene lambert = base;
  lambert.material.specular = SpecularModel::None;
  lambert.lights = { distant("sun", { -1, -1, -1 }, 1.0) };

  Scene one = base;
  one.lights = { point("key", at(2, 2, 2), 12.0), room };

  Scene three = base;
  three.lights = { point("key", at(2, 2, 2), 12.0), distant("fill", { 1, -0.2, -0.6 }, 0.4),
    point("back", at(-2, 1, -2), 9.0), room };

  Scene eight = base;
  const char* names[] = { "p0", "d0", "p1", "d1", "p2", "d2", "p3", "d3" };
  for (int l = 0; l < 8; ++l)
  {
    const double angle = l * 0.785398;
    eight.lights.push_back(l % 2 == 0 ? point(names[l], at(3 * std::cos(angle), 1.5, 3 * std::sin(angle)), 4.0)
                                      : distant(names[l], { -std::cos(angle), -0.5, -std::sin(angle) }, 0.2));
  }
  eight.lights.push_back(room);

  Scene threeMatte = three;
  threeMatte.material.specular = SpecularModel::None;

  return {
    { "lambert", lambert, { "diffuse" }, "diffuse" },
    { "complete, 1 point light", one, { "total" }, "total" },
    { "complete, 3 lights", three, { "total" }, "total" },
    { "complete, 8 lights", eight, { "total" }, "total" },
    { "all 40 arrays, 3 lights", three, { "all" }, "" },
    // The pair that shows an unrequested term costs nothing: the shiny material's specular
    // lobes are not computed when only the diffuse total is asked for.
    { "diffuse only, 3 lights, shiny", three, { "diffuse" }, "diffuse" },
    { "diffuse only, 3 lights, matte", threeMatte, { "diffuse" }, "diffuse" },
  };
}

/// The bytes of the arrays the filter added.
std::size_t addedBytes(vtkPolyData* input, vtkPolyData* output)
{
  std::size_t bytes = 0;
  vtkPointData* pointData = output->GetPointData();
  for (int a = 0; a < pointData->GetNumberOfArrays(); ++a)
  {
    vtkDataArray* array = pointData->GetArray(a);
    if (!input->GetPointData()->HasArray(array->GetName()))
    {
      bytes += array->GetNumberOfValues() * array->GetDataTypeSize();
    }
  }
  return bytes;
}

struct Row
{
  long long vertices;
  std::string mesh, name;
  double firstMilliseconds, milliseconds, floorMilliseconds;
  std::optional<double> calculatorMilliseconds, calculatorDifference;
  std::optional<double> peakMegabytes;
  double arrayMegabytes;
};

/// The floor: reading the input bytes and writing the output bytes once, with memcpy and
/// memset into buffers that are already mapped.
double floorMilliseconds(vtkPolyData* mesh, std::size_t outputBytes, int repeats)
{
  vtkDataArray* points = mesh->GetPoints()->GetData();
  vtkDataArray* normals = mesh->GetPointData()->GetNormals();
  const std::size_t pointBytes = points->GetNumberOfValues() * points->GetDataTypeSize();
  const std::size_t normalBytes = normals->GetNumberOfValues() * normals->GetDataTypeSize();
  std::vector<char> in(pointBytes + normalBytes, 1), out(outputBytes, 1);
  return medianMilliseconds(
    [&]
    {
      std::memcpy(in.data(), points->GetVoidPointer(0), pointBytes);
      std::memcpy(in.data() + pointBytes, normals->GetVoidPointer(0), normalBytes);
      std::memset(out.data(), static_cast<int>(in[in.size() / 2]), out.size());
    },
    repeats);
}

Row measure(const Mesh& mesh, const Case& c, int repeats)
{
  Row row{ mesh.data->GetNumberOfPoints(), mesh.name, c.name, 0, 0, 0, {}, {}, {}, 0 };
  vtkNew<vtkLocalReflectanceFilter> filter;
  filter->SetInputData(mesh.data);
  filter->SetScene(c.scene);
  filter->SetArraySelection(c.arrays);

  // The first run, which also prepares the normals, and its peak memory above what the
  // process held before it.
  const std::optional<std::size_t> before = statusBytes("VmRSS");
  const bool peakReset = resetPeakMemory();
  const Clock::time_point firstStart = Clock::now();
  filter->Update();
  row.firstMilliseconds = std::chrono::duration<double, std::milli>(Clock::now() - firstStart).count();
  const std::optional<std::size_t> peak = statusBytes("VmHWM");
  if (peakReset && before && peak)
  {
    row.peakMegabytes = (static_cast<double>(*peak) - static_cast<double>(*before)) / 1e6;
  }
  const std::size_t outputBytes = addedBytes(mesh.data, filter->GetOutput());
  row.arrayMegabytes = outputBytes / 1e6;
  row.milliseconds = medianMilliseconds(
    [&]
    {
      filter->Modified();
      filter->Update();
    },
    repeats);

  if (const std::optional<std::string> expression =
        c.calculatorArray.empty() ? std::nullopt : calculatorExpression(c.scene, c.calculatorArray == "diffuse"))
  {
    vtkNew<vtkArrayCalculator> calculator;
    calculator->SetInputData(mesh.data);
    calculator->AddVectorArrayName(mesh.data->GetPointData()->GetNormals()->GetName(), 0, 1, 2);
    calculator->AddCoordinateVectorVariable("coords", 0, 1, 2);
    calculator->SetFunction(expression->c_str());
    calculator->SetResultArrayName("calculator");
    calculator->SetResultArrayType(VTK_FLOAT);
    row.calculatorMilliseconds = medianMilliseconds(
      [&]
      {
        calculator->Modified();
        calculator->Update();
      },
      repeats);
    vtkDataArray* ours = filter->GetOutput()->GetPointData()->GetArray(c.calculatorArray.c_str());
    vtkDataArray* theirs = vtkDataSet::SafeDownCast(calculator->GetOutput())->GetPointData()->GetArray("calculator");
    double largest = 0;
    for (vtkIdType v = 0; v < ours->GetNumberOfValues(); ++v)
    {
      largest = std::max(largest, std::abs(ours->GetComponent(v / 3, v % 3) - theirs->GetComponent(v / 3, v % 3)));
    }
    row.calculatorDifference = largest;
  }
  row.floorMilliseconds = floorMilliseconds(mesh.data, outputBytes, repeats);
  return row;
}

std::string fixed(std::optional<double> value, int decimals)
{
  if (!value)
  {
    return "-";
  }
  std::ostringstream text;
  text << std::fixed << std::setprecision(decimals) << *value;
  return text.str();
}

std::string scientific(std::optional<double> value)
{
  if (!value)
  {
    return "-";
  }
  std::ostringstream text;
  text << std::scientific << std::setprecision(1) << *value;
  return text.str();
}

struct Column
{
  const char* title;
  int width;
  std::function<std::string(const Row&)> cell;
};

const std::vector<Column>& columns()
{
  static const std::vector<Column> all = {
    { "vertices", 10, [](const Row& r) { return std::to_string(r.vertices); } },
    { "mesh", 11, [](const Row& r) { return r.mesh; } },
    { "case", 31, [](const Row& r) { return r.name; } },
    { "first ms", 9, [](const Row& r) { return fixed(r.firstMilliseconds, 2); } },
    { "ms", 9, [](const Row& r) { return fixed(r.milliseconds, 2); } },
    { "Mvertices/s", 12, [](const Row& r) { return fixed(r.vertices / r.milliseconds / 1e3, 1); } },
    { "x floor", 8, [](const Row& r) { return fixed(r.milliseconds / r.floorMilliseconds, 1); } },
    { "floor ms", 9, [](const Row& r) { return fixed(r.floorMilliseconds, 2); } },
    { "calculator ms", 14, [](const Row& r) { return fixed(r.calculatorMilliseconds, 1); } },
    { "x faster", 9,
      [](const Row& r)
      {
        return r.calculatorMilliseconds ? fixed(*r.calculatorMilliseconds / r.milliseconds, 1) : "-";
      } },
    { "max |diff|", 11, [](const Row& r) { return scientific(r.calculatorDifference); } },
    { "peak MB", 9, [](const Row& r) { return fixed(r.peakMegabytes, 1); } },
    { "arrays MB", 10, [](const Row& r) { return fixed(r.arrayMegabytes, 1); } },
  };
  return all;
}

void printRow(const Row& row)
{
  for (const Column& column : columns())
  {
    std::cout << std::setw(column.width) << column.cell(row) << " ";
  }
  std::cout << std::endl;
}
}

void runBenchmark(const BenchmarkOptions& options)
{
  // Blocks of 1 MB and more are mapped and unmapped on their own, so that resident memory
  // follows what is allocated (glibc otherwise keeps freed blocks resident for reuse, and a
  // run's peak would not show its arrays).
  mallopt(M_MMAP_THRESHOLD, 1 << 20);
  if (!options.csvFile.empty())
  {
    checkOutputFile(options.csvFile, { ".csv" });
  }
  std::cout << "shadelab bench: " << vtkSMPTools::GetEstimatedNumberOfThreads()
            << " threads, float32. first ms: the first run, which also prepares the normals; "
               "ms: the median of up to "
            << options.maxRepeats
            << " later runs (new lights on the same mesh); x floor: ms / (memcpy of the input and "
               "memset of the output bytes);\nx faster: vtkArrayCalculator's time for the same "
               "expression / ms; max |diff|: between the two results; peak MB: resident memory "
               "above the start of the first run; arrays MB: the arrays written.\n";
  for (const Column& column : columns())
  {
    std::cout << std::setw(column.width) << column.title << " ";
  }
  std::cout << "\n";

  std::vector<Row> rows;
  for (const long long size : options.sizes)
  {
    std::vector<Mesh> meshes{ sphereOfAbout(size) };
    if (!options.bunnyFile.empty())
    {
      if (std::optional<Mesh> bunny = bunnyOfAbout(options.bunnyFile, size))
      {
        meshes.push_back(*bunny);
      }
    }
    for (const Mesh& mesh : meshes)
    {
      double bounds[6];
      mesh.data->GetBounds(bounds);
      const glm::dvec3 centre{ (bounds[0] + bounds[1]) / 2, (bounds[2] + bounds[3]) / 2, (bounds[4] + bounds[5]) / 2 };
      const double radius = 0.5 * glm::length(glm::dvec3(bounds[1] - bounds[0], bounds[3] - bounds[2], bounds[5] - bounds[4]));
      for (const Case& c : casesAround(centre, radius))
      {
        rows.push_back(measure(mesh, c, options.maxRepeats));
        printRow(rows.back());
      }
    }
  }

  if (!options.csvFile.empty())
  {
    writeThroughTemporary(options.csvFile,
      [&](const std::string& temporary) -> std::string
      {
        std::ofstream csv(temporary);
        for (std::size_t c = 0; c < columns().size(); ++c)
        {
          csv << (c ? "," : "") << columns()[c].title;
        }
        csv << "\n";
        for (const Row& row : rows)
        {
          for (std::size_t c = 0; c < columns().size(); ++c)
          {
            const std::string cell = columns()[c].cell(row);
            csv << (c ? "," : "") << (cell.find(',') != std::string::npos ? "\"" + cell + "\"" : cell);
          }
          csv << "\n";
        }
        csv.close();
        return csv ? "" : "the CSV could not be written (disk full?)";
      });
    std::cout << "wrote " << options.csvFile << "\n";
  }
}
}
