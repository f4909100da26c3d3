#pragma once
// Checks of a mesh file, made while VTK's reader reads it in a process of its own
// (MeshFiles.cxx); what they find wins over whatever the reader made of the file. A PLY
// header's counts against the bytes the file has, an OBJ's indices against what it lists: a
// lie there crashes or stalls VTK's readers, or has them read out of bounds. And every number
// of a text file (OBJ, ASCII PLY, ASCII STL), read strictly: VTK 9.1's readers read "1.0abc"
// as 1, "abc" as 0 or as the previous value and "nan" as NaN, and skip a line they do not
// know, all without a word. Found here, each gets a message that says where ("line 12: ...")
// and what is wrong.
#include <cstdint>
#include <string>
#include <string_view>

namespace shadelab::app
{
/// What a check of a mesh file found.
struct MeshFileCheck
{
  /// What is wrong, or "" when nothing was found (a file that passes may still be refused by
  /// its reader, or by the checks of the mesh it reads).
  std::string problem;
  /// What the file holds that the reader skips, for the command's summary ("3 's' statements
  /// (smoothing groups are not read)"), or "".
  std::string ignored;
};

/// Checks the file by its extension (lower case, with its dot); fileSize in bytes. Only .obj,
/// .ply and .stl files are checked.
MeshFileCheck checkMeshFile(const std::string& fileName, const std::string& extension, std::uintmax_t fileSize);

/// A PLY file's header; text is the file from its start (at least its header), fileSize the
/// whole file's bytes.
std::string plyHeaderProblem(std::string_view text, std::uintmax_t fileSize);

/// A whole PLY file: its header, and then every value of its body, ASCII or binary.
std::string plyFileProblem(std::string_view text);

/// A whole OBJ file: every statement, number and index, as VTK 9.1's vtkOBJReader reads them.
MeshFileCheck objFileCheck(std::string_view text);

/// A whole STL file, ASCII or binary as VTK's reader takes it (vtksys's guess from its first
/// 256 bytes).
MeshFileCheck stlFileCheck(std::string_view text, bool ascii);
}
