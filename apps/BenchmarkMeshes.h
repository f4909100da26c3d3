#pragma once
// What `shadelab bench` and its accuracy studies share: the meshes and the timer.
#include "vtkPolyData.h"
#include "vtkSmartPointer.h"

#include <functional>
#include <optional>
#include <string>

namespace shadelab::app
{
struct Mesh
{
  std::string name;
  vtkSmartPointer<vtkPolyData> data;
};

/// Median time in milliseconds of run(): at least minRepeats runs, then more up to
/// maxRepeats while they fit in about two seconds.
double medianMilliseconds(const std::function<void()>& run, int minRepeats, int maxRepeats);

/// A UV sphere with about `points` vertices and exact unit normals.
Mesh sphereOfAbout(long long points);

/// The Stanford bunny, merged and compacted.
vtkSmartPointer<vtkPolyData> cleanBunny(const std::string& file);

/// The bunny Loop-subdivided until it has the number of vertices closest to `points` (about
/// 4x per level), with outward normals, or nothing if no level is within a factor 2.5.
std::optional<Mesh> bunnyOfAbout(vtkPolyData* bunny, long long points);
}
