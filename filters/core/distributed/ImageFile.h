#pragma once
// An image file read through OpenImageIO, which ShadeLab loads only when it reads an image: with
// the 230 libraries it brings (GDAL, FFmpeg, OpenVDB, DCMTK, ...), linking it would add most of a
// second and 130 MB to the start of every command, and four logging threads to every process.
// It lives in a module of its own, libshadelab_images.so (OpenImageIOFile.cpp), found the first
// time an image is opened: at SHADELAB_IMAGE_MODULE if it is set; else beside the program (or
// plugin, or Python extension), then in lib/shadelab/ under each folder above it (an install's
// prefix, wherever it was moved), then where ShadeLab installs it, then in its build tree.
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>

namespace shadelab
{
class ImageFile
{
public:
  /// The image at path, its header read. Throws std::runtime_error "<path>: cannot read as an
  /// image: <why>", "<path>: no such file", "<path>: is a folder, not an image file", one for a
  /// device or a pipe (refused before OpenImageIO tries its formats on them), or one that says
  /// which module could not be loaded and where it was sought.
  static std::unique_ptr<ImageFile> open(const std::string& path);

  virtual ~ImageFile() = default;
  virtual int width() const = 0;
  virtual int height() const = 0;
  virtual int channels() const = 0;
  /// Whether the file holds floating-point values (linear light, as OpenEXR and Radiance .hdr
  /// do), rather than integers (a display encoding, such as sRGB).
  virtual bool floatingPoint() const = 0;
  /// Reads the first `channels` channels of every pixel as floats, row by row from the top, into
  /// pixels (width x height x channels of them). Throws std::runtime_error as open() does.
  virtual void read(int channels, float* pixels) = 0;
};

/// The most texels a file of `fileBytes` bytes can hold, as far as ShadeLab believes a header: a
/// header can declare any size, but the pixels must be in the file. Compressed formats hold far
/// more texels than bytes only for flat images, so the bound is generous (64 a byte), and it
/// stops a 1 kB file from asking for gigabytes before a single pixel is read.
inline std::size_t mostTexelsIn(std::uintmax_t fileBytes)
{
  return std::max<std::size_t>(4096, 64 * static_cast<std::size_t>(fileBytes));
}

/// The module's one entry point (SHADELAB_IMAGE_ENTRY, a name that holds ShadeLab's version):
/// the image at path, or null with error set to why it cannot be read.
using OpenImageFunction = ImageFile* (*)(const std::string& path, std::string& error);
}
