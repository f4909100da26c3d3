#include "RelightCommand.h"

#include "CommandLineParse.h"
#include "MeshFiles.h"
#include "RunWarnings.h"
#include "StageTime.h"
#include "VtkErrorCapture.h"
#include "vtkTransferRelightFilter.h"

#include "vtkDataArray.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkSMPTools.h"

#include <iomanip>
#include <iostream>

namespace shadelab::app
{
CLI::App* addRelightCommand(CLI::App& cli, RelightOptions& options)
{
  CLI::App* command = cli.add_subcommand("relight",
    "Light a mesh shaded with --envmap-estimator prt (\"estimator\": \"prt\") under another map, turned any\n"
    "way, from the transfer vectors it stores, without tracing a ray: each vertex's irradiance is the\n"
    "dot product of the map's spherical-harmonic coefficients with its transfer vector, written as an\n"
    "RGB array (docs/guide/relighting.md). A mesh shaded with interreflection also stores what the\n"
    "bounces add to each transfer vector (<transfer>_indirect): the irradiance then includes the light\n"
    "the mesh reflects onto itself under the new map, and <name>_indirect holds that part alone.");
  command->add_option("mesh", options.mesh, "the shaded mesh (.vtp, .vtk) with a transfer array")->required();
  command->add_option("--envmap", options.environmentMap, "the equirectangular map (.hdr, .exr) to light it with")
    ->required();
  command->add_option("--output,-o", options.output, "the mesh to write (.vtp, .vtk), with every input array")
    ->required();
  command
    ->add_option("--rotation", options.rotation,
      "turn the map about +y by this many degrees (anticlockwise seen from above), as a scene's \"rotation\"")
    ->capture_default_str();
  command->add_option("--intensity", options.intensity, "multiply the map's radiance")
    ->check(CLI::NonNegativeNumber)
    ->capture_default_str();
  command->add_option("--transfer", options.transferArray,
    "the transfer array (default: the one array whose name ends in _sh_transfer, such as envmap_sh_transfer)");
  command
    ->add_option("--name", options.outputArray,
      "the name of the irradiance array it writes (an input array of that name is replaced, and the run says so)")
    ->capture_default_str();
  command->add_flag("--direct-only", options.directOnly,
    "leave out the interreflection that <transfer>_indirect carries, where the mesh has it");
  addCompressionOption(command, options.compression, ".vtp compression, as shade's");
  return command;
}

int runRelight(const RelightOptions& options)
{
  checkOutputFile(options.output, meshExtensions);
  RunWarnings warnings;
  const Clock::time_point readStart = Clock::now();
  vtkSmartPointer<vtkPolyData> mesh = readMesh(options.mesh);
  warnings.collect(options.mesh);
  const double readSeconds = secondsSince(readStart);

  vtkNew<vtkTransferRelightFilter> relighting;
  relighting->SetInputData(mesh);
  relighting->SetEnvironmentMapFileName(options.environmentMap);
  relighting->SetRotation(options.rotation);
  relighting->SetIntensity(options.intensity);
  relighting->SetTransferArrayName(options.transferArray);
  relighting->SetOutputArrayName(options.outputArray);
  relighting->SetUseIndirectTransfer(!options.directOnly);
  vtkNew<VtkErrorCapture> errors;
  errors->watch(relighting);
  const Clock::time_point relightStart = Clock::now();
  relighting->Update();
  const double relightSeconds = secondsSince(relightStart);
  if (errors->failed())
  {
    throw UserError(options.mesh + ": " + errors->message());
  }
  vtkPolyData* output = relighting->GetOutput();

  const Clock::time_point writeStart = Clock::now();
  writeMesh(output, options.output, compressionNamed(options.compression));
  warnings.collect(options.output);
  const double writeSeconds = secondsSince(writeStart);

  warnings.show();
  std::cout << "shadelab relight: " << options.mesh << " -> " << options.output << "\n"
            << "  map: " << options.environmentMap << ", turned " << options.rotation << " degrees, intensity "
            << options.intensity << "\n"
            << "  " << output->GetNumberOfPoints() << " vertices: " << relighting->GetReport() << "\n";
  for (const std::string& name : { options.outputArray, options.outputArray + "_indirect" })
  {
    vtkDataArray* irradiance = output->GetPointData()->GetArray(name.c_str());
    for (int c = 0; irradiance && c < 3; ++c)
    {
      double range[2];
      irradiance->GetRange(range, c);
      std::cout << "    " << name << " "
                << "RGB"[c] << " from " << std::setprecision(6) << range[0] << " to " << range[1] << "\n";
    }
  }
  const int threads = vtkSMPTools::GetEstimatedNumberOfThreads();
  std::cout << std::setprecision(3) << "  time: read " << readSeconds << " s, relight " << relightSeconds << " s ("
            << threads << (threads == 1 ? " thread" : " threads") << "), write " << writeSeconds << " s\n";
  return 0;
}
}
