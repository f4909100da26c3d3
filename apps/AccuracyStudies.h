#pragma once
// `shadelab bench --charts DIR`: each method's error against its time, as PNG charts and one
// CSV, including every method at the point where it fails.
#include <string>

namespace shadelab::app
{
struct AccuracyOptions
{
  std::string directory;
  std::string bunnyFile;
  int maxRepeats = 9;
};

/// Runs the five studies (arithmetic and pow, pow over eta, a point light as distant, Phong
/// against Blinn-Phong, tessellation) and the failure points; writes accuracy.csv and one
/// PNG per study into the directory. Needs an X display for the charts. Throws UserError.
void runAccuracyStudies(const AccuracyOptions& options);
}
