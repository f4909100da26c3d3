#pragma once
// What `shadelab-bench` and its accuracy studies share: the meshes, the timer and the
// comparison of results.
#include "vtkDataArray.h"
#include "vtkPolyData.h"
#include "vtkSmartPointer.h"

#include <cmath>
#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace shadelab
{
struct Scene;
}

namespace shadelab::app
{
/// vtkLocalReflectanceFilter's output on the mesh under the scene. Throws UserError where the
/// mesh could not be shaded.
vtkSmartPointer<vtkPolyData> shaded(vtkPolyData* mesh, const Scene& scene);

struct Mesh
{
  std::string name;
  vtkSmartPointer<vtkPolyData> data;
};

/// Median time in milliseconds of run(): at least minRepeats runs, then more up to
/// maxRepeats while they fit in about two seconds.
double medianMilliseconds(const std::function<void()>& run, int minRepeats, int maxRepeats);

/// The same for several runs taken in turn, one of each per round, so that a ratio of their
/// medians compares them under the same load on a shared machine: one median per run.
std::vector<double> interleavedMedianMilliseconds(
  const std::vector<std::function<void()>>& runs, int minRepeats, int maxRepeats);

/// The largest and RMS differences between two results. A NaN difference makes the largest
/// NaN, so that a broken result cannot pass for an accurate one.
struct Differences
{
  double largest = 0, rms = 0;
};

class DifferenceSum
{
public:
  void add(double difference)
  {
    largest_ = difference <= largest_ ? largest_ : difference; // a NaN wins
    sumOfSquares_ += difference * difference;
    ++count_;
  }
  Differences result() const { return { largest_, count_ ? std::sqrt(sumOfSquares_ / count_) : 0.0 }; }

private:
  double largest_ = 0, sumOfSquares_ = 0;
  long long count_ = 0;
};

/// |a - b| over every value of two arrays; NaN when either is missing or the shapes differ.
Differences compareArrays(vtkDataArray* a, vtkDataArray* b);

/// A UV sphere with about `points` vertices and exact unit normals.
Mesh sphereOfAbout(long long points);

/// The Stanford bunny, merged and compacted.
vtkSmartPointer<vtkPolyData> cleanBunny(const std::string& file);

/// The bunny Loop-subdivided until it has the number of vertices closest to `points` (about
/// 4x per level), with outward normals, or nothing if no level is within a factor 2.5.
std::optional<Mesh> bunnyOfAbout(vtkPolyData* bunny, long long points);
}
