// libshadelab_images.so: ImageFile through OpenImageIO, loaded by ImageFile::open at the first
// image read (ImageFile.h says why it is a module of its own).
#include "ImageFile.h"

#include <OpenImageIO/imageio.h>

namespace shadelab
{
namespace
{
class OpenImageIOFile : public ImageFile
{
public:
  OpenImageIOFile(std::unique_ptr<OIIO::ImageInput> input, std::string path)
    : input_(std::move(input))
    , path_(std::move(path))
  {
  }
  int width() const override { return input_->spec().width; }
  int height() const override { return input_->spec().height; }
  int channels() const override { return input_->spec().nchannels; }
  bool floatingPoint() const override { return input_->spec().format.is_floating_point(); }
  void read(int channels, float* pixels) override
  {
    if (!input_->read_image(0, 0, 0, channels, OIIO::TypeDesc::FLOAT, pixels))
    {
      throw std::runtime_error(path_ + ": cannot read as an image: " + input_->geterror());
    }
  }

private:
  std::unique_ptr<OIIO::ImageInput> input_;
  std::string path_;
};
}
}

extern "C" __attribute__((visibility("default"))) shadelab::ImageFile* SHADELAB_IMAGE_ENTRY(
  const std::string& path, std::string& error)
{
  // No thread pools, OpenImageIO's nor OpenEXR's: the command reads a mesh (and its textures)
  // in a forked child, which has none of the parent's threads, so a pool a map's read had
  // started in the parent left the child's read of an EXR texture waiting for ever. ShadeLab
  // reads each image once; one thread is enough.
  static const bool singleThreaded = OIIO::attribute("threads", 1) && OIIO::attribute("exr_threads", -1);
  (void)singleThreaded;
  // Clears any error an earlier failure left, so that the message is this file's.
  OIIO::geterror();
  // Colours as the file holds them, not multiplied by an alpha channel ShadeLab does not read
  // (OpenImageIO premultiplies a PNG's, a TGA's or a TIFF's by default).
  OIIO::ImageSpec config;
  config.attribute("oiio:UnassociatedAlpha", 1);
  auto input = OIIO::ImageInput::open(path, &config);
  if (!input)
  {
    error = OIIO::geterror();
    return nullptr;
  }
  return new shadelab::OpenImageIOFile(std::move(input), path);
}
