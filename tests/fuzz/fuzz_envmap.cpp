// An environment map's bytes, as a .hdr or .exr file (by its magic number): read and checked
// as `shade --envmap` reads it.
#include "EnvironmentMap.h"
#include "FuzzFiles.h"

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <fstream>
#include <stdexcept>
#include <string>
#include <unistd.h>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
  const bool exr = size >= 4 && data[0] == 0x76 && data[1] == 0x2f && data[2] == 0x31 && data[3] == 0x01;
  const std::string path = fuzzFolder() + "/shadelab-fuzz-" + std::to_string(::getpid()) + (exr ? ".exr" : ".hdr");
  std::ofstream(path, std::ios::binary).write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
  try
  {
    const shadelab::EnvironmentMap map = shadelab::readEnvironmentMap(path);
    if (map.width >= 4)
    {
      shadelab::downsampled(map, 2); // what the brute-force estimator does with it
    }
  }
  catch (const std::runtime_error&)
  {
  }
  std::remove(path.c_str());
  return 0;
}
