#pragma once
// Reading and writing meshes by file extension, with errors that name the file.
#include "vtkAlgorithm.h"
#include "vtkPolyData.h"
#include "vtkSmartPointer.h"
#include "vtkXMLWriterBase.h"

#include <functional>
#include <initializer_list>
#include <stdexcept>
#include <string>

namespace shadelab::app
{
/// A problem the user can fix; what() is the whole message, naming the file.
class UserError : public std::runtime_error
{
public:
  using std::runtime_error::runtime_error;
};

/// The file name's extension with its dot, in lower case (".obj"), or "".
std::string lowerExtension(const std::string& fileName);

/// The extensions readMesh understands, for messages.
extern const char* const readableExtensions;
/// The extensions writeMesh writes.
constexpr std::initializer_list<const char*> meshExtensions = { ".vtp", ".vtk" };
/// The extensions `shadelab shade` writes: writeMesh's, and .pvtp (PieceFiles.h's writePieces).
constexpr std::initializer_list<const char*> shadedMeshExtensions = { ".vtp", ".pvtp", ".vtk" };

/// Writes fileName through a temporary file in the same folder: write(temporary) returns ""
/// on success or the reason it failed; only a complete file is renamed over fileName, so a
/// failed run never leaves a partial file or spoils an existing one. Throws UserError.
void writeThroughTemporary(
  const std::string& fileName, const std::function<std::string(const std::string& temporary)>& write);

/// Removes what runs killed before they could left of their writing to fileName: the files
/// FILE.partial-PID whose process is gone, and with folders (a .pvtp's staging) such folders too.
void removeStaleTemporaries(const std::string& fileName, bool folders = false);

/// Writes text to fileName whole, through a temporary file (a report, a CSV). Throws UserError.
void writeTextFile(const std::string& fileName, const std::string& text);

/// Which piece of a mesh split over processes readMesh keeps: piece `index` of `count` (0 of 1:
/// the whole mesh).
struct PieceToRead
{
  int index = 0;
  int count = 1;
};

/// Reads .vtp, .pvtp, .vtk (legacy polydata), .ply, .obj, .stl, .gltf or .glb, showing
/// progress on a terminal. An .obj, .ply or .stl is checked whole while it is read
/// (MeshFileChecks.h); ignored, when given, is set to what the file holds that the reader skips
/// ("" when nothing). Of a piece of several, a .pvtp's reader reads the pieces it names that
/// fall to that piece; any other file is read whole, and the piece kept (PieceFiles.h's
/// meshPiece), all in the reading process. Throws UserError.
vtkSmartPointer<vtkPolyData> readMesh(
  const std::string& fileName, std::string* ignored = nullptr, PieceToRead piece = {});

/// The extensions readDataSet understands, for messages.
extern const char* const readableDataSetExtensions;

/// Reads any VTK dataset (.vtu, .vti, .vts, .vtr, legacy .vtk of any type) as readMesh reads a
/// mesh, in a reading process of its own; .vtp, .pvtp (every piece), .ply, .obj and .stl through readMesh. Throws
/// UserError.
vtkSmartPointer<vtkDataSet> readDataSet(const std::string& fileName);

/// Throws UserError unless fileName ends in one of the extensions (in any case) and its
/// folder exists.
void checkOutputFile(const std::string& fileName, std::initializer_list<const char*> extensions);

/// How .vtp data are compressed. LZ4 writes about 7x and reads about 10x faster than zlib
/// for files about 1.5x larger (measured on a 1M-vertex mesh with every array); ParaView
/// reads all three.
enum class Compression
{
  LZ4,
  ZLib,
  None,
};

/// The compression a command line names: "lz4", "zlib" or "none" (compressionNames).
Compression compressionNamed(const std::string& name);
constexpr std::initializer_list<const char*> compressionNames = { "lz4", "zlib", "none" };

/// Where a .vtp keeps its arrays' bytes: in base64 inside each array's element (Inline, the
/// default), or raw in one block at the end (RawAppended: a quarter smaller, and written in
/// about two thirds of the time, but Debian 12's ParaView 5.11 reads such a file as empty since
/// its Expat security update: docs/packaging.md section 3).
enum class VtpLayout
{
  Inline,
  RawAppended,
};

/// VTK's reader for the file's extension, set to read it: without ShadeLab's checks and
/// without a process of its own (the benchmark's floor). Throws UserError for an unknown one.
vtkSmartPointer<vtkAlgorithm> vtkReaderFor(const std::string& fileName);

/// VTK's writer of mesh to path, as writeMesh writes extension (".vtp" or ".vtk"): Update()
/// writes, and GetErrorCode() tells whether it could.
vtkSmartPointer<vtkAlgorithm> vtkWriterFor(vtkPolyData* mesh, const std::string& path, const std::string& extension,
  Compression compression, VtpLayout layout = VtpLayout::Inline);

/// Sets an XML writer's layout and compression as writeMesh sets them for a .vtp.
void setXmlEncoding(vtkXMLWriterBase* writer, Compression compression, VtpLayout layout);

/// Whether VTK 9.1's XML writer would write text unescaped into an attribute, making the file
/// unreadable: a quote, <, > or &, or a byte that is not printable ASCII.
bool xmlCannotHold(const std::string& text);

/// Why the mesh cannot be written as VTK XML ("" where it can): an array's name that VTK 9.1
/// would write unescaped, making the file unreadable.
std::string xmlNameProblem(vtkPolyData* mesh);

/// Writes .vtp (binary) or legacy .vtk (binary), through a temporary file, showing progress on
/// a terminal. Throws UserError.
void writeMesh(vtkPolyData* mesh, const std::string& fileName, Compression compression = Compression::LZ4,
  VtpLayout layout = VtpLayout::Inline);
}
