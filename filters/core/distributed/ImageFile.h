#pragma once
// An image file read through OpenImageIO, which ShadeLab loads only when it reads an image: with
// the 230 libraries it brings (GDAL, FFmpeg, OpenVDB, DCMTK, ...), linking it would add most of a
// second and 130 MB to the start of every command, and four logging threads to every process.
// It lives in a module of its own, libshadelab_images.so (OpenImageIOFile.cpp), found the first
// time an image is opened: at SHADELAB_IMAGE_MODULE if it is set; else beside the program (or
// plugin, or Python extension), then in lib/shadelab/ under each folder above it (an install's
// prefix, wherever it was moved), then where ShadeLab installs it, then in its build tree.
#include <memory>
#include <string>

namespace shadelab
{
class ImageFile
{
public:
  /// The image at path, its header read. Throws std::runtime_error "<path>: cannot read as an
  /// image: <why>", or one that says which module could not be loaded and where it was sought.
  static std::unique_ptr<ImageFile> open(const std::string& path);

  virtual ~ImageFile() = default;
  virtual int width() const = 0;
  virtual int height() const = 0;
  virtual int channels() const = 0;
  /// Reads the first `channels` channels of every pixel as floats, row by row from the top, into
  /// pixels (width x height x channels of them). Throws std::runtime_error as open() does.
  virtual void read(int channels, float* pixels) = 0;
};

/// The module's one entry point (SHADELAB_IMAGE_ENTRY, a name that holds ShadeLab's version):
/// the image at path, or null with error set to why it cannot be read.
using OpenImageFunction = ImageFile* (*)(const std::string& path, std::string& error);
}
