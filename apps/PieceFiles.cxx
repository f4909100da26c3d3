#include "PieceFiles.h"

#include "ProgressLine.h"
#include "VtkErrorCapture.h"

#include "ShadeLabMeshPieces.h"

#include "vtkCellData.h"
#include "vtkCommand.h"
#include "vtkExtractPolyDataPiece.h"
#include "vtkFieldData.h"
#include "vtkIdTypeArray.h"
#include "vtkMultiProcessController.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkXMLDataReader.h"
#include "vtkXMLPPolyDataReader.h"
#include "vtkXMLPPolyDataWriter.h"

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <functional>
#include <numeric>
#include <regex>
#include <sstream>
#include <unistd.h>
#include <vector>

namespace fs = std::filesystem;

namespace shadelab::app
{
namespace
{
/// Makes attributes' global ids (added as each tuple's index where there are none) an ordinary
/// array, which vtkExtractPolyDataPiece passes on (it drops the global ids attribute); returns
/// its name.
std::string globalIdsAsArray(vtkDataSetAttributes* attributes, vtkIdType count)
{
  vtkSmartPointer<vtkDataArray> ids = attributes->GetGlobalIds();
  if (!ids)
  {
    auto indices = vtkSmartPointer<vtkIdTypeArray>::New();
    indices->SetNumberOfValues(count);
    std::iota(indices->GetPointer(0), indices->GetPointer(0) + count, vtkIdType(0));
    ids = indices;
  }
  else if (!ids->GetName())
  {
    ids = vtk::TakeSmartPointer(ids->NewInstance()); // the mesh's own, under a name of their own
    ids->DeepCopy(attributes->GetGlobalIds());
  }
  if (!ids->GetName())
  {
    ids->SetName("GlobalIds");
  }
  attributes->SetActiveAttribute(-1, vtkDataSetAttributes::GLOBALIDS);
  attributes->AddArray(ids);
  return ids->GetName();
}

/// vtkXMLPPolyDataWriter writing a summary that names every piece with points or cells (VTK
/// writes no file for an empty one), not only the one it wrote itself: each process writes its
/// own piece alone, without the collective call inside VTK's writer, in which a process that
/// failed to write would leave the others waiting.
class SummaryOfEveryPiece : public vtkXMLPPolyDataWriter
{
public:
  static SummaryOfEveryPiece* New();
  vtkTypeMacro(SummaryOfEveryPiece, vtkXMLPPolyDataWriter);
  /// Whether each process's piece has points or cells, in process order.
  std::vector<int> piecesWithData;

protected:
  void PrepareSummaryFile() override
  {
    std::copy(this->piecesWithData.begin(), this->piecesWithData.end(), this->PieceWrittenFlags);
  }
};
vtkStandardNewMacro(SummaryOfEveryPiece);

/// Whether each process's piece has points or cells, in process order (a collective call).
std::vector<int> piecesWithData(vtkPolyData* piece, vtkMultiProcessController* processes)
{
  const int mine = piece->GetNumberOfPoints() > 0 || piece->GetNumberOfCells() > 0 ? 1 : 0;
  std::vector<int> all(processes ? processes->GetNumberOfProcesses() : 1, mine);
  if (processes)
  {
    processes->AllGather(&mine, all.data(), 1);
  }
  return all;
}

/// vtkXMLPPolyDataReader whose pieces' readers' errors are its own, with the piece's file named.
class StrictPPolyDataReader : public vtkXMLPPolyDataReader
{
public:
  static StrictPPolyDataReader* New();
  vtkTypeMacro(StrictPPolyDataReader, vtkXMLPPolyDataReader);

protected:
  vtkXMLDataReader* CreatePieceReader() override
  {
    vtkXMLDataReader* reader = this->Superclass::CreatePieceReader();
    reader->AddObserver(vtkCommand::ErrorEvent, this, &StrictPPolyDataReader::passError);
    return reader;
  }

private:
  void passError(vtkObject* pieceReader, unsigned long, void* text)
  {
    const char* file = static_cast<vtkXMLDataReader*>(pieceReader)->GetFileName();
    const std::string message =
      "its piece " + std::string(file ? file : "") + ": " + messageText(text ? static_cast<const char*>(text) : "");
    this->InvokeEvent(vtkCommand::ErrorEvent, const_cast<char*>(message.c_str()));
  }
};
vtkStandardNewMacro(StrictPPolyDataReader);

/// Why the folder of the pieces cannot hold them ("" where it can): something else of that
/// name is in the way. A folder that holds only an earlier run's pieces is replaced.
std::string piecesFolderProblem(const fs::path& folder, const std::string& base)
{
  std::error_code error;
  if (!fs::exists(fs::symlink_status(folder, error)))
  {
    return "";
  }
  if (!fs::is_directory(fs::symlink_status(folder, error)))
  {
    return folder.string() + ", where its pieces go, is not a folder: move it or write elsewhere";
  }
  const std::regex pieceName(std::regex_replace(base, std::regex(R"([.^$|()\[\]{}*+?\\])"), R"(\$&)") + R"(_\d+\.vtp)");
  fs::directory_iterator entry(folder, error);
  for (; !error && entry != fs::directory_iterator(); entry.increment(error))
  {
    if (!std::regex_match(entry->path().filename().string(), pieceName))
    {
      return folder.string() + ", where its pieces go, holds other files (" + entry->path().filename().string() +
        "): move them or write elsewhere";
    }
  }
  return error ? "cannot list " + folder.string() + ", where its pieces go: " + error.message() : "";
}

/// This process's piece written into staging (as VTK's writer names it there), the summary too
/// on the first; "" or why it failed.
std::string writeOwnPiece(vtkPolyData* piece, const fs::path& summary, int index, const std::vector<int>& withData,
  Compression compression, VtpLayout layout)
{
  vtkSmartPointer<vtkXMLPPolyDataWriter> writer = vtkSmartPointer<vtkXMLPPolyDataWriter>::New();
  if (index == 0)
  {
    auto first = vtkSmartPointer<SummaryOfEveryPiece>::New();
    first->piecesWithData = withData;
    writer = first;
  }
  writer->SetInputData(piece);
  writer->SetFileName(summary.c_str());
  writer->SetNumberOfPieces(static_cast<int>(withData.size()));
  writer->SetStartPiece(index);
  writer->SetEndPiece(index);
  writer->SetWriteSummaryFile(index == 0);
  writer->SetUseSubdirectory(true);
  setXmlEncoding(writer, compression, layout);
  vtkNew<VtkErrorCapture> errors;
  errors->watch(writer);
  vtkNew<ProgressLine> progress;
  progress->watch(writer, "writing");
  const bool written = writer->Write() == 1;
  return errors->failed() ? errors->message() : written ? "" : "the writer failed (disk full, or no permission?)";
}

/// What work() returns, or the message of what it throws: the first process's own steps,
/// which must reach the others as text, or they would wait for it.
std::string onFirstProcess(const std::function<std::string()>& work)
{
  try
  {
    return work();
  }
  catch (const std::exception& error)
  {
    return error.what();
  }
}

/// Moves the staged summary and pieces into place, an earlier run's pieces set aside in staging
/// and put back where the new ones cannot take their place; "" or why not. Earlier pieces that
/// cannot be put back are moved beside the .pvtp (BASE.earlier-PID), out of the staging
/// folder, which the caller then removes; where even that fails, keepStaging is set.
std::string moveIntoPlace(
  const fs::path& staging, const fs::path& target, const fs::path& folder, const std::string& base, bool& keepStaging)
{
  const fs::path earlier = staging / (base + ".earlier");
  std::error_code error;
  const bool replacing = fs::exists(fs::symlink_status(folder, error));
  if (replacing)
  {
    // Checked again: the folder may have changed while the pieces were written.
    const std::string problem = piecesFolderProblem(folder, base);
    if (!problem.empty())
    {
      return problem;
    }
    fs::rename(folder, earlier, error);
    if (error)
    {
      return "cannot move the earlier pieces in " + folder.string() + " aside: " + error.message();
    }
  }
  fs::rename(staging / base, folder, error);
  if (!error)
  {
    fs::rename(staging / target.filename(), target, error);
    if (!error)
    {
      return "";
    }
    std::error_code ignored;
    fs::rename(folder, staging / base, ignored); // the new pieces back, so that the earlier can return
  }
  const std::string why = error.message();
  if (!replacing)
  {
    return why;
  }
  fs::rename(earlier, folder, error);
  if (!error)
  {
    return why;
  }
  const fs::path rescued = target.parent_path() / (base + ".earlier-" + std::to_string(::getpid()));
  fs::rename(earlier, rescued, error);
  keepStaging = bool(error);
  return why + "; the earlier pieces could not be put back, and are in " +
    (error ? earlier.string() : rescued.string());
}
}

std::string pvtpPlaceProblem(const std::string& fileName)
{
  const fs::path target = fs::absolute(fileName);
  if (xmlCannotHold(target.filename().string()))
  {
    return "its name has a character that the .pvtp's own lines cannot hold (a quote, <, >, & or a byte that is "
           "not printable ASCII): name it otherwise";
  }
  // VTK's writer names the pieces' folder after the name up to its first dot: a.b.pvtp's would be
  // a/, which a.c.pvtp would share and silently replace.
  const std::string name = target.filename().string();
  const std::size_t firstDot = name.find('.');
  const std::size_t extensionDot = name.size() - std::string(".pvtp").size();
  if (firstDot == 0)
  {
    return "its name starts with a dot, and VTK's writer names the folder of the pieces after what comes before the "
           "first, which is nothing: name it otherwise (shaded.pvtp, say)";
  }
  if (firstDot != extensionDot)
  {
    std::string dotless = name.substr(0, extensionDot);
    std::replace(dotless.begin(), dotless.end(), '.', '_');
    return "its name has a dot before .pvtp, and VTK's writer names the folder of the pieces after what comes "
           "before the first (" +
      name.substr(0, firstDot) + "/), which other names share: name it without (" + dotless +
      name.substr(extensionDot) + ", say)";
  }
  std::error_code error;
  if (fs::is_directory(target, error))
  {
    return target.string() + " is a folder";
  }
  return piecesFolderProblem(target.parent_path() / target.stem(), target.stem().string());
}

vtkSmartPointer<vtkPolyData> meshPiece(vtkPolyData* mesh, int piece, int pieces, int ghostLevels)
{
  vtkNew<vtkPolyData> numbered;
  numbered->ShallowCopy(mesh); // attributes of its own: the mesh's stay as they are
  const std::string pointIds = globalIdsAsArray(numbered->GetPointData(), mesh->GetNumberOfPoints());
  const std::string cellIds = globalIdsAsArray(numbered->GetCellData(), mesh->GetNumberOfCells());
  vtkNew<vtkExtractPolyDataPiece> extract;
  extract->SetInputData(numbered);
  extract->SetCreateGhostCells(ghostLevels > 0);
  extract->UpdatePiece(piece, pieces, ghostLevels);
  vtkSmartPointer<vtkPolyData> result = extract->GetOutput();
  result->GetPointData()->SetActiveGlobalIds(pointIds.c_str());
  result->GetCellData()->SetActiveGlobalIds(cellIds.c_str());
  result->GetFieldData()->PassData(mesh->GetFieldData()); // the parts' names, a glTF file's lights
  return result;
}

vtkSmartPointer<vtkAlgorithm> pvtpReader(const std::string& fileName)
{
  auto reader = vtkSmartPointer<StrictPPolyDataReader>::New();
  reader->SetFileName(fileName.c_str());
  return reader;
}

std::uintmax_t pieceFileBytes(const std::string& fileName)
{
  // A summary names its pieces in a few hundred bytes each: a larger file is not one.
  constexpr std::uintmax_t largestSummary = std::uintmax_t(64) << 20;
  std::error_code error;
  if (fs::file_size(fileName, error) > largestSummary)
  {
    throw UserError(fileName + ": larger than 64 MB, which no .pvtp summary is: is it a .vtp renamed?");
  }
  std::ifstream summary(fileName);
  std::ostringstream text;
  text << summary.rdbuf();
  const std::string xml = text.str();
  std::uintmax_t bytes = 0;
  for (std::size_t at = xml.find("<Piece"); at != std::string::npos; at = xml.find("<Piece", at + 1))
  {
    const std::string element = xml.substr(at, xml.find('>', at) - at); // to the end where there is no '>'
    const std::size_t source = element.find("Source=\"");
    if (source == std::string::npos)
    {
      continue; // VTK's reader says what it makes of it
    }
    const std::size_t first = source + 8;
    const std::string name = element.substr(first, element.find('"', first) - first);
    const fs::path piece = fs::path(name).is_absolute() ? fs::path(name) : fs::path(fileName).parent_path() / name;
    if (!fs::is_regular_file(piece, error))
    {
      throw UserError(fileName + ": its piece " + name +
        (fs::exists(piece, error) ? " is not a regular file" : " does not exist") +
        ": a .pvtp needs the folder of pieces written with it");
    }
    bytes += fs::file_size(piece, error);
  }
  return bytes;
}

void writePieces(vtkPolyData* piece, const std::string& fileName, vtkMultiProcessController* processes,
  Compression compression, VtpLayout layout)
{
  const int index = processes ? processes->GetLocalProcessId() : 0;
  const std::vector<int> withData = piecesWithData(piece, processes);
  const fs::path target = fs::absolute(fileName);
  const std::string base = target.stem().string();
  const fs::path folder = target.parent_path() / base;
  // Every process checks its piece's names; then the first checks the place and makes the
  // staging folder. Whatever any finds, all stop alike, and no staging folder is left.
  std::string staging = target.string() + ".partial-" + std::to_string(::getpid());
  std::string problem = firstText(processes, xmlNameProblem(piece));
  if (index == 0 && problem.empty())
  {
    problem = onFirstProcess(
      [&]() -> std::string
      {
        const std::string place = pvtpPlaceProblem(fileName);
        if (!place.empty())
        {
          return place;
        }
        removeStaleTemporaries(target.string(), true);
        std::error_code error;
        if (!fs::create_directory(staging, error))
        {
          return "cannot make the folder " + staging + " to write into: " + (error ? error.message() : "it exists");
        }
        return "";
      });
  }
  problem = firstText(processes, problem);
  if (!problem.empty())
  {
    throw UserError(fileName + ": cannot be written: " + problem);
  }
  staging = firstText(processes, index == 0 ? staging : "");
  std::string failure;
  try
  {
    failure = writeOwnPiece(piece, fs::path(staging) / target.filename(), index, withData, compression, layout);
  }
  catch (const std::exception& error) // no memory to encode the arrays, say: the others must hear of it
  {
    failure = error.what();
  }
  failure = firstText(processes, failure);
  if (index == 0)
  {
    failure = onFirstProcess(
      [&]
      {
        bool keepStaging = false;
        const std::string moved = failure.empty() ? moveIntoPlace(staging, target, folder, base, keepStaging) : "";
        std::error_code ignored;
        if (!keepStaging)
        {
          fs::remove_all(staging, ignored);
        }
        return failure.empty() ? moved : failure;
      });
  }
  failure = firstText(processes, failure);
  if (!failure.empty())
  {
    throw UserError(fileName + ": cannot be written: " + failure);
  }
}
}
