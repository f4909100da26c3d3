// A mesh file's bytes, under the extension MESH_EXTENSION: through what `shadelab shade` does
// with it (the file checks, VTK's reader in its own process, the cell checks, normals and
// shading under the default light kit). A refusal is an outcome; only a crash, hang, leak or
// undefined behaviour in this process is a finding.
#include "FuzzFiles.h"
#include "MeshFiles.h"

#include "DefaultLightKit.h"
#include "vtkLocalReflectanceFilter.h"

#include "vtkLogger.h"
#include "vtkNew.h"
#include "vtkObject.h"
#include "vtkPolyData.h"
#include "vtkSMPTools.h"

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <fstream>
#include <string>
#include <unistd.h>

extern "C" int LLVMFuzzerInitialize(int*, char***)
{
  vtkObject::GlobalWarningDisplayOff(); // errors are the filters', read from their state
  vtkLogger::SetStderrVerbosity(vtkLogger::VERBOSITY_OFF);
  // One thread, so that the reader's fork() happens in a process without other threads, as
  // in the command line (which reads before it shades). A child forked while other threads
  // run inherits any lock they held at that moment (glibc resets malloc's, clang 14's
  // AddressSanitizer not all of its own): the one hang the STL fuzzer found, in 8,500 runs
  // with shading on two threads, was a reading child that never answered.
  vtkSMPTools::SetBackend("Sequential");
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
  const std::string path = fuzzFolder() + "/shadelab-fuzz-" + std::to_string(::getpid()) + MESH_EXTENSION;
  std::ofstream(path, std::ios::binary).write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
  try
  {
    vtkSmartPointer<vtkPolyData> mesh = shadelab::app::readMesh(path);
    vtkNew<vtkLocalReflectanceFilter> filter;
    filter->SetInputData(mesh);
    filter->SetScene(shadelab::defaultLightKit());
    filter->SetArraySelection({ "all" });
    filter->Update();
  }
  catch (const shadelab::app::UserError&)
  {
  }
  std::remove(path.c_str());
  return 0;
}
