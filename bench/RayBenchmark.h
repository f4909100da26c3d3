#pragma once
// `shadelab-bench --visibility DIR`: what casting rays costs (visibility/OccluderMesh.h):
// building the BVH, shadow rays and ambient occlusion rays per second on the bunny and the
// bunny subdivided to 2.2M vertices, against VTK's own way of casting the same rays
// (vtkStaticCellLocator::IntersectWithLine) in the same run; and ambient occlusion's error
// against its time, for 4 to 1024 rays, against a 4096-ray reference, as CSV and a chart.
#include <string>

namespace shadelab::app
{
struct RayBenchmarkOptions
{
  std::string folder;    // where visibility.csv and 9_ambient_occlusion.png (chart 9) go
  std::string bunnyFile; // the Stanford bunny
  std::string envmapFile = "data/envmaps/studio_small_03_1k.hdr"; // the map whose shadows are timed
  int repeats = 3;
};

void runRayBenchmark(const RayBenchmarkOptions& options);
}
