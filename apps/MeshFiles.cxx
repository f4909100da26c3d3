#include "MeshFiles.h"

#include "ProgressLine.h"
#include "VtkErrorCapture.h"

#include "vtkAlgorithm.h"
#include "vtkErrorCode.h"
#include "vtkOBJReader.h"
#include "vtkPLYReader.h"
#include "vtkPolyDataReader.h"
#include "vtkPolyDataWriter.h"
#include "vtkSTLReader.h"
#include "vtkXMLPolyDataReader.h"
#include "vtkXMLPolyDataWriter.h"

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <fstream>
#include <unistd.h>

namespace fs = std::filesystem;

namespace shadelab::app
{
const char* const readableExtensions = ".vtp, .vtk, .ply, .obj, .stl";

namespace
{
std::string lowerExtension(const std::string& fileName)
{
  std::string extension = fs::path(fileName).extension().string();
  std::transform(extension.begin(), extension.end(), extension.begin(),
    [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return extension;
}

vtkSmartPointer<vtkAlgorithm> readerFor(const std::string& fileName, const std::string& extension)
{
  if (extension == ".vtp")
  {
    auto reader = vtkSmartPointer<vtkXMLPolyDataReader>::New();
    if (!reader->CanReadFile(fileName.c_str()))
    {
      throw UserError(fileName + ": not a VTK XML PolyData file (a .vtp must be VTK XML of type PolyData)");
    }
    reader->SetFileName(fileName.c_str());
    return reader;
  }
  if (extension == ".vtk")
  {
    auto reader = vtkSmartPointer<vtkPolyDataReader>::New();
    reader->SetFileName(fileName.c_str());
    if (!reader->IsFilePolyData())
    {
      throw UserError(fileName + ": not a legacy VTK polydata file (ShadeLab shades surfaces: "
                                 "extract one first, e.g. with vtkGeometryFilter)");
    }
    return reader;
  }
  if (extension == ".ply")
  {
    if (!vtkPLYReader::CanReadFile(fileName.c_str()))
    {
      throw UserError(fileName + ": not a PLY file (it does not start with a PLY header)");
    }
    auto reader = vtkSmartPointer<vtkPLYReader>::New();
    reader->SetFileName(fileName.c_str());
    return reader;
  }
  if (extension == ".obj")
  {
    auto reader = vtkSmartPointer<vtkOBJReader>::New();
    reader->SetFileName(fileName.c_str());
    return reader;
  }
  if (extension == ".stl")
  {
    auto reader = vtkSmartPointer<vtkSTLReader>::New();
    reader->SetFileName(fileName.c_str());
    return reader;
  }
  throw UserError(fileName + ": unknown mesh format '" + extension + "'; ShadeLab reads " +
    readableExtensions);
}
}

vtkSmartPointer<vtkPolyData> readMesh(const std::string& fileName)
{
  const std::string extension = lowerExtension(fileName);
  if (!fs::exists(fileName))
  {
    throw UserError(fileName + ": no such file");
  }
  if (fs::is_directory(fileName) || !std::ifstream(fileName))
  {
    throw UserError(fileName + ": cannot be read (is it a readable file?)");
  }
  vtkSmartPointer<vtkAlgorithm> reader = readerFor(fileName, extension);
  vtkNew<VtkErrorCapture> errors;
  errors->watch(reader);
  vtkNew<ProgressLine> progress;
  progress->watch(reader, "reading");
  reader->Update();
  auto mesh = vtkPolyData::SafeDownCast(reader->GetOutputDataObject(0));
  const unsigned long code = reader->GetErrorCode();
  if (errors->failed() || code != vtkErrorCode::NoError || !mesh)
  {
    const std::string reason = errors->failed() ? errors->message()
      : code != vtkErrorCode::NoError           ? vtkErrorCode::GetStringFromErrorCode(code)
                                                : "the reader produced no polydata";
    throw UserError(fileName + ": cannot be read as " + extension + ": " + reason);
  }
  return mesh;
}

void checkOutputFile(const std::string& fileName, std::initializer_list<const char*> extensions)
{
  const std::string extension = lowerExtension(fileName);
  std::string list;
  bool known = false;
  for (const char* allowed : extensions)
  {
    list += (list.empty() ? "" : ", ") + std::string(allowed);
    known = known || extension == allowed;
  }
  if (!known)
  {
    throw UserError(fileName + ": cannot write '" + extension + "' files here; use " + list);
  }
  const fs::path folder = fs::absolute(fileName).parent_path();
  if (!fs::is_directory(folder))
  {
    throw UserError(fileName + ": the folder " + folder.string() + " does not exist");
  }
}

void writeThroughTemporary(
  const std::string& fileName, const std::function<std::string(const std::string& temporary)>& write)
{
  // Same folder as the target, so the final rename cannot cross file systems.
  const std::string temporary = fileName + ".partial-" + std::to_string(::getpid());
  const std::string failure = write(temporary);
  std::error_code ignored;
  if (!failure.empty())
  {
    fs::remove(temporary, ignored);
    throw UserError(fileName + ": cannot be written: " + failure);
  }
  std::error_code renameError;
  fs::rename(temporary, fileName, renameError);
  if (renameError)
  {
    fs::remove(temporary, ignored);
    throw UserError(fileName + ": cannot be written: " + renameError.message());
  }
}

void writeMesh(vtkPolyData* mesh, const std::string& fileName, Compression compression)
{
  checkOutputFile(fileName, meshExtensions);
  writeThroughTemporary(fileName,
    [&](const std::string& temporary) -> std::string
    {
      vtkNew<VtkErrorCapture> errors;
      vtkNew<ProgressLine> progress;
      int written = 0;
      if (lowerExtension(fileName) == ".vtp")
      {
        vtkNew<vtkXMLPolyDataWriter> writer;
        errors->watch(writer);
        progress->watch(writer, "writing");
        writer->SetInputData(mesh);
        writer->SetFileName(temporary.c_str());
        writer->SetDataModeToAppended();
        writer->EncodeAppendedDataOff(); // raw binary, not base64
        writer->SetCompressorType(compression == Compression::LZ4 ? vtkXMLWriterBase::LZ4
            : compression == Compression::ZLib                   ? vtkXMLWriterBase::ZLIB
                                                                 : vtkXMLWriterBase::NONE);
        written = writer->Write();
      }
      else
      {
        vtkNew<vtkPolyDataWriter> writer;
        errors->watch(writer);
        progress->watch(writer, "writing");
        writer->SetInputData(mesh);
        writer->SetFileName(temporary.c_str());
        writer->SetFileTypeToBinary();
        written = writer->Write();
      }
      if (errors->failed())
      {
        return errors->message();
      }
      return written ? "" : "the writer failed (disk full, or no permission?)";
    });
}
}
