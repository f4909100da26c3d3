#include "ImageFile.h"

#include <dlfcn.h>

#include <algorithm>
#include <cstring>
#include <filesystem>
#include <mutex>
#include <stdexcept>
#include <vector>

namespace shadelab
{
namespace
{
namespace fs = std::filesystem;

constexpr const char* moduleName = "libshadelab_images.so";

#define SHADELAB_TEXT(name) #name
#define SHADELAB_NAME_TEXT(name) SHADELAB_TEXT(name)
/// The module's entry point, named for ShadeLab's version: a module of another version is not
/// taken for this one's.
constexpr const char* entryPoint = SHADELAB_NAME_TEXT(SHADELAB_IMAGE_ENTRY);

/// SHADELAB_IMAGE_MODULE, or null where it is unset or empty.
const char* givenModule()
{
  const char* given = std::getenv("SHADELAB_IMAGE_MODULE");
  return given && *given ? given : nullptr;
}

/// Where the module may be, in the order it is sought: where SHADELAB_IMAGE_MODULE says only,
/// if it is set.
std::vector<fs::path> moduleCandidates()
{
  std::error_code error;
  if (const char* given = givenModule())
  {
    return { fs::absolute(given, error) }; // dlopen would search the library path for a bare name
  }
  // The object this code was linked into (a plugin or a Python extension; for a program dladdr
  // may give only the name it was run by), then the running program, and the folders up to five
  // above each (a Python package's or a plugin's prefix): an install moved to another prefix
  // keeps the module at the same place relative to them.
  std::vector<fs::path> origins;
  Dl_info self{};
  if (::dladdr(reinterpret_cast<void*>(&moduleCandidates), &self) && self.dli_fname && std::strchr(self.dli_fname, '/'))
  {
    origins.push_back(fs::absolute(self.dli_fname, error));
  }
  const fs::path program = fs::read_symlink("/proc/self/exe", error);
  if (!error)
  {
    origins.push_back(program);
  }
  std::vector<fs::path> candidates;
  auto add = [&](const fs::path& candidate)
  {
    if (std::find(candidates.begin(), candidates.end(), candidate) == candidates.end())
    {
      candidates.push_back(candidate);
    }
  };
  for (const fs::path& origin : origins)
  {
    add(origin.parent_path() / moduleName);
    fs::path folder = origin.parent_path();
    for (int level = 0; level <= 5 && folder != folder.root_path(); ++level, folder = folder.parent_path())
    {
      add(folder / SHADELAB_IMAGE_MODULE_UNDER_PREFIX);
    }
  }
  add(SHADELAB_IMAGE_MODULE_INSTALLED);
  add(SHADELAB_IMAGE_MODULE_BUILT);
  return candidates;
}

/// Why the module was not found: given is SHADELAB_IMAGE_MODULE (null if unset), sought the
/// paths tried.
std::string notFoundMessage(const char* given, const std::string& sought)
{
  if (given)
  {
    return std::string("SHADELAB_IMAGE_MODULE names ") + given +
      ", which does not exist: give the path of ShadeLab's " + moduleName + ", or unset it";
  }
  return std::string("ShadeLab's image module ") + moduleName + " is not installed (sought at " + sought +
    "): reinstall ShadeLab, or set SHADELAB_IMAGE_MODULE to the module's path";
}

/// The module's entry point, from the first candidate that exists. Throws std::runtime_error
/// with where it was sought, or why what was found does not load.
OpenImageFunction loadedEntryPoint()
{
  std::string sought;
  for (const fs::path& candidate : moduleCandidates())
  {
    std::error_code error;
    if (!fs::exists(candidate, error))
    {
      sought += (sought.empty() ? "" : ", ") + candidate.string();
      continue;
    }
    void* module = ::dlopen(candidate.c_str(), RTLD_NOW | RTLD_LOCAL);
    if (!module)
    {
      throw std::runtime_error("ShadeLab's image module " + candidate.string() + " does not load (" + ::dlerror() +
        "): is it ShadeLab's " + moduleName + ", and is OpenImageIO installed (Debian 12: libopenimageio2.4)?");
    }
    if (auto function = reinterpret_cast<OpenImageFunction>(::dlsym(module, entryPoint)))
    {
      return function;
    }
    ::dlclose(module);
    throw std::runtime_error(candidate.string() + " has no " + entryPoint +
      ": it is not the image module of this version of ShadeLab; reinstall ShadeLab");
  }
  throw std::runtime_error(notFoundMessage(givenModule(), sought));
}

/// The module's entry point, loaded at the first image. A failure is not kept: a long-lived
/// process (ParaView, Python) finds the module once it is installed or named.
OpenImageFunction openImageFunction()
{
  static std::mutex loading;
  static OpenImageFunction function = nullptr;
  const std::lock_guard<std::mutex> lock(loading);
  if (!function)
  {
    function = loadedEntryPoint();
  }
  return function;
}
}

std::unique_ptr<ImageFile> ImageFile::open(const std::string& path)
{
  std::error_code ignored;
  if (!fs::exists(path, ignored))
  {
    throw std::runtime_error(path + ": no such file");
  }
  // Before OpenImageIO, which tries every format on what its own does not read: libheif took a
  // folder for a 512 MB file, and a device never ends.
  if (fs::is_directory(path, ignored))
  {
    throw std::runtime_error(path + ": is a folder, not an image file");
  }
  if (!fs::is_regular_file(path, ignored))
  {
    throw std::runtime_error(path + ": not a regular file (a pipe or a device?): give an image file");
  }
  std::string error;
  std::unique_ptr<ImageFile> image(openImageFunction()(path, error));
  if (!image)
  {
    throw std::runtime_error(path + ": cannot read as an image: " + error);
  }
  return image;
}
}
