#pragma once
// `shadelab-bench --end-to-end MESH`: what `shadelab shade` spends on one mesh, stage by stage
// (read, normals, orientation, shading, write), against the floors of reading the file with
// VTK's reader alone and writing the result with VTK's writer alone, and its peak memory
// against the bytes of the mesh and of the arrays it writes.
#include <string>

namespace shadelab::app
{
struct EndToEndOptions
{
  std::string mesh;
  std::string scene; // empty: the default light kit
  int minRepeats = 3;
};

/// Prints the row's stages and ratios to standard output. Throws UserError.
void runEndToEnd(const EndToEndOptions& options);
}
