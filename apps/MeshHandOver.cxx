#include "MeshHandOver.h"

#include "MeshFiles.h"
#include "VtkErrorCapture.h"

#include "vtkCellArray.h"
#include "vtkCellData.h"
#include "vtkDataArray.h"
#include "vtkErrorCode.h"
#include "vtkFieldData.h"
#include "vtkInformation.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkStringArray.h"
#include "vtkXMLDataSetWriter.h"
#include "vtkXMLGenericDataObjectReader.h"

#include <cstdint>
#include <cstring>
#include <fcntl.h>
#include <map>
#include <mutex>
#include <stdexcept>
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>
#include <vector>

namespace shadelab::app
{
namespace
{
// ---- Raw: a table, then each array's bytes at a page boundary ----

constexpr char rawMagic[8] = { 'S', 'L', 'M', 'E', 'S', 'H', '1', '\n' };
constexpr std::size_t page = 4096;

/// Where an array goes in the mesh.
enum Place : std::int32_t
{
  Points,
  VertOffsets,
  VertIds,
  LineOffsets,
  LineIds,
  PolyOffsets,
  PolyIds,
  StripOffsets,
  StripIds,
  PointData,
  CellData,
  FieldData,
  PlaceCount
};

struct Entry
{
  std::int32_t place = 0, type = 0, components = 0, attribute = -1;
  std::int64_t tuples = 0;
  std::uint64_t offset = 0, bytes = 0;
  bool named = false, componentsNamed = false;
  std::string name;
  std::vector<std::string> componentNames;
  vtkDataArray* array = nullptr; // the child's, while writing
  std::string text;              // a string array's values, each after its length (packedText)
};

/// A field-data string array (part names, a scene's JSON) as one block: each value's length as
/// 32 bits, then its bytes.
std::string packedText(vtkStringArray* strings)
{
  std::string block;
  for (vtkIdType i = 0; i < strings->GetNumberOfValues(); ++i)
  {
    const std::string& value = strings->GetValue(i);
    const auto size = static_cast<std::uint32_t>(value.size());
    block.append(reinterpret_cast<const char*>(&size), sizeof size);
    block += value;
  }
  return block;
}

vtkCellArray* cellsAt(vtkPolyData* mesh, int kind)
{
  vtkCellArray* cells[] = { mesh->GetVerts(), mesh->GetLines(), mesh->GetPolys(), mesh->GetStrips() };
  return cells[kind];
}

/// Whether the array is one block of numbers in memory, as raw hand-over needs.
vtkDataArray* plainArray(vtkAbstractArray* array)
{
  vtkDataArray* data = vtkDataArray::SafeDownCast(array);
  return data && data->HasStandardMemoryLayout() && data->GetDataType() != VTK_BIT ? data : nullptr;
}

/// The entries for every array of the mesh, or an empty list if one of them is not plain.
std::vector<Entry> entriesOf(vtkPolyData* mesh)
{
  std::vector<Entry> entries;
  bool allPlain = true;
  auto add = [&](vtkAbstractArray* abstract, Place place, int attribute)
  {
    auto* strings = vtkStringArray::SafeDownCast(abstract);
    if (strings && place == FieldData && strings->GetNumberOfComponents() == 1)
    {
      Entry entry;
      entry.place = place;
      entry.type = VTK_STRING;
      entry.components = 1;
      entry.tuples = strings->GetNumberOfValues();
      entry.text = packedText(strings);
      entry.bytes = entry.text.size();
      entry.named = strings->GetName() != nullptr;
      entry.name = entry.named ? strings->GetName() : "";
      entries.push_back(std::move(entry));
      return;
    }
    vtkDataArray* array = plainArray(abstract);
    allPlain = allPlain && array;
    if (!array)
    {
      return;
    }
    Entry entry;
    entry.place = place;
    entry.type = array->GetDataType();
    entry.components = array->GetNumberOfComponents();
    entry.attribute = attribute;
    entry.tuples = array->GetNumberOfTuples();
    entry.bytes =
      static_cast<std::uint64_t>(array->GetNumberOfValues()) * static_cast<std::uint64_t>(array->GetDataTypeSize());
    entry.named = array->GetName() != nullptr;
    entry.name = entry.named ? array->GetName() : "";
    entry.componentsNamed = array->HasAComponentName();
    for (int c = 0; entry.componentsNamed && c < entry.components; ++c)
    {
      entry.componentNames.push_back(array->GetComponentName(c) ? array->GetComponentName(c) : "");
    }
    entry.array = array;
    entries.push_back(std::move(entry));
  };
  if (mesh->GetPoints())
  {
    add(mesh->GetPoints()->GetData(), Points, -1);
  }
  for (int kind = 0; kind < 4; ++kind)
  {
    add(cellsAt(mesh, kind)->GetOffsetsArray(), Place(VertOffsets + 2 * kind), -1);
    add(cellsAt(mesh, kind)->GetConnectivityArray(), Place(VertIds + 2 * kind), -1);
  }
  for (const auto& [data, place] : { std::make_pair<vtkDataSetAttributes*, Place>(mesh->GetPointData(), PointData),
         std::make_pair<vtkDataSetAttributes*, Place>(mesh->GetCellData(), CellData) })
  {
    for (int a = 0; a < data->GetNumberOfArrays(); ++a)
    {
      add(data->GetAbstractArray(a), place, data->IsArrayAnAttribute(a));
    }
  }
  for (int a = 0; a < mesh->GetFieldData()->GetNumberOfArrays(); ++a)
  {
    add(mesh->GetFieldData()->GetAbstractArray(a), FieldData, -1);
  }
  return allPlain ? entries : std::vector<Entry>{};
}

// The table: fixed-width numbers (native byte order: both sides are one program on one
// machine) and length-prefixed strings.
template<typename Number>
void put(std::string& table, Number value)
{
  table.append(reinterpret_cast<const char*>(&value), sizeof value);
}

void putText(std::string& table, const std::string& text)
{
  put<std::uint32_t>(table, static_cast<std::uint32_t>(text.size()));
  table += text;
}

/// The file's first bytes: the magic, the table's length, the table.
std::string tableOf(const std::vector<Entry>& entries)
{
  std::string table;
  put<std::uint64_t>(table, entries.size());
  for (const Entry& entry : entries)
  {
    put(table, entry.place);
    put(table, entry.type);
    put(table, entry.components);
    put(table, entry.attribute);
    put(table, entry.tuples);
    put(table, entry.offset);
    put(table, entry.bytes);
    put<std::uint8_t>(table, entry.named);
    putText(table, entry.name);
    put<std::uint8_t>(table, entry.componentsNamed);
    put<std::uint32_t>(table, static_cast<std::uint32_t>(entry.componentNames.size()));
    for (const std::string& name : entry.componentNames)
    {
      putText(table, name);
    }
  }
  std::string head(rawMagic, sizeof rawMagic);
  put<std::uint64_t>(head, table.size());
  return head + table;
}

void writeAt(int fd, const void* data, std::size_t size, std::uint64_t offset)
{
  const char* bytes = static_cast<const char*>(data);
  while (size > 0)
  {
    const ssize_t written = ::pwrite(fd, bytes, size, static_cast<off_t>(offset));
    if (written <= 0)
    {
      throw std::runtime_error("the mesh could not be handed over (out of memory?)");
    }
    bytes += written;
    size -= static_cast<std::size_t>(written);
    offset += static_cast<std::uint64_t>(written);
  }
}

std::uint64_t roundUpToPage(std::uint64_t bytes)
{
  return (bytes + page - 1) / page * page;
}

void handOverRaw(std::vector<Entry>& entries, const std::string& path)
{
  // The table's size does not depend on the offsets in it: lay out once, then write.
  std::uint64_t offset = roundUpToPage(tableOf(entries).size());
  for (Entry& entry : entries)
  {
    entry.offset = offset;
    offset = roundUpToPage(offset + entry.bytes);
  }
  const std::string table = tableOf(entries);
  const int fd = ::open(path.c_str(), O_WRONLY);
  if (fd < 0)
  {
    throw std::runtime_error("the mesh could not be handed over: its result file does not open");
  }
  try
  {
    writeAt(fd, table.data(), table.size(), 0);
    for (const Entry& entry : entries)
    {
      writeAt(fd, entry.array ? entry.array->GetVoidPointer(0) : entry.text.data(),
        static_cast<std::size_t>(entry.bytes), entry.offset);
    }
  }
  catch (...)
  {
    ::close(fd);
    throw;
  }
  ::close(fd);
}

/// Reads the table, every value checked against the file it describes.
class TableReader
{
public:
  TableReader(const std::string& bytes)
    : bytes_(bytes)
  {
  }

  template<typename Number>
  Number number()
  {
    Number value;
    take(&value, sizeof value);
    return value;
  }
  std::string text()
  {
    const std::uint32_t size = number<std::uint32_t>();
    if (size > bytes_.size() - at_)
    {
      fail();
    }
    std::string value = bytes_.substr(at_, size);
    at_ += size;
    return value;
  }
  [[noreturn]] static void fail() { throw std::runtime_error("the reading process handed over a damaged mesh"); }

private:
  void take(void* into, std::size_t size)
  {
    if (size > bytes_.size() - at_)
    {
      fail();
    }
    std::memcpy(into, bytes_.data() + at_, size);
    at_ += size;
  }
  const std::string& bytes_;
  std::size_t at_ = 0;
};

// Mapped arrays give their pages back through VTK's free function, which is told only the
// address: the sizes are kept here.
std::mutex mappedMutex;
std::map<void*, std::size_t>& mappedSizes()
{
  static std::map<void*, std::size_t> sizes;
  return sizes;
}

void unmapArray(void* address)
{
  std::size_t size = 0;
  {
    const std::lock_guard<std::mutex> lock(mappedMutex);
    auto found = mappedSizes().find(address);
    if (found == mappedSizes().end())
    {
      return;
    }
    size = found->second;
    mappedSizes().erase(found);
  }
  ::munmap(address, size);
}

vtkSmartPointer<vtkDataArray> mappedArray(const Entry& entry, int fd, std::uint64_t fileSize)
{
  auto array = vtk::TakeSmartPointer(vtkDataArray::CreateDataArray(entry.type));
  const std::uint64_t values = static_cast<std::uint64_t>(entry.tuples) * static_cast<std::uint64_t>(entry.components);
  if (!array || !array->HasStandardMemoryLayout() || entry.type == VTK_BIT || entry.components < 1 ||
    entry.tuples < 0 || entry.offset % page != 0 || entry.bytes > fileSize ||
    (entry.bytes > 0 && entry.offset > fileSize - entry.bytes) ||
    (entry.components > 0 &&
      values / static_cast<std::uint64_t>(entry.components) != static_cast<std::uint64_t>(entry.tuples)) ||
    values * static_cast<std::uint64_t>(array->GetDataTypeSize()) != entry.bytes)
  {
    TableReader::fail();
  }
  array->SetNumberOfComponents(entry.components);
  if (entry.named)
  {
    array->SetName(entry.name.c_str());
  }
  for (std::size_t c = 0; entry.componentsNamed && c < entry.componentNames.size(); ++c)
  {
    array->SetComponentName(static_cast<vtkIdType>(c), entry.componentNames[c].c_str());
  }
  if (entry.bytes == 0)
  {
    array->SetNumberOfTuples(0);
    return array;
  }
  // Private: copy on write, so that the arrays can be changed like any other. Populated: the
  // pages are mapped in one go here, not one fault at a time when first read.
  void* pages = ::mmap(
    nullptr, entry.bytes, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_POPULATE, fd, static_cast<off_t>(entry.offset));
  if (pages == MAP_FAILED)
  {
    throw std::bad_alloc();
  }
  {
    const std::lock_guard<std::mutex> lock(mappedMutex);
    mappedSizes()[pages] = entry.bytes;
  }
  array->SetVoidArray(pages, static_cast<vtkIdType>(values), 0, vtkAbstractArray::VTK_DATA_ARRAY_USER_DEFINED);
  array->SetArrayFreeFunction(unmapArray);
  return array;
}

/// A string array packedText wrote: read (not mapped, a few bytes) and checked value by value.
vtkSmartPointer<vtkStringArray> unpackedText(const Entry& entry, int fd, std::uint64_t fileSize)
{
  if (entry.place != FieldData || entry.components != 1 || entry.tuples < 0 || entry.bytes > fileSize ||
    entry.offset > fileSize - entry.bytes)
  {
    TableReader::fail();
  }
  std::string block(static_cast<std::size_t>(entry.bytes), '\0');
  if (::pread(fd, block.data(), block.size(), static_cast<off_t>(entry.offset)) != static_cast<ssize_t>(block.size()))
  {
    TableReader::fail();
  }
  auto strings = vtkSmartPointer<vtkStringArray>::New();
  if (entry.named)
  {
    strings->SetName(entry.name.c_str());
  }
  std::size_t at = 0;
  for (std::int64_t i = 0; i < entry.tuples; ++i)
  {
    std::uint32_t size = 0;
    if (block.size() - at < sizeof size)
    {
      TableReader::fail();
    }
    std::memcpy(&size, block.data() + at, sizeof size);
    at += sizeof size;
    if (size > block.size() - at)
    {
      TableReader::fail();
    }
    strings->InsertNextValue(block.substr(at, size));
    at += size;
  }
  if (at != block.size())
  {
    TableReader::fail();
  }
  return strings;
}

vtkSmartPointer<vtkPolyData> takeOverRaw(const std::string& table, int fd, std::uint64_t fileSize)
{
  TableReader reader(table);
  const std::uint64_t count = reader.number<std::uint64_t>();
  auto mesh = vtkSmartPointer<vtkPolyData>::New();
  vtkSmartPointer<vtkDataArray> cellArrays[2 * 4];
  for (std::uint64_t e = 0; e < count; ++e)
  {
    Entry entry;
    entry.place = reader.number<std::int32_t>();
    entry.type = reader.number<std::int32_t>();
    entry.components = reader.number<std::int32_t>();
    entry.attribute = reader.number<std::int32_t>();
    entry.tuples = reader.number<std::int64_t>();
    entry.offset = reader.number<std::uint64_t>();
    entry.bytes = reader.number<std::uint64_t>();
    entry.named = reader.number<std::uint8_t>() != 0;
    entry.name = reader.text();
    entry.componentsNamed = reader.number<std::uint8_t>() != 0;
    const std::uint32_t names = reader.number<std::uint32_t>();
    for (std::uint32_t c = 0; c < names; ++c)
    {
      entry.componentNames.push_back(reader.text());
    }
    if (entry.place < 0 || entry.place >= PlaceCount)
    {
      TableReader::fail();
    }
    if (entry.type == VTK_STRING)
    {
      mesh->GetFieldData()->AddArray(unpackedText(entry, fd, fileSize));
      continue;
    }
    vtkSmartPointer<vtkDataArray> array = mappedArray(entry, fd, fileSize);
    if (entry.place == Points)
    {
      if (entry.components != 3)
      {
        TableReader::fail();
      }
      vtkNew<vtkPoints> points;
      points->SetData(array);
      mesh->SetPoints(points);
    }
    else if (entry.place < PointData)
    {
      cellArrays[entry.place - VertOffsets] = array;
    }
    else
    {
      vtkFieldData* data = entry.place == PointData ? static_cast<vtkFieldData*>(mesh->GetPointData())
        : entry.place == CellData                   ? static_cast<vtkFieldData*>(mesh->GetCellData())
                                                    : mesh->GetFieldData();
      const int index = data->AddArray(array);
      if (entry.attribute >= 0 && entry.attribute < vtkDataSetAttributes::NUM_ATTRIBUTES && entry.place != FieldData)
      {
        static_cast<vtkDataSetAttributes*>(data)->SetActiveAttribute(index, entry.attribute);
      }
    }
  }
  for (int kind = 0; kind < 4; ++kind)
  {
    vtkDataArray* offsets = cellArrays[2 * kind];
    vtkDataArray* ids = cellArrays[2 * kind + 1];
    if (offsets && ids && offsets->GetNumberOfTuples() > 0)
    {
      vtkNew<vtkCellArray> cells;
      if (!cells->SetData(offsets, ids))
      {
        TableReader::fail();
      }
      (kind == 0      ? mesh->SetVerts(cells)
          : kind == 1 ? mesh->SetLines(cells)
          : kind == 2 ? mesh->SetPolys(cells)
                      : mesh->SetStrips(cells));
    }
  }
  for (vtkDataSetAttributes* data : { static_cast<vtkDataSetAttributes*>(mesh->GetPointData()),
         static_cast<vtkDataSetAttributes*>(mesh->GetCellData()) })
  {
    const vtkIdType expected = data == mesh->GetPointData() ? mesh->GetNumberOfPoints() : mesh->GetNumberOfCells();
    for (int a = 0; a < data->GetNumberOfArrays(); ++a)
    {
      if (data->GetAbstractArray(a)->GetNumberOfTuples() != expected)
      {
        TableReader::fail();
      }
    }
  }
  return mesh;
}

// ---- XML, for meshes with arrays that are not plain ----

/// Calls rename(array) for every array of the mesh: point, cell and field data.
template<typename Rename>
void forEachArray(vtkDataSet* mesh, Rename rename)
{
  for (vtkFieldData* data : { static_cast<vtkFieldData*>(mesh->GetPointData()),
         static_cast<vtkFieldData*>(mesh->GetCellData()), mesh->GetFieldData() })
  {
    for (int a = 0; a < data->GetNumberOfArrays(); ++a)
    {
      rename(data->GetAbstractArray(a));
    }
  }
}

/// A name as 'x' and the hexadecimal digits of its bytes, which any XML attribute holds.
std::string encodedName(const char* name)
{
  static const char digits[] = "0123456789abcdef";
  std::string text = "x";
  for (const char* c = name; *c; ++c)
  {
    const unsigned char byte = static_cast<unsigned char>(*c);
    text += { digits[byte >> 4], digits[byte & 15] };
  }
  return text;
}

std::string decodedName(const char* text)
{
  std::string name;
  auto value = [](char digit) { return digit <= '9' ? digit - '0' : digit - 'a' + 10; };
  for (const char* c = text + 1; c[0] && c[1]; c += 2)
  {
    name += static_cast<char>(value(c[0]) * 16 + value(c[1]));
  }
  return name;
}

/// Renames the array and its components with code(name); unnamed ones stay unnamed.
template<typename Code>
void recodeNames(vtkAbstractArray* array, Code code)
{
  if (array->GetName())
  {
    array->SetName(code(array->GetName()).c_str());
  }
  for (int c = 0; c < array->GetNumberOfComponents(); ++c)
  {
    if (array->HasAComponentName() && array->GetComponentName(c))
    {
      array->SetComponentName(c, code(array->GetComponentName(c)).c_str());
    }
  }
}

/// Writes the dataset as VTK XML with raw appended data (the fastest of VTK's writers and
/// readers on large meshes: a third of the time of legacy binary, which swaps every byte) into
/// path. VTK 9.1 writes names into XML attributes unescaped, so every name is written
/// hex-encoded and decoded on the other side; array information keys, which the other side
/// may not know, are dropped.
void handOverXml(vtkDataSet* mesh, const std::string& path)
{
  forEachArray(mesh,
    [](vtkAbstractArray* array)
    {
      recodeNames(array, encodedName);
      if (array->HasInformation())
      {
        array->GetInformation()->Clear();
      }
    });
  vtkNew<vtkXMLDataSetWriter> writer; // the writer of the dataset's type
  writer->SetInputData(mesh);
  writer->SetFileName(path.c_str());
  writer->SetDataModeToAppended();
  writer->EncodeAppendedDataOff();
  writer->SetCompressorTypeToNone();
  writer->SetHeaderTypeToUInt64(); // arrays of more than 4 GB
  writer->Update();                // writes
  if (writer->GetErrorCode() != vtkErrorCode::NoError)
  {
    throw std::runtime_error("the mesh could not be handed over (out of memory?)");
  }
}

/// The dataset handOverXml wrote. Throws std::runtime_error if it cannot be read back.
vtkSmartPointer<vtkDataSet> takeOverXml(const std::string& path)
{
  vtkNew<vtkXMLGenericDataObjectReader> reader;
  vtkNew<VtkErrorCapture> errors;
  errors->watch(reader);
  reader->SetFileName(path.c_str());
  reader->Update();
  vtkDataSet* read = vtkDataSet::SafeDownCast(reader->GetOutputDataObject(0));
  if (errors->failed() || reader->GetErrorCode() != vtkErrorCode::NoError || !read)
  {
    throw std::runtime_error(errors->failed() ? errors->message() : "it holds no dataset");
  }
  vtkSmartPointer<vtkDataSet> mesh;
  mesh.TakeReference(read->NewInstance());
  mesh->ShallowCopy(read);
  forEachArray(mesh, [](vtkAbstractArray* array) { recodeNames(array, decodedName); });
  return mesh;
}
}

void handOverDataSet(vtkDataSet* data, const std::string& path)
{
  if (auto* mesh = vtkPolyData::SafeDownCast(data))
  {
    handOverMesh(mesh, path);
    return;
  }
  handOverXml(data, path);
}

void handOverMesh(vtkPolyData* mesh, const std::string& path)
{
  std::vector<Entry> entries = entriesOf(mesh);
  if (entries.empty())
  {
    handOverXml(mesh, path);
    return;
  }
  handOverRaw(entries, path);
}

vtkSmartPointer<vtkPolyData> takeOverMesh(const std::string& path)
{
  vtkSmartPointer<vtkDataSet> data = takeOverDataSet(path);
  auto* mesh = vtkPolyData::SafeDownCast(data);
  if (!mesh)
  {
    throw std::runtime_error("it holds a dataset that is not polydata");
  }
  return mesh;
}

vtkSmartPointer<vtkDataSet> takeOverDataSet(const std::string& path)
{
  const int fd = ::open(path.c_str(), O_RDONLY);
  struct stat status;
  if (fd < 0 || ::fstat(fd, &status) != 0)
  {
    throw std::runtime_error("its result file does not open");
  }
  const std::uint64_t fileSize = static_cast<std::uint64_t>(status.st_size);
  // The table: its magic and length first, then the whole of it.
  std::string table(sizeof rawMagic + sizeof(std::uint64_t), '\0');
  const bool raw = ::pread(fd, table.data(), table.size(), 0) == static_cast<ssize_t>(table.size()) &&
    std::memcmp(table.data(), rawMagic, sizeof rawMagic) == 0;
  try
  {
    if (!raw)
    {
      ::close(fd);
      return takeOverXml(path);
    }
    std::uint64_t length = 0;
    std::memcpy(&length, table.data() + sizeof rawMagic, sizeof length);
    if (length > (std::uint64_t(64) << 20) || length > fileSize)
    {
      TableReader::fail();
    }
    std::string content(static_cast<std::size_t>(length), '\0');
    if (::pread(fd, content.data(), content.size(), static_cast<off_t>(table.size())) !=
      static_cast<ssize_t>(content.size()))
    {
      TableReader::fail();
    }
    vtkSmartPointer<vtkDataSet> mesh = takeOverRaw(content, fd, fileSize);
    ::close(fd);
    return mesh;
  }
  catch (...)
  {
    if (raw)
    {
      ::close(fd);
    }
    throw;
  }
}
}
