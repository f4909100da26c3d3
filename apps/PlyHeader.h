#pragma once
// A PLY file's header as vtkPLY reads it: its elements, their properties and their types, and
// where the body starts; shared by the checks of the header and of the body.
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace shadelab::app
{
/// A PLY scalar type (Turk's format and its sized aliases) and the values it holds.
struct PlyType
{
  const char* name;
  int bytes;
  bool real;
  double least, most; // for the integer types
};

struct PlyProperty
{
  std::string name;
  const PlyType* type = nullptr;      // of the value, or of a list's items
  const PlyType* countType = nullptr; // a list's count; null for a scalar
  bool coordinate = false;            // a vertex's x, y or z
  bool vertexIndices = false;         // a face's vertex_indices
};

struct PlyElement
{
  std::string name;
  long long count = 0;
  std::vector<PlyProperty> properties;
};

enum class PlyFormat
{
  Ascii,
  BinaryLittleEndian,
  BinaryBigEndian,
};

struct PlyHeader
{
  std::vector<PlyElement> elements;
  PlyFormat format = PlyFormat::BinaryLittleEndian;
  std::size_t bodyStart = 0; // the byte after end_header's line
  long long lines = 0;       // the header's
};

/// Reads the header's lines into header; what is wrong with them, or "".
std::string parsePlyHeader(std::string_view text, PlyHeader& header);

/// The header's counts against each other and against the bytes the file has after it.
std::string plyCountsProblem(const PlyHeader& header, std::uintmax_t fileSize);

/// The count of the vertex element, 0 if there is none.
long long vertexCount(const PlyHeader& header);
}
