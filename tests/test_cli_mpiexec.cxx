// shadelab shade under mpiexec: the processes shade a piece of the mesh each and write one
// .pvtp, whose arrays must be the single process's, bit for bit, at every point of every piece.
#include "ArrayComparison.h"
#include "CliFixture.h"
#include "TestScenes.h"

#include "vtkCellData.h"
#include "vtkIdList.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkXMLPPolyDataReader.h"
#include "vtkXMLPolyDataReader.h"
#include "vtkXMLPolyDataWriter.h"

#include <algorithm>
#include <functional>
#include <regex>
#include <set>
#include <sstream>
#include <vector>

namespace shadelab::testing
{
namespace
{
class CliUnderMpiexec : public Cli
{
protected:
  /// The entries of the test's folder that a write leaves only while it runs or where it failed.
  std::vector<std::string> leftovers() const
  {
    std::vector<std::string> found;
    for (const fs::directory_entry& entry : fs::directory_iterator(folder))
    {
      const std::string name = entry.path().filename().string();
      if (name.find(".partial-") != std::string::npos || name.find(".earlier") != std::string::npos)
      {
        found.push_back(name);
      }
    }
    return found;
  }

  static std::size_t occurrences(const std::string& text, const std::string& part)
  {
    std::size_t count = 0;
    for (std::size_t at = text.find(part); at != std::string::npos; at = text.find(part, at + 1))
    {
      ++count;
    }
    return count;
  }

  /// shadelab under mpiexec with this many processes.
  Result shadelabOn(int processes, const std::string& arguments)
  {
    return shadelab(
      arguments, std::string(MPIEXEC) + " --allow-run-as-root --oversubscribe -np " + std::to_string(processes) + " ");
  }

  template<typename Reader>
  static vtkSmartPointer<vtkPolyData> read(const std::string& path)
  {
    vtkNew<Reader> reader;
    reader->SetFileName(path.c_str());
    reader->Update();
    return reader->GetOutput();
  }

  /// Expects every point array of whole (one process's result) at each point of the pieces
  /// (read as one mesh, their shared points once per piece), found by the points' global ids,
  /// bit for bit; and the pieces' ids to cover every point of whole.
  static void expectWholeAtEveryPiecePoint(vtkPolyData* whole, vtkPolyData* pieces, const std::string& prefix = "")
  {
    vtkDataArray* globalIds = pieces->GetPointData()->GetGlobalIds();
    ASSERT_NE(globalIds, nullptr);
    vtkNew<vtkIdList> ids;
    std::set<vtkIdType> distinct;
    for (vtkIdType k = 0; k < globalIds->GetNumberOfTuples(); ++k)
    {
      ids->InsertNextId(static_cast<vtkIdType>(globalIds->GetTuple1(k)));
      distinct.insert(ids->GetId(k));
    }
    ASSERT_EQ(distinct.size(), static_cast<std::size_t>(whole->GetNumberOfPoints()));
    EXPECT_EQ(*distinct.rbegin(), whole->GetNumberOfPoints() - 1);
    vtkPointData* wholeData = whole->GetPointData();
    ASSERT_GT(wholeData->GetNumberOfArrays(), 4);
    for (int a = 0; a < wholeData->GetNumberOfArrays(); ++a)
    {
      vtkDataArray* values = wholeData->GetArray(a);
      const std::string name = values->GetName();
      auto atIds = vtk::TakeSmartPointer(values->NewInstance());
      atIds->SetNumberOfComponents(values->GetNumberOfComponents());
      atIds->SetNumberOfTuples(ids->GetNumberOfIds());
      values->GetTuples(ids, atIds);
      const std::string pieceName = name == "Normals" ? name : prefix + name;
      expectSameBits(atIds, pieces->GetPointData()->GetArray(pieceName.c_str()), pieceName);
    }
  }

  /// The report's lines, without those that count rays by piece (the first process's, or every
  /// process's with shared points once for each), the times, and the first, which names the files.
  static std::vector<std::string> wholeMeshLines(const std::string& report)
  {
    std::istringstream lines(report);
    std::vector<std::string> kept;
    std::string line;
    std::getline(lines, line);
    while (std::getline(lines, line))
    {
      // (The mean indirect light, summed piece by piece, may differ in its last digit.)
      if (line.rfind("  visibility", 0) != 0 && line.rfind("  interreflection", 0) != 0 &&
        line.rfind("    the constant ambient term", 0) != 0 && line.rfind("  time:", 0) != 0)
      {
        kept.push_back(line);
      }
    }
    return kept;
  }
};

// Shadows and ambient occlusion (the whole surface gathered on every process) on 2 processes,
// interreflection's bounces on 3, whose pieces are uneven: the pieces' arrays are the single
// process's, and so is the report's every line about the whole mesh.
TEST_F(CliUnderMpiexec, ThePiecesHoldWhatOneProcessComputes)
{
  const std::string bounces =
    file("bounces.json", bouncesUnderAMapScene(sourcePath("data/envmaps/studio_small_03_1k.hdr")));
  for (const auto& [scene, processes] :
    { std::make_pair(sourcePath("data/scenes/shadows_occlusion.json"), 2), std::make_pair(bounces, 3) })
  {
    SCOPED_TRACE(scene);
    const std::string arguments = "shade " + goodMesh() + " --scene " + scene;
    const Result alone = shadelab(arguments + " -o " + (folder / "alone.vtp").string());
    ASSERT_EQ(alone.exitCode, 0) << alone.err;
    const Result split = shadelabOn(processes, arguments + " -o " + (folder / "split.pvtp").string());
    ASSERT_EQ(split.exitCode, 0) << split.err;
    EXPECT_EQ(split.err, "");
    EXPECT_EQ(split.out.find("shadelab shade: " + goodMesh() + " -> " + (folder / "split.pvtp").string() + " (" +
                std::to_string(processes) + " processes, a piece each)\n"),
      0u)
      << split.out;
    EXPECT_EQ(wholeMeshLines(split.out), wholeMeshLines(alone.out));
    for (int p = 0; p < processes; ++p)
    {
      EXPECT_TRUE(fs::is_regular_file(folder / "split" / ("split_" + std::to_string(p) + ".vtp"))) << p;
    }
    expectWholeAtEveryPiecePoint(read<vtkXMLPolyDataReader>((folder / "alone.vtp").string()),
      read<vtkXMLPPolyDataReader>((folder / "split.pvtp").string()));
  }
}

// A .pvtp is read a piece per process, whichever number of processes wrote it: here 3 pieces
// on 2 processes, and 2 pieces on 3, one of which then holds none.
TEST_F(CliUnderMpiexec, APvtpIsReadAPiecePerProcess)
{
  const std::string scene = " --scene " + sourcePath("data/scenes/shadows_occlusion.json");
  ASSERT_EQ(shadelab("shade " + goodMesh() + scene + " -o " + (folder / "alone.vtp").string()).exitCode, 0);
  const vtkSmartPointer<vtkPolyData> alone = read<vtkXMLPolyDataReader>((folder / "alone.vtp").string());
  for (const auto& [written, reading] : { std::make_pair(3, 2), std::make_pair(2, 3) })
  {
    SCOPED_TRACE(std::to_string(written) + " pieces on " + std::to_string(reading) + " processes");
    const std::string input = (folder / ("in" + std::to_string(written) + ".pvtp")).string();
    ASSERT_EQ(shadelabOn(written, "shade " + goodMesh() + " --arrays totals -o " + input).exitCode, 0);
    const std::string output = (folder / ("out" + std::to_string(reading) + ".pvtp")).string();
    const Result split = shadelabOn(reading, "shade " + input + scene + " --prefix again_ -o " + output);
    ASSERT_EQ(split.exitCode, 0) << split.err;
    expectWholeAtEveryPiecePoint(alone, read<vtkXMLPPolyDataReader>(output), "again_");
  }
}

// shadelab compare reads a .pvtp's pieces as the mesh they were cut from, each point once in
// the order of its global id, so that what two processes wrote compares with what one wrote. A
// difference is placed at the whole mesh's point; copies of a point that differ, and a cell on
// two pieces, are each said.
TEST_F(CliUnderMpiexec, CompareReadsThePiecesAsOneMesh)
{
  const std::string alone = (folder / "alone.vtp").string(), split = (folder / "split.pvtp").string();
  ASSERT_EQ(shadelab("shade " + goodMesh() + " --arrays totals -o " + alone).exitCode, 0);
  ASSERT_EQ(shadelabOn(2, "shade " + goodMesh() + " --arrays totals -o " + split).exitCode, 0);
  const vtkIdType copies = read<vtkXMLPPolyDataReader>(split)->GetNumberOfPoints() - 35947;
  ASSERT_GT(copies, 0);
  Result compared = shadelab("compare " + alone + " " + split);
  EXPECT_EQ(compared.exitCode, 0) << compared.out << compared.err;
  EXPECT_EQ(compared.out.substr(0, compared.out.find('\n') + 1),
    "shadelab compare: the result " + split +
      " (35947 points, 69451 cells, put in the order of their global ids, which are not themselves compared; " +
      std::to_string(copies) + " copies of points that pieces share left out) against the baseline " + alone +
      " (35947 points, 69451 cells); points and cells matched by id\n");
  EXPECT_NE(compared.out.find("\nPASS: 6 arrays agree\n"), std::string::npos) << compared.out;

  // A point only the second piece holds, and one both hold.
  const fs::path second = folder / "split" / "split_1.vtp";
  const vtkSmartPointer<vtkPolyData> first = read<vtkXMLPolyDataReader>((folder / "split" / "split_0.vtp").string());
  const vtkSmartPointer<vtkPolyData> original = read<vtkXMLPolyDataReader>(second.string());
  auto idsOf = [](vtkDataSetAttributes* attributes)
  {
    std::vector<vtkIdType> ids;
    vtkDataArray* globalIds = attributes->GetGlobalIds();
    EXPECT_NE(globalIds, nullptr);
    for (vtkIdType k = 0; globalIds && k < globalIds->GetNumberOfTuples(); ++k)
    {
      ids.push_back(static_cast<vtkIdType>(globalIds->GetTuple1(k)));
    }
    return ids;
  };
  const std::vector<vtkIdType> firstIds = idsOf(first->GetPointData());
  const std::vector<vtkIdType> secondIds = idsOf(original->GetPointData());
  const std::set<vtkIdType> inFirst(firstIds.begin(), firstIds.end());
  auto inSecond = [&](bool shared)
  {
    return static_cast<vtkIdType>(std::find_if(secondIds.begin(), secondIds.end(),
                                    [&](vtkIdType id) { return inFirst.count(id) == (shared ? 1u : 0u); }) -
      secondIds.begin());
  };
  const vtkIdType own = inSecond(false), shared = inSecond(true);
  ASSERT_LT(std::max(own, shared), original->GetNumberOfPoints());
  auto compareWithSecond = [&](const std::function<void(vtkPolyData*)>& edit)
  {
    vtkNew<vtkPolyData> piece;
    piece->DeepCopy(original);
    edit(piece);
    vtkNew<vtkXMLPolyDataWriter> writer;
    writer->SetInputData(piece);
    writer->SetFileName(second.c_str());
    EXPECT_EQ(writer->Write(), 1);
    return shadelab("compare " + alone + " " + split);
  };
  auto raiseTotal = [](vtkIdType point)
  {
    return [point](vtkPolyData* piece)
    {
      vtkDataArray* total = piece->GetPointData()->GetArray("total");
      total->SetComponent(point, 0, total->GetComponent(point, 0) + 0.25);
    };
  };
  compared = compareWithSecond(raiseTotal(own));
  EXPECT_EQ(compared.exitCode, 1) << compared.out << compared.err;
  EXPECT_NE(compared.out.find("  DIFFER total "), std::string::npos) << compared.out;
  EXPECT_NE(
    compared.out.find("point " + std::to_string(secondIds[static_cast<std::size_t>(own)]) + " ("), std::string::npos)
    << compared.out;

  compared = compareWithSecond(raiseTotal(shared));
  EXPECT_EQ(compared.exitCode, 2);
  const vtkIdType sharedId = secondIds[static_cast<std::size_t>(shared)];
  const auto inFirstPiece = std::find(firstIds.begin(), firstIds.end(), sharedId) - firstIds.begin();
  EXPECT_EQ(compared.err,
    "shadelab compare: " + split + ": the point with global id " + std::to_string(sharedId) +
      " has different values of 'total' in two of its pieces (points " + std::to_string(inFirstPiece) + " and " +
      std::to_string(first->GetNumberOfPoints() + shared) +
      " as read): the pieces are not of one mesh, or each computed the point alone; compare its pieces' files one "
      "at a time\n");

  const std::vector<vtkIdType> firstCellIds = idsOf(first->GetCellData());
  ASSERT_FALSE(firstCellIds.empty());
  const vtkIdType firstCellId = firstCellIds.front();
  compared = compareWithSecond(
    [&](vtkPolyData* piece) { piece->GetCellData()->GetGlobalIds()->SetTuple1(0, static_cast<double>(firstCellId)); });
  EXPECT_EQ(compared.exitCode, 2);
  EXPECT_EQ(compared.err,
    "shadelab compare: " + split + ": the global cell id " + std::to_string(firstCellId) +
      " is on two of its pieces' polygons: the pieces are not of one mesh, or their copies of a cell are not marked "
      "as ghost cells (vtkGhostType)\n");
}

// A warning that every process meets (each reads the file) is said once; the second process's
// piece of a one-triangle mesh is empty, and the .pvtp names only the first's.
TEST_F(CliUnderMpiexec, AWarningIsSaidOnce)
{
  const std::string truncated = file("truncated.vtk",
    "# vtk DataFile Version 3.0\nt\nASCII\nDATASET POLYDATA\nPOINTS 3 float\n0 0 0 1 0 0 0 1 0\n"
    "POLYGONS 1 4\n3 0 1 2\nPOINT_DATA 3\nNORMALS Normals float\n0 0 1 0 0\n");
  const std::string pvtp = (folder / "out.pvtp").string();
  const Result result = shadelabOn(2, "shade " + truncated + " -s " + goodScene() + " -o " + pvtp);
  EXPECT_EQ(result.exitCode, 0) << result.err;
  EXPECT_EQ(result.err,
    "shadelab: warning: " + truncated +
      ": Error reading ascii data. Possible mismatch of datasize with declaration.\n");
  EXPECT_EQ(occurrences(slurp(pvtp), "<Piece "), 1u);
  EXPECT_EQ(read<vtkXMLPPolyDataReader>(pvtp)->GetNumberOfPoints(), 3);
}

// A failure says why once, on the first process, whichever process met it; nothing is written.
TEST_F(CliUnderMpiexec, AFailureIsSaidOnceAndNothingIsWritten)
{
  const std::string vtp = (folder / "out.vtp").string();
  Result result = shadelabOn(2, "shade " + goodMesh() + " -o " + vtp);
  EXPECT_NE(result.exitCode, 0);
  EXPECT_EQ(result.out, "");
  const std::string onePiecePerProcess = "shadelab: " + vtp +
    ": 2 processes write a piece of the mesh each: name a .pvtp, which ParaView opens as one mesh (its pieces go in "
    "a folder beside it)\n";
  EXPECT_EQ(result.err.substr(0, onePiecePerProcess.size()), onePiecePerProcess);
  // The filter fails on every process: the input already has the array it would write.
  const std::string shaded = (folder / "shaded.vtp").string();
  ASSERT_EQ(shadelab("shade " + goodMesh() + " -o " + shaded).exitCode, 0);
  result = shadelabOn(2, "shade " + shaded + " -o " + (folder / "again.pvtp").string());
  EXPECT_NE(result.exitCode, 0);
  const std::string clash = "shadelab: " + shaded +
    ": the input already has a point array named 'ambient', which this filter would write: set an array prefix "
    "(shadelab shade --prefix) to keep both\n";
  EXPECT_EQ(result.err.substr(0, clash.size()), clash);
  EXPECT_EQ(occurrences(result.err, "shadelab:"), 1u) << result.err; // after it, mpiexec's own lines
  EXPECT_FALSE(fs::exists(folder / "again.pvtp"));
  EXPECT_FALSE(fs::exists(folder / "again"));
  EXPECT_EQ(leftovers(), std::vector<std::string>{});
  // A piece that only the second process reads is cut short: the first says what the second met.
  const std::string pieces = (folder / "pieces.pvtp").string();
  ASSERT_EQ(shadelabOn(2, "shade " + goodMesh() + " --arrays totals -o " + pieces).exitCode, 0);
  fs::resize_file(folder / "pieces" / "pieces_1.vtp", 3000);
  result = shadelabOn(2, "shade " + pieces + " --prefix again_ -o " + (folder / "again.pvtp").string());
  EXPECT_NE(result.exitCode, 0);
  EXPECT_EQ(result.err.rfind("shadelab: " + pieces + ": cannot be read as .pvtp: its piece ", 0), 0u) << result.err;
  EXPECT_NE(result.err.find("pieces_1.vtp: "), std::string::npos) << result.err;
  EXPECT_EQ(result.err.find("another process"), std::string::npos) << result.err;
  EXPECT_EQ(occurrences(result.err, "shadelab:"), 1u) << result.err;
  EXPECT_FALSE(fs::exists(folder / "again.pvtp"));
  // Splitting sharp edges adds points, which pieces cannot take.
  result = shadelabOn(2, "shade " + goodMesh() + " --split-sharp-edges 30 -o " + (folder / "split.pvtp").string());
  const std::string noSplitting = "shadelab: --split-sharp-edges: splitting adds points, which a mesh split over "
                                  "processes cannot take: split it in one process first (its output keeps the split "
                                  "normals, which shade then uses)\n";
  EXPECT_EQ(result.err.substr(0, noSplitting.size()), noSplitting);
  // Only shade runs under mpiexec: the others would each do the whole work, into one file.
  result = shadelabOn(2, "render " + goodMesh() + " -o " + (folder / "picture.png").string());
  const std::string shadeOnly =
    "shadelab: only `shadelab shade` runs under mpiexec, a piece of the mesh on each process; run `shadelab render` "
    "without it\n";
  EXPECT_EQ(result.err.substr(0, shadeOnly.size()), shadeOnly);
  EXPECT_FALSE(fs::exists(folder / "picture.png"));
}
}

// One process writes a .pvtp of one piece over an earlier run's two: the earlier pieces go, and
// so does what a killed run left of its writing. A folder of the pieces' name that holds
// anything else is left alone, with a message, and so is a folder where the .pvtp would go.
TEST_F(CliUnderMpiexec, APvtpReplacesOnlyItsOwnPieces)
{
  const std::string pvtp = (folder / "shaded.pvtp").string();
  ASSERT_EQ(shadelabOn(2, "shade " + goodMesh() + " -o " + pvtp).exitCode, 0);
  ASSERT_TRUE(fs::is_regular_file(folder / "shaded" / "shaded_1.vtp"));
  fs::create_directories(folder / "shaded.pvtp.partial-99999999" / "shaded"); // no such process
  ASSERT_EQ(shadelab("shade " + goodMesh() + " -o " + pvtp).exitCode, 0);
  EXPECT_TRUE(fs::is_regular_file(folder / "shaded" / "shaded_0.vtp"));
  EXPECT_FALSE(fs::exists(folder / "shaded" / "shaded_1.vtp"));
  EXPECT_EQ(leftovers(), std::vector<std::string>{});
  const Result again = shadelab("shade " + goodMesh() + " --arrays totals -o " + pvtp);
  ASSERT_EQ(again.exitCode, 0) << again.err;
  vtkNew<vtkXMLPPolyDataReader> reader;
  reader->SetFileName(pvtp.c_str());
  reader->Update();
  EXPECT_EQ(reader->GetOutput()->GetNumberOfPoints(), 35947);
  EXPECT_NE(reader->GetOutput()->GetPointData()->GetArray("total"), nullptr);
  EXPECT_EQ(reader->GetOutput()->GetPointData()->GetArray("shading_flags"), nullptr); // not in totals
  file("shaded/notes.txt", "mine");
  expectError("shade " + goodMesh() + " -o " + pvtp,
    pvtp + ": cannot be written: " + (folder / "shaded").string() +
      ", where its pieces go, holds other files (notes.txt): move them or write elsewhere");
  EXPECT_EQ(slurp(folder / "shaded" / "notes.txt"), "mine");
  EXPECT_TRUE(fs::is_regular_file(folder / "shaded" / "shaded_0.vtp"));
  EXPECT_EQ(leftovers(), std::vector<std::string>{});
  // A summary names its pieces after it: its name must be one that VTK writes as it is.
  const std::string ampersand = (folder / "a&b.pvtp").string();
  expectError("shade " + goodMesh() + " -o '" + ampersand + "'",
    ampersand +
      ": cannot be written: its name has a character that the .pvtp's own lines cannot hold (a quote, <, "
      ">, & or a byte that is not printable ASCII): name it otherwise");
  // VTK's writer names the pieces' folder after the name up to its first dot, which other names
  // share: such a name is refused before any work, and nothing is written.
  const std::string dotted = (folder / "bunny.shaded.pvtp").string();
  const std::string dottedMessage = dotted +
    ": cannot be written: its name has a dot before .pvtp, and VTK's writer names the folder of the pieces "
    "after what comes before the first (bunny/), which other names share: name it without (bunny_shaded.pvtp, say)";
  expectError("shade " + goodMesh() + " -o " + dotted, dottedMessage);
  const Result onTwo = shadelabOn(2, "shade " + goodMesh() + " -o " + dotted);
  EXPECT_NE(onTwo.exitCode, 0);
  EXPECT_EQ(onTwo.err.substr(0, dottedMessage.size() + 11), "shadelab: " + dottedMessage + "\n");
  EXPECT_EQ(occurrences(onTwo.err, "shadelab:"), 1u) << onTwo.err;
  EXPECT_FALSE(fs::exists(folder / "bunny"));
  const std::string hidden = (folder / ".shaded.pvtp").string();
  expectError("shade " + goodMesh() + " -o " + hidden,
    hidden +
      ": cannot be written: its name starts with a dot, and VTK's writer names the folder of the pieces after what "
      "comes before the first, which is nothing: name it otherwise (shaded.pvtp, say)");
  fs::create_directories(folder / "taken.pvtp");
  expectError("shade " + goodMesh() + " -o " + (folder / "taken.pvtp").string(),
    (folder / "taken.pvtp").string() + ": cannot be written: " + (folder / "taken.pvtp").string() + " is a folder");
  EXPECT_TRUE(fs::is_empty(folder / "taken.pvtp"));
}
}
