#include "MeshFiles.h"

#include "GltfScene.h"
#include "IsolatedWork.h"
#include "MeshFileChecks.h"
#include "MeshHandOver.h"
#include "ObjScene.h"
#include "PieceFiles.h"
#include "ProgressLine.h"
#include "VtkErrorCapture.h"

#include "ShadeLabMeshChecks.h"

#include "vtkAlgorithm.h"
#include "vtkCellData.h"
#include "vtkErrorCode.h"
#include "vtkFieldData.h"
#include "vtkGenericDataObjectReader.h"
#include "vtkInformation.h"
#include "vtkOBJReader.h"
#include "vtkPLYReader.h"
#include "vtkPointData.h"
#include "vtkPolyDataReader.h"
#include "vtkPolyDataWriter.h"
#include "vtkRectilinearGridReader.h"
#include "vtkSMPTools.h"
#include "vtkSTLReader.h"
#include "vtkStructuredGridReader.h"
#include "vtkStructuredPointsReader.h"
#include "vtkUnstructuredGridReader.h"
#include "vtkXMLImageDataReader.h"
#include "vtkXMLPPolyDataReader.h"
#include "vtkXMLPolyDataReader.h"
#include "vtkXMLPolyDataWriter.h"
#include "vtkXMLRectilinearGridReader.h"
#include "vtkXMLStructuredGridReader.h"
#include "vtkXMLUnstructuredGridReader.h"

#include <algorithm>
#include <cctype>
#include <csignal>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <signal.h>
#include <sstream>
#include <stdexcept>
#include <unistd.h>
#include <vector>

namespace fs = std::filesystem;

namespace shadelab::app
{
const char* const readableExtensions = ".vtp, .pvtp, .vtk, .ply, .obj, .stl, .gltf, .glb";

std::string lowerExtension(const std::string& fileName)
{
  std::string extension = fs::path(fileName).extension().string();
  std::transform(extension.begin(), extension.end(), extension.begin(),
    [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return extension;
}

namespace
{
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
  if (extension == ".pvtp")
  {
    if (!vtkNew<vtkXMLPPolyDataReader>()->CanReadFile(fileName.c_str()))
    {
      throw UserError(fileName + ": not a VTK XML PPolyData file (a .pvtp must be VTK XML of type PPolyData)");
    }
    return pvtpReader(fileName);
  }
  if (extension == ".vtk")
  {
    auto reader = vtkSmartPointer<vtkPolyDataReader>::New();
    reader->SetFileName(fileName.c_str());
    if (!reader->IsFilePolyData())
    {
      throw UserError(fileName +
        ": not a legacy VTK polydata file (ShadeLab shades surfaces: "
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
  throw UserError(fileName + ": unknown mesh format '" + extension + "'; ShadeLab reads " + readableExtensions);
}

/// Runs the reader of the file, in this process, showing progress on terminal (null:
/// nowhere), and returns its output as a Data (kind names it in the message where it is not
/// one). Throws UserError with VTK's reason.
template<typename Data>
vtkSmartPointer<Data> outputOf(vtkAlgorithm* reader, const std::string& fileName, const std::string& extension,
  std::FILE* terminal, const char* kind, PieceToRead piece = {})
{
  vtkNew<VtkErrorCapture> errors;
  errors->watch(reader);
  vtkNew<ProgressLine> progress;
  progress->watch(reader, "reading", terminal);
  reader->UpdatePiece(piece.index, piece.count, 0);
  auto* data = Data::SafeDownCast(reader->GetOutputDataObject(0));
  const unsigned long code = reader->GetErrorCode();
  if (errors->failed() || code != vtkErrorCode::NoError || !data)
  {
    const std::string reason = errors->failed() ? errors->message()
      : code != vtkErrorCode::NoError           ? vtkErrorCode::GetStringFromErrorCode(code)
                                                : std::string("the reader produced no ") + kind;
    throw UserError(fileName + ": cannot be read as " + extension + ": " + printableText(reason));
  }
  return data;
}

/// Reads the file (of a .pvtp, the piece asked for) with VTK's reader for its extension, in
/// this process, showing progress on terminal (null: nowhere). Throws UserError.
vtkSmartPointer<vtkPolyData> readDirectly(
  const std::string& fileName, const std::string& extension, std::FILE* terminal, PieceToRead piece = {})
{
  return outputOf<vtkPolyData>(readerFor(fileName, extension), fileName, extension, terminal, "polydata", piece);
}
}

namespace
{
/// The size of the file, once it is known to be a regular file that can be opened. Throws
/// UserError.
std::uintmax_t readableFileSize(const std::string& fileName)
{
  std::error_code error;
  if (!fs::exists(fileName, error))
  {
    throw UserError(fileName + ": no such file");
  }
  if (!fs::is_directory(fileName, error) && !fs::is_regular_file(fileName, error))
  {
    // A pipe or a device would have the reader wait, or read without end.
    throw UserError(fileName + ": not a regular file (a pipe or a device?): save the mesh to a file first");
  }
  if (fs::is_directory(fileName, error) || !std::ifstream(fileName))
  {
    throw UserError(fileName + ": cannot be read (is it a readable file?)");
  }
  const std::uintmax_t size = fs::file_size(fileName, error);
  return error ? 0 : size;
}

/// Runs read(channel), which reads the file and hands its dataset over, in a process of its
/// own, and takes the dataset over. VTK's readers are not hardened against damaged files: the
/// process is bounded in processor time and memory by the file's size (a reader asking for far
/// more is answering a lie in the file), so that a crash there is an error here. reader names
/// the reader in messages ("VTK's .ply reader"). fileProblem, if given, checks the file in this
/// process while the reader reads it (VTK's readers use one core); what it finds is the error,
/// whatever the reader made of the file. With textures, the file may name images, which are
/// given room of their own. Throws UserError.
vtkSmartPointer<vtkDataSet> readIsolated(const std::string& fileName, const std::string& reader, std::uintmax_t size,
  const std::function<void(ChildChannel&)>& read, const std::function<std::string()>& fileProblem = {},
  bool textures = false)
{
  const double megabytes = static_cast<double>(size) / 1e6;
  IsolationLimits limits;
  limits.cpuSeconds = 10 + 2 * megabytes;
  limits.memoryBytes = (std::size_t(512) << 20) + 32 * static_cast<std::size_t>(size);
  if (textures)
  {
    // A compressed image says little of its decoded size (a smooth 4096 x 4096 PNG of 1 MB is
    // 1.2 GB once decoded and summed, 72 bytes a texel): room for such textures.
    limits.cpuSeconds += 30;
    limits.memoryBytes += std::size_t(4) << 30;
  }
  limits.wallSeconds = 10 + 3 * limits.cpuSeconds; // room for a busy machine
  std::string problem;
  const IsolatedOutcome outcome = runIsolated(
    [&](ChildChannel& channel)
    {
      // oneTBB does not support fork(): worker threads the parent may have started are not in
      // the child. So VTK's parallel loops (the cell checks) run here on threads of their own
      // (VTK's std::thread backend), started in the child, as many as the parent's.
      const int threads = vtkSMPTools::GetEstimatedNumberOfThreads();
      vtkSMPTools::SetBackend("STDThread");
      vtkSMPTools::Initialize(threads);
      read(channel);
      if (auto* window = QuietOutputWindow::SafeDownCast(vtkOutputWindow::GetInstance()))
      {
        for (const std::string& warning : window->takeWarnings())
        {
          channel.warning(printableText(warning));
        }
      }
      channel.finished();
    },
    limits,
    [&]()
    {
      problem = fileProblem ? fileProblem() : "";
      return problem.empty();
    });
  for (const std::string& warning : outcome.warnings)
  {
    vtkOutputWindow::GetInstance()->DisplayWarningText(warning.c_str());
  }
  std::ostringstream message;
  message << fileName << ": ";
  switch (outcome.end)
  {
    case IsolatedOutcome::End::Finished:
      try
      {
        return takeOverDataSet(outcome.resultPath);
      }
      catch (const std::bad_alloc&)
      {
        message << "not enough memory to take over the mesh read from it";
        break;
      }
      catch (const std::runtime_error& error)
      {
        message << "the mesh read from it could not be taken over: " << printableText(error.what());
        break;
      }
    case IsolatedOutcome::End::Stopped: throw UserError(fileName + ": " + problem);
    case IsolatedOutcome::End::Failed:
      throw UserError(printableText(outcome.error, 400)); // the reading's message names the file
    case IsolatedOutcome::End::OutOfMemory:
      message << "reading it needs more than " << limits.memoryBytes / (1 << 20)
              << " MB, far more than a file of this size can hold: it declares more data than it has";
      break;
    case IsolatedOutcome::End::TimedOut:
      message << "reading it took more than " << limits.cpuSeconds
              << " s of processor time, far more than a file of this size needs: it is damaged";
      break;
    case IsolatedOutcome::End::Stalled:
      message << reader << " had not finished after " << limits.wallSeconds
              << " s, and was stopped: is the file on a slow or stalled disk?";
      break;
    case IsolatedOutcome::End::Crashed:
      message << reader << " crashed on it (" << outcome.signalName << "): the file is damaged or not a valid "
              << fs::path(fileName).extension().string() << " file";
      break;
  }
  throw UserError(message.str());
}

/// What an importer skipped, as warnings that replace VTK's own (ours say what was done instead).
void sendNotes(const std::vector<std::string>& notes, ChildChannel& channel)
{
  if (auto* window = QuietOutputWindow::SafeDownCast(vtkOutputWindow::GetInstance()))
  {
    window->takeWarnings();
  }
  for (const std::string& note : notes)
  {
    channel.warning(printableText(note, 400));
  }
}

/// An OBJ file with its materials where it names a material library that is there (ObjScene.h),
/// else the mesh alone; what was skipped is a warning that names the file, in place of VTK's own.
vtkSmartPointer<vtkPolyData> readObj(const std::string& fileName, ChildChannel& channel)
{
  std::vector<std::string> notes;
  const ObjStatements statements = objStatementsOf(fileName, notes);
  std::error_code error;
  vtkSmartPointer<vtkPolyData> mesh;
  if (!statements.library.empty() && !fs::is_regular_file(statements.library, error))
  {
    notes.push_back("names the material library " + statements.library +
      ", which is not there: its parts are read as one mesh, shaded with the scene's material");
  }
  else if (!statements.library.empty())
  {
    mesh = importObjScene(fileName, statements, notes);
  }
  sendNotes(notes, channel);
  return mesh ? mesh : readDirectly(fileName, ".obj", channel.terminal());
}

/// A glTF file's parts with their materials, and its lights (GltfScene.h); what was skipped
/// is a warning, in place of VTK's own.
vtkSmartPointer<vtkPolyData> readGltf(const std::string& fileName, ChildChannel& channel)
{
  std::vector<std::string> notes;
  vtkSmartPointer<vtkPolyData> mesh = importGltfScene(fileName, notes);
  sendNotes(notes, channel);
  return mesh;
}

/// Checked before a mesh is handed over: a reader can build cells whose offsets lie, and
/// reading them back would trust the lie.
void checkCells(vtkPolyData* mesh, const std::string& fileName)
{
  const std::string cells = cellProblem(mesh);
  if (!cells.empty())
  {
    throw std::runtime_error(fileName + ": " + cells);
  }
}
}

vtkSmartPointer<vtkPolyData> readMesh(const std::string& fileName, std::string* ignored, PieceToRead piece)
{
  const std::string extension = lowerExtension(fileName);
  std::uintmax_t size = readableFileSize(fileName); // first: it refuses what is not a regular file
  size = extension == ".gltf" ? std::max(size, gltfBytes(fileName))
    : extension == ".pvtp"    ? size + pieceFileBytes(fileName)
                              : size;
  MeshFileCheck check;
  vtkSmartPointer<vtkDataSet> data = readIsolated(
    fileName, "VTK's " + extension + " reader", size,
    [&](ChildChannel& channel)
    {
      vtkSmartPointer<vtkPolyData> mesh = extension == ".obj" ? readObj(fileName, channel)
        : isGltfFile(fileName)                                ? readGltf(fileName, channel)
        : extension == ".pvtp" ? readDirectly(fileName, extension, channel.terminal(), piece)
                               : readDirectly(fileName, extension, channel.terminal());
      checkCells(mesh, fileName);
      if (piece.count > 1 && extension != ".pvtp")
      {
        mesh = meshPiece(mesh, piece.index, piece.count, 0);
      }
      handOverMesh(mesh, channel.resultPath());
    },
    [&]()
    {
      check = checkMeshFile(fileName, extension, size);
      return check.problem;
    },
    extension == ".obj" || isGltfFile(fileName)); // the formats with textures
  if (ignored)
  {
    *ignored = check.ignored;
  }
  auto* mesh = vtkPolyData::SafeDownCast(data);
  if (!mesh)
  {
    throw UserError(fileName + ": the mesh read from it could not be taken over: it is not polydata");
  }
  return mesh;
}

namespace
{
/// VTK's reader of the dataset type the extension (or, for legacy .vtk, the file's header) names.
/// Throws UserError.
vtkSmartPointer<vtkAlgorithm> datasetReaderFor(const std::string& fileName, const std::string& extension)
{
  auto withFile = [&](auto reader) -> vtkSmartPointer<vtkAlgorithm>
  {
    reader->SetFileName(fileName.c_str());
    return reader;
  };
  auto xml = [&](auto reader, const char* type) -> vtkSmartPointer<vtkAlgorithm>
  {
    if (!reader->CanReadFile(fileName.c_str()))
    {
      throw UserError(
        fileName + ": not a VTK XML " + type + " file (a " + extension + " must be VTK XML of type " + type + ")");
    }
    return withFile(reader);
  };
  if (extension == ".vtu")
  {
    return xml(vtkSmartPointer<vtkXMLUnstructuredGridReader>::New(), "UnstructuredGrid");
  }
  if (extension == ".vti")
  {
    return xml(vtkSmartPointer<vtkXMLImageDataReader>::New(), "ImageData");
  }
  if (extension == ".vts")
  {
    return xml(vtkSmartPointer<vtkXMLStructuredGridReader>::New(), "StructuredGrid");
  }
  if (extension == ".vtr")
  {
    return xml(vtkSmartPointer<vtkXMLRectilinearGridReader>::New(), "RectilinearGrid");
  }
  // Legacy: the header says which dataset follows.
  vtkNew<vtkGenericDataObjectReader> header;
  header->SetFileName(fileName.c_str());
  switch (header->ReadOutputType())
  {
    case VTK_POLY_DATA: return withFile(vtkSmartPointer<vtkPolyDataReader>::New());
    case VTK_UNSTRUCTURED_GRID: return withFile(vtkSmartPointer<vtkUnstructuredGridReader>::New());
    case VTK_STRUCTURED_POINTS:
    case VTK_IMAGE_DATA: return withFile(vtkSmartPointer<vtkStructuredPointsReader>::New());
    case VTK_STRUCTURED_GRID: return withFile(vtkSmartPointer<vtkStructuredGridReader>::New());
    case VTK_RECTILINEAR_GRID: return withFile(vtkSmartPointer<vtkRectilinearGridReader>::New());
    case -1: throw UserError(fileName + ": not a legacy VTK file (its header does not name a dataset)");
    default: break;
  }
  throw UserError(fileName +
    ": the legacy VTK file holds no dataset of a type ShadeLab compares (polydata, "
    "unstructured, structured or rectilinear grid, image)");
}
}

const char* const readableDataSetExtensions = ".vtp, .pvtp, .vtu, .vti, .vts, .vtr, .vtk (legacy), .ply, .obj, .stl";

vtkSmartPointer<vtkDataSet> readDataSet(const std::string& fileName)
{
  const std::string extension = lowerExtension(fileName);
  static const std::vector<std::string> xml = { ".vtu", ".vti", ".vts", ".vtr" };
  const bool generic = extension == ".vtk" || std::find(xml.begin(), xml.end(), extension) != xml.end();
  if (!generic)
  {
    if (extension != ".vtp" && extension != ".pvtp" && extension != ".ply" && extension != ".obj" &&
      extension != ".stl")
    {
      throw UserError(
        fileName + ": unknown dataset format '" + extension + "'; ShadeLab reads " + readableDataSetExtensions);
    }
    return readMesh(fileName);
  }
  const std::uintmax_t size = readableFileSize(fileName);
  return readIsolated(fileName, "VTK's " + extension + " reader", size,
    [&](ChildChannel& channel)
    {
      vtkSmartPointer<vtkDataSet> data =
        outputOf<vtkDataSet>(datasetReaderFor(fileName, extension), fileName, extension, channel.terminal(), "dataset");
      if (auto* mesh = vtkPolyData::SafeDownCast(data))
      {
        checkCells(mesh, fileName);
      }
      handOverDataSet(data, channel.resultPath());
    });
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
  std::error_code error;
  const fs::path folder = fs::absolute(fileName, error).parent_path();
  if (!fs::is_directory(folder, error))
  {
    throw UserError(fileName + ": the folder " + folder.string() + " does not exist");
  }
}

namespace
{
/// The temporary file being written, for the signal handler: a fixed buffer, since a handler
/// may touch nothing that allocates.
char temporaryBeingWritten[4096] = "";

extern "C" void removeTemporaryAndDie(int signal)
{
  if (temporaryBeingWritten[0] != '\0')
  {
    ::unlink(temporaryBeingWritten);
  }
  std::signal(signal, SIG_DFL);
  std::raise(signal);
}

/// While it lives, an interrupt, hang-up or termination removes the temporary file first.
class TemporaryGuard
{
public:
  explicit TemporaryGuard(const std::string& temporary)
  {
    if (temporary.size() < sizeof temporaryBeingWritten)
    {
      std::memcpy(temporaryBeingWritten, temporary.c_str(), temporary.size() + 1);
    }
    for (int signal : { SIGINT, SIGTERM, SIGHUP })
    {
      previous_.push_back(std::signal(signal, removeTemporaryAndDie));
    }
  }
  ~TemporaryGuard()
  {
    int i = 0;
    for (int signal : { SIGINT, SIGTERM, SIGHUP })
    {
      std::signal(signal, previous_[i++]);
    }
    temporaryBeingWritten[0] = '\0';
  }

private:
  std::vector<void (*)(int)> previous_;
};

}

void removeStaleTemporaries(const std::string& fileName, bool folders)
{
  const fs::path target = fs::absolute(fileName);
  const std::string stem = target.filename().string() + ".partial-";
  std::error_code error;
  for (const fs::directory_entry& entry : fs::directory_iterator(target.parent_path(), error))
  {
    const std::string name = entry.path().filename().string();
    if (name.rfind(stem, 0) != 0)
    {
      continue;
    }
    const std::string pid = name.substr(stem.size());
    if (pid.empty() || pid.size() > 9 || pid.find_first_not_of("0123456789") != std::string::npos)
    {
      continue;
    }
    if (::kill(static_cast<pid_t>(std::stol(pid)), 0) != 0 && errno == ESRCH)
    {
      if (folders)
      {
        fs::remove_all(entry.path(), error);
      }
      else
      {
        fs::remove(entry.path(), error);
      }
    }
  }
}

void writeThroughTemporary(
  const std::string& fileName, const std::function<std::string(const std::string& temporary)>& write)
{
  removeStaleTemporaries(fileName);
  // Same folder as the target, so the final rename cannot cross file systems.
  const std::string temporary = fileName + ".partial-" + std::to_string(::getpid());
  const TemporaryGuard guard(temporary);
  std::string failure;
  try
  {
    failure = write(temporary);
  }
  catch (const std::bad_alloc&)
  {
    failure = "not enough memory to write it";
  }
  catch (const std::exception& error)
  {
    failure = error.what();
  }
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

namespace
{
/// The first array name of the mesh that VTK 9.1's XML writer would write unescaped into an
/// attribute, making the file unreadable (a quote, <, > or &, or a byte that is not
/// printable ASCII), with where it is; "" when there is none.
std::string nameXmlCannotHold(vtkPolyData* mesh)
{
  for (const auto& [data, kind] : { std::make_pair<vtkFieldData*, const char*>(mesh->GetPointData(), "point"),
         std::make_pair<vtkFieldData*, const char*>(mesh->GetCellData(), "cell"),
         std::make_pair<vtkFieldData*, const char*>(mesh->GetFieldData(), "field") })
  {
    for (int a = 0; a < data->GetNumberOfArrays(); ++a)
    {
      const char* name = data->GetArrayName(a);
      if (name && xmlCannotHold(name))
      {
        return std::string("the ") + kind + " array '" + printableText(name, 60) + "'";
      }
    }
  }
  return "";
}
}

bool xmlCannotHold(const std::string& text)
{
  return std::any_of(text.begin(), text.end(),
    [](char c) { return c < 0x20 || c >= 0x7f || c == '"' || c == '<' || c == '>' || c == '&'; });
}

std::string xmlNameProblem(vtkPolyData* mesh)
{
  const std::string unsafeName = nameXmlCannotHold(mesh);
  return unsafeName.empty() ? ""
                            : unsafeName +
      " has a name that a .vtp file cannot hold (VTK 9.1 writes it unescaped, and no reader could open the "
      "file): rename it in the input, or write legacy .vtk";
}

void writeTextFile(const std::string& fileName, const std::string& text)
{
  writeThroughTemporary(fileName,
    [&](const std::string& temporary) -> std::string
    {
      std::ofstream file(temporary);
      file << text;
      file.close();
      return file ? "" : "the disk is full, or the file system refuses it";
    });
}

void setXmlEncoding(vtkXMLWriterBase* writer, Compression compression, VtpLayout layout)
{
  if (layout == VtpLayout::RawAppended)
  {
    writer->SetDataModeToAppended();
    writer->EncodeAppendedDataOff();
  }
  else
  {
    writer->SetDataModeToBinary(); // base64 in each array's element
  }
  writer->SetCompressorType(compression == Compression::LZ4 ? vtkXMLWriterBase::LZ4
      : compression == Compression::ZLib                    ? vtkXMLWriterBase::ZLIB
                                                            : vtkXMLWriterBase::NONE);
}

vtkSmartPointer<vtkAlgorithm> vtkWriterFor(
  vtkPolyData* mesh, const std::string& path, const std::string& extension, Compression compression, VtpLayout layout)
{
  if (extension == ".vtp")
  {
    auto writer = vtkSmartPointer<vtkXMLPolyDataWriter>::New();
    writer->SetInputData(mesh);
    writer->SetFileName(path.c_str());
    setXmlEncoding(writer, compression, layout);
    return writer;
  }
  auto writer = vtkSmartPointer<vtkPolyDataWriter>::New();
  writer->SetInputData(mesh);
  writer->SetFileName(path.c_str());
  writer->SetFileTypeToBinary();
  return writer;
}

vtkSmartPointer<vtkAlgorithm> vtkReaderFor(const std::string& fileName)
{
  return readerFor(fileName, lowerExtension(fileName));
}

void writeMesh(vtkPolyData* mesh, const std::string& fileName, Compression compression, VtpLayout layout)
{
  checkOutputFile(fileName, meshExtensions);
  const std::string unsafeName = lowerExtension(fileName) == ".vtp" ? xmlNameProblem(mesh) : "";
  if (!unsafeName.empty())
  {
    throw UserError(fileName + ": " + unsafeName);
  }
  writeThroughTemporary(fileName,
    [&](const std::string& temporary) -> std::string
    {
      vtkSmartPointer<vtkAlgorithm> writer =
        vtkWriterFor(mesh, temporary, lowerExtension(fileName), compression, layout);
      vtkNew<VtkErrorCapture> errors;
      errors->watch(writer);
      vtkNew<ProgressLine> progress;
      progress->watch(writer, "writing");
      writer->Update(); // writes
      const bool written = writer->GetErrorCode() == vtkErrorCode::NoError;
      if (errors->failed())
      {
        return errors->message();
      }
      return written ? "" : "the writer failed (disk full, or no permission?)";
    });
}

Compression compressionNamed(const std::string& name)
{
  return name == "zlib" ? Compression::ZLib : name == "none" ? Compression::None : Compression::LZ4;
}
}
