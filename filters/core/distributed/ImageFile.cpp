#include "ImageFile.h"

#include <dlfcn.h>

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

/// Where the module may be, in the order it is sought: where SHADELAB_IMAGE_MODULE says only,
/// if it is set.
std::vector<fs::path> moduleCandidates()
{
  if (const char* given = std::getenv("SHADELAB_IMAGE_MODULE"))
  {
    return { fs::path(given) };
  }
  // The object this code was linked into (a plugin's or a Python extension's path; for a program
  // dladdr may give only the name it was run by) and the running program, with the folders above
  // them: an install moved to another prefix keeps the module at the same place relative to them.
  std::vector<fs::path> origins;
  std::error_code error;
  const fs::path program = fs::read_symlink("/proc/self/exe", error);
  if (!error)
  {
    origins.push_back(program);
  }
  Dl_info self{};
  if (::dladdr(reinterpret_cast<void*>(&moduleCandidates), &self) && self.dli_fname && std::strchr(self.dli_fname, '/'))
  {
    origins.push_back(fs::absolute(self.dli_fname, error));
  }
  std::vector<fs::path> candidates;
  for (const fs::path& origin : origins)
  {
    candidates.push_back(origin.parent_path() / moduleName);
    for (fs::path folder = origin.parent_path(); folder != folder.root_path(); folder = folder.parent_path())
    {
      candidates.push_back(folder / SHADELAB_IMAGE_MODULE_UNDER_PREFIX);
    }
  }
  candidates.emplace_back(SHADELAB_IMAGE_MODULE_INSTALLED);
  candidates.emplace_back(SHADELAB_IMAGE_MODULE_BUILT);
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

/// The module's entry point, loaded once. Throws std::runtime_error with where it was sought.
OpenImageFunction openImageFunction()
{
  static std::once_flag loaded;
  static OpenImageFunction function = nullptr;
  static std::string failure;
  std::call_once(loaded,
    []
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
          failure = "ShadeLab's image module " + candidate.string() + " does not load (" + ::dlerror() +
            "): is it ShadeLab's " + moduleName + ", and is OpenImageIO installed (Debian 12: libopenimageio2.4)?";
          return;
        }
        function = reinterpret_cast<OpenImageFunction>(::dlsym(module, openImageSymbol));
        if (!function)
        {
          failure = "ShadeLab's image module " + candidate.string() + " has no " + openImageSymbol +
            ": it is from another version of ShadeLab; reinstall it";
        }
        return;
      }
      failure = notFoundMessage(std::getenv("SHADELAB_IMAGE_MODULE"), sought);
    });
  if (!function)
  {
    throw std::runtime_error(failure);
  }
  return function;
}
}

std::unique_ptr<ImageFile> ImageFile::open(const std::string& path)
{
  std::string error;
  std::unique_ptr<ImageFile> image(openImageFunction()(path, error));
  if (!image)
  {
    throw std::runtime_error(path + ": cannot read as an image: " + error);
  }
  return image;
}
}
