#include "MeshFileChecks.h"

#include <vtksys/SystemTools.hxx>

#include <fcntl.h>
#include <sys/mman.h>
#include <unistd.h>

namespace shadelab::app
{
namespace
{
/// A file's bytes, mapped into memory read-only while it lives (no copy of a large mesh).
class MappedFile
{
public:
  MappedFile(const std::string& fileName, std::uintmax_t size)
  {
    const int descriptor = ::open(fileName.c_str(), O_RDONLY);
    if (descriptor < 0 || size == 0)
    {
      if (descriptor >= 0)
      {
        ::close(descriptor);
      }
      return;
    }
    void* address = ::mmap(nullptr, size, PROT_READ, MAP_PRIVATE, descriptor, 0);
    ::close(descriptor);
    if (address != MAP_FAILED)
    {
      address_ = address, size_ = size;
    }
  }
  ~MappedFile()
  {
    if (address_)
    {
      ::munmap(address_, size_);
    }
  }
  MappedFile(const MappedFile&) = delete;
  MappedFile& operator=(const MappedFile&) = delete;

  bool mapped() const { return address_ != nullptr; }
  std::string_view bytes() const { return { static_cast<const char*>(address_), size_ }; }

private:
  void* address_ = nullptr;
  std::size_t size_ = 0;
};
}

MeshFileCheck checkMeshFile(const std::string& fileName, const std::string& extension, std::uintmax_t fileSize)
{
  if (extension != ".obj" && extension != ".ply" && extension != ".stl")
  {
    return {};
  }
  const MappedFile file(fileName, fileSize);
  if (!file.mapped() && fileSize > 0)
  {
    return {}; // not to be mapped: the reader says what it makes of it
  }
  if (extension == ".obj")
  {
    return objFileCheck(file.bytes());
  }
  if (extension == ".ply")
  {
    return { plyFileProblem(file.bytes()), "" };
  }
  // vtkSTLReader reads a file as ASCII when vtksys takes its first 256 bytes for text.
  const bool ascii = vtksys::SystemTools::DetectFileType(fileName.c_str()) == vtksys::SystemTools::FileTypeText;
  return stlFileCheck(file.bytes(), ascii);
}
}
