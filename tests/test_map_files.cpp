// Reading environment map files that the tests write with OpenImageIO: Radiance HDR and
// half-float OpenEXR round trips, one and four channels, and each kind of broken file refused
// with its message; and an OBJ's texture that VTK's readers do not take. Kept apart from test_environment_map.cpp,
// whose tests need no image written, so that only this binary links OpenImageIO (tests/CMakeLists.txt says why).
#include "EnvironmentMap.h"
#include "MeshFiles.h"
#include "ShadeLabImportedParts.h"
#include "TestFolder.h"
#include "TestPaths.h"
#include "TwoPartObj.h"
#include "VtkErrorCapture.h"

#include "vtkDataArray.h"
#include "vtkNew.h"
#include "vtkOutputWindow.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"

#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <limits>
#include <random>
#include <stdexcept>
#include <string>
#include <tuple>
#include <vector>

namespace
{
using namespace shadelab;
const std::string venicePath = shadelab::testing::sourcePath("data/envmaps/venice_sunset_1k");

std::string tempPath(const std::string& name)
{
  return ::testing::TempDir() + "shadelab_envmap_" + name;
}

void writeImage(const std::string& path, int width, int height, int channels, const std::vector<float>& pixels,
  OIIO::TypeDesc storedAs)
{
  const auto output = OIIO::ImageOutput::create(path);
  ASSERT_TRUE(output) << OIIO::geterror();
  const OIIO::ImageSpec spec(width, height, channels, storedAs);
  ASSERT_TRUE(output->open(path, spec)) << output->geterror();
  ASSERT_TRUE(output->write_image(OIIO::TypeDesc::FLOAT, pixels.data())) << output->geterror();
  ASSERT_TRUE(output->close());
}

std::vector<float> randomPixels(std::size_t count, unsigned seed)
{
  // Log-uniform over five decades, as in real HDR maps.
  std::mt19937_64 random(seed);
  std::uniform_real_distribution<float> exponent(-2.0f, 3.0f);
  std::vector<float> pixels(count);
  for (float& p : pixels)
  {
    p = std::pow(10.0f, exponent(random));
  }
  return pixels;
}

std::string readError(const std::string& path)
{
  try
  {
    readEnvironmentMap(path);
  }
  catch (const std::runtime_error& error)
  {
    return error.what();
  }
  ADD_FAILURE() << path << " was read without an error";
  return "";
}

TEST(ReadEnvironmentMap, RadianceHdrRoundTrip)
{
  const std::string path = tempPath("round_trip.hdr");
  const std::vector<float> pixels = randomPixels(16 * 8 * 3, 3);
  writeImage(path, 16, 8, 3, pixels, OIIO::TypeDesc::FLOAT);
  const EnvironmentMap map = readEnvironmentMap(path);
  ASSERT_EQ(map.width, 16);
  ASSERT_EQ(map.height, 8);
  for (std::size_t i = 0; i < map.radiance.size(); ++i)
  {
    // RGBE keeps 8 bits of mantissa under the largest channel's exponent: every channel is
    // within 1/128 of the texel's largest channel.
    const Rgb written(pixels[3 * i], pixels[3 * i + 1], pixels[3 * i + 2]);
    EXPECT_LE(largestComponent(map.radiance[i] - written), 0.01 * largestComponent(written)) << i;
  }
}

TEST(ReadEnvironmentMap, HalfExrRoundTrip)
{
  const std::string path = tempPath("round_trip.exr");
  const std::vector<float> pixels = randomPixels(16 * 8 * 3, 4);
  writeImage(path, 16, 8, 3, pixels, OIIO::TypeDesc::HALF);
  const EnvironmentMap map = readEnvironmentMap(path);
  ASSERT_EQ(map.width, 16);
  ASSERT_EQ(map.height, 8);
  for (std::size_t i = 0; i < map.radiance.size(); ++i)
  {
    for (int c = 0; c < 3; ++c)
    {
      // A half has 11 significant bits: relative rounding below 2^-11 = 4.9e-4.
      EXPECT_NEAR(map.radiance[i][c], pixels[3 * i + c], 1e-3 * pixels[3 * i + c]) << i;
    }
  }
}

TEST(ReadEnvironmentMap, OneChannelIsGreyAndAlphaIsIgnored)
{
  const std::string greyPath = tempPath("grey.exr");
  const std::vector<float> grey = randomPixels(8 * 4, 5);
  writeImage(greyPath, 8, 4, 1, grey, OIIO::TypeDesc::FLOAT);
  const EnvironmentMap greyMap = readEnvironmentMap(greyPath);
  for (std::size_t i = 0; i < grey.size(); ++i)
  {
    EXPECT_EQ(greyMap.radiance[i], Rgb(grey[i]));
  }

  const std::string rgbaPath = tempPath("rgba.exr");
  std::vector<float> rgba = randomPixels(8 * 4 * 4, 6);
  writeImage(rgbaPath, 8, 4, 4, rgba, OIIO::TypeDesc::FLOAT);
  const EnvironmentMap rgbaMap = readEnvironmentMap(rgbaPath);
  for (std::size_t i = 0; i < rgbaMap.radiance.size(); ++i)
  {
    EXPECT_EQ(rgbaMap.radiance[i], Rgb(rgba[4 * i], rgba[4 * i + 1], rgba[4 * i + 2]));
  }
}

TEST(ReadEnvironmentMap, MissingFile)
{
  const std::string path = tempPath("missing.hdr");
  EXPECT_EQ(readError(path), path + ": no such file");
}

// Refused before OpenImageIO tries its formats on them (libheif read a folder as a 512 MB file).
TEST(ReadEnvironmentMap, AFolderOrADeviceIsNotAnImage)
{
  const std::string folder = tempPath("maps");
  std::filesystem::create_directories(folder);
  EXPECT_EQ(readError(folder), folder + ": is a folder, not an image file");
  EXPECT_EQ(readError("/dev/zero"), "/dev/zero: not a regular file (a pipe or a device?): give an image file");
}

TEST(ReadEnvironmentMap, NotAnImage)
{
  const std::string path = tempPath("text.hdr");
  std::ofstream(path) << "this is text, not a Radiance picture\n";
  // The reason after the colon is OpenImageIO's own, as it gives it.
  ASSERT_FALSE(OIIO::ImageInput::open(path));
  const std::string oiioError = OIIO::geterror();
  EXPECT_FALSE(oiioError.empty());
  EXPECT_EQ(readError(path), path + ": cannot read as an image: " + oiioError);
}

TEST(ReadEnvironmentMap, HeaderDeclaresMoreThanTheFileCanHold)
{
  // The sunset's header (1024 x 512) on its first 2000 bytes: 64 texels a byte at most is
  // 128,000, so it is refused before anything is allocated or decoded.
  std::ifstream whole(venicePath + ".hdr", std::ios::binary);
  std::vector<char> start(2000);
  whole.read(start.data(), static_cast<std::streamsize>(start.size()));
  const std::string path = tempPath("cut_short.hdr");
  std::ofstream(path, std::ios::binary).write(start.data(), whole.gcount());
  EXPECT_EQ(readError(path),
    path +
      ": the header declares 1024x512 texels (0.00629146 GB as floats), more than a "
      "file of 2000 bytes can hold: it is damaged, or too large a map");
}

TEST(ReadEnvironmentMap, TruncatedFile)
{
  // A real header with 20000 bytes of pixels: OpenImageIO opens it and fails while decoding.
  std::ifstream whole(venicePath + ".hdr", std::ios::binary);
  std::vector<char> start(20000);
  whole.read(start.data(), static_cast<std::streamsize>(start.size()));
  const std::string path = tempPath("truncated.hdr");
  std::ofstream(path, std::ios::binary).write(start.data(), whole.gcount());
  const std::string prefix = path + ": cannot read as an image: ";
  const std::string message = readError(path);
  EXPECT_EQ(message.substr(0, prefix.size()), prefix);
  EXPECT_GT(message.size(), prefix.size()) << "no reason given";
}

TEST(ReadEnvironmentMap, EmptyImage)
{
  const std::string path = tempPath("empty.ppm");
  std::ofstream(path) << "P6\n0 0\n255\n";
  EXPECT_EQ(readError(path), path + ": the image is empty (0x0)");
}

TEST(ReadEnvironmentMap, TwoChannels)
{
  const std::string path = tempPath("two_channels.exr");
  writeImage(path, 8, 4, 2, std::vector<float>(8 * 4 * 2, 1.0f), OIIO::TypeDesc::HALF);
  EXPECT_EQ(readError(path), path + ": has 2 channels; expected 1 (grey) or 3 or more (RGB)");
}

TEST(ReadEnvironmentMap, NotTwiceAsWideAsHigh)
{
  const std::string path = tempPath("square.exr");
  writeImage(path, 6, 4, 3, std::vector<float>(6 * 4 * 3, 1.0f), OIIO::TypeDesc::HALF);
  EXPECT_EQ(readError(path), path + ": an equirectangular map must be twice as wide as it is high; this one is 6x4");
}

TEST(ReadEnvironmentMap, NegativeOrNonFiniteTexel)
{
  const std::string path = tempPath("bad_texel.exr");
  std::vector<float> pixels(8 * 4 * 3, 1.0f);
  pixels[3 * (2 * 8 + 5) + 1] = -1.5f; // column 5, row 2, green
  writeImage(path, 8, 4, 3, pixels, OIIO::TypeDesc::FLOAT);
  EXPECT_EQ(readError(path), path + ": texel (column 5, row 2) is not a finite non-negative radiance (1, -1.5, 1)");

  // The first bad texel in row-major order is the one named.
  pixels[3 * (1 * 8 + 3) + 2] = std::numeric_limits<float>::quiet_NaN(); // column 3, row 1
  pixels[3 * (3 * 8 + 0) + 0] = std::numeric_limits<float>::infinity();
  writeImage(path, 8, 4, 3, pixels, OIIO::TypeDesc::FLOAT);
  EXPECT_EQ(readError(path), path + ": texel (column 3, row 1) is not a finite non-negative radiance (1, 1, nan)");
}
}

namespace
{
/// A folder of the test's own, where the two-part OBJ is read with a texture of its own.
struct TextureFiles : shadelab::testing::TestFolder
{
  /// The two-part OBJ read with its MTL's map_Kd naming `texture` (in the folder); what the
  /// reading said goes to `said`.
  vtkSmartPointer<vtkPolyData> readParts(const std::string& texture, std::vector<std::string>& said)
  {
    std::string mtl = shadelab::testing::partsMtl;
    mtl.replace(mtl.find("texture.png"), 11, texture);
    file("parts.mtl", mtl);
    vtkNew<app::QuietOutputWindow> warnings;
    vtkOutputWindow::SetInstance(warnings);
    vtkSmartPointer<vtkPolyData> mesh = app::readMesh(file("parts.obj", shadelab::testing::twoPartObj));
    vtkOutputWindow::SetInstance(nullptr);
    said = warnings->takeWarnings();
    return mesh;
  }
};

/// A Radiance .hdr file of 4 x 2 texels, written byte by byte: each texel's R, G and B bytes
/// (rows from the top) with the exponent 129, so that each value is its byte / 128 exactly;
/// rows shorter than 8 texels are never run-length encoded. Written without OpenImageIO: an
/// OpenEXR file written through it would start OpenEXR's thread pool in this process, whose
/// threads the mesh reader's forked child would not have. (ShadeLab's own reads start no pool,
/// for that reason: Cli.AnEnvironmentMapInOpenExrBeforeAnExrTexture.)
void writeRadiance(const std::string& path, const std::vector<unsigned char>& bytes)
{
  std::ofstream out(path, std::ios::binary);
  out << "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 2 +X 4\n";
  for (std::size_t texel = 0; texel < 8; ++texel)
  {
    out << bytes[3 * texel] << bytes[3 * texel + 1] << bytes[3 * texel + 2] << static_cast<unsigned char>(129);
  }
}

/// Every vertex's Kd is its part's MTL Kd alone (green 0.8 in part 1, 0.2 in the other): the
/// texture was not applied.
void expectUntexturedKd(vtkPolyData* mesh)
{
  vtkDataArray* kd = mesh->GetPointData()->GetArray(materialKdArrayName);
  vtkDataArray* part = mesh->GetPointData()->GetArray(partArrayName);
  for (vtkIdType p = 0; p < mesh->GetNumberOfPoints(); ++p)
  {
    EXPECT_EQ(kd->GetComponent(p, 1), double(part->GetComponent(p, 0) == 1 ? 0.8f : 0.2f));
  }
}

/// The textured part's kd at each of its vertices, each at a texel's centre, against the MTL's
/// Kd times expected(column, row, channel), rows from the bottom; returns the vertices seen.
int expectTexturedKd(vtkPolyData* mesh, const std::function<double(int, int, int)>& expected)
{
  vtkDataArray* kd = mesh->GetPointData()->GetArray(materialKdArrayName);
  vtkDataArray* part = mesh->GetPointData()->GetArray(partArrayName);
  vtkDataArray* uv = mesh->GetPointData()->GetTCoords();
  if (!kd || !part || !uv)
  {
    ADD_FAILURE() << "the mesh has no material arrays or texture coordinates";
    return 0;
  }
  const float partKd[3] = { 0.9f, 0.8f, 0.6f };
  int texelsSeen = 0;
  for (vtkIdType p = 0; p < mesh->GetNumberOfPoints(); ++p)
  {
    if (part->GetComponent(p, 0) == 1)
    {
      const int column = int(std::floor(uv->GetComponent(p, 0) * 4)), row = int(std::floor(uv->GetComponent(p, 1) * 2));
      for (int c = 0; c < 3; ++c)
      {
        EXPECT_NEAR(kd->GetComponent(p, c), partKd[c] * expected(column, row, c), 1e-6)
          << "texel " << column << ", " << row;
      }
      ++texelsSeen;
    }
  }
  return texelsSeen;
}

/// IEC 61966-2-1's decoding of an 8-bit value, written out here.
double srgbDecoded(unsigned char byte)
{
  const double c = byte / 255.0;
  return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4);
}

// A texture that VTK's readers do not take, a Radiance .hdr file, read through OpenImageIO:
// each vertex of the two-part OBJ's textured part sits at a texel's centre, so its kd is the
// MTL's Kd times that texel, taken as linear (floating point) and clamped into [0, 1]; the
// file's rows run from the top, the texture's v from the bottom. Its texel above 1 is said.
TEST_F(TextureFiles, AnHdrTextureIsReadThroughOpenImageIOItsTexelsAbove1Clamped)
{
  const std::vector<unsigned char> bytes = { 64, 32, 96, 16, 128, 0, 255, 64, 64, 48, 80, 112, 8, 64, 128, 32, 32, 32,
    96, 64, 32, 128, 128, 128 };
  writeRadiance((folder / "texture.hdr").string(), bytes);
  std::vector<std::string> said;
  vtkSmartPointer<vtkPolyData> mesh = readParts("texture.hdr", said);
  EXPECT_EQ(said,
    std::vector<std::string>{ "part 'tex': its texture has 1 texel value outside [0, 1] (as high as 1.992): "
                              "clamped into it, since the texture multiplies kd, a reflectance" });
  const int texelsSeen = expectTexturedKd(mesh,
    [&](int column, int row, int c)
    { return std::min(1.0, bytes[std::size_t(3 * ((1 - row) * 4 + column) + c)] / 128.0); });
  EXPECT_EQ(texelsSeen, 18);
}

/// A 4 x 2 TGA file of 8-bit BGRA texels, written byte by byte (uncompressed, the bottom row
/// first, as TGA's default origin has it); `rgba` holds each texel's R, G, B and A, rows from
/// the bottom.
void writeTga(const std::string& path, const std::vector<unsigned char>& rgba)
{
  std::ofstream out(path, std::ios::binary);
  const unsigned char header[18] = { 0, 0, 2, 0, 0, 0, 0, 0, 0, 0, 0, 0, 4, 0, 2, 0, 32, 8 };
  out.write(reinterpret_cast<const char*>(header), sizeof(header));
  for (std::size_t texel = 0; texel < 8; ++texel)
  {
    out << rgba[4 * texel + 2] << rgba[4 * texel + 1] << rgba[4 * texel] << rgba[4 * texel + 3];
  }
}

/// The same with one 8-bit grey channel (TGA's image type 3).
void writeGreyTga(const std::string& path, const std::vector<unsigned char>& grey)
{
  std::ofstream out(path, std::ios::binary);
  const unsigned char header[18] = { 0, 0, 3, 0, 0, 0, 0, 0, 0, 0, 0, 0, 4, 0, 2, 0, 8, 0 };
  out.write(reinterpret_cast<const char*>(header), sizeof(header));
  out.write(reinterpret_cast<const char*>(grey.data()), std::streamsize(grey.size()));
}

// An 8-bit texture that VTK's importer does not read, a TGA file, through OpenImageIO: its
// values are sRGB-decoded, as VTK's PNG texels are, and its alpha channel, half transparent on
// some texels, leaves the colours as they are (OpenImageIO would premultiply them by it).
TEST_F(TextureFiles, AnEightBitTextureThroughOpenImageIOIsSrgbDecodedWithoutItsAlpha)
{
  const std::vector<unsigned char> rgba = { 255, 128, 0, 255, 10, 200, 90, 128, 64, 64, 64, 0, 250, 20, 150, 255, 0, 0,
    255, 128, 30, 60, 90, 255, 180, 180, 30, 64, 1, 254, 77, 255 };
  writeTga((folder / "texture.tga").string(), rgba);
  std::vector<std::string> said;
  vtkSmartPointer<vtkPolyData> mesh = readParts("texture.tga", said);
  EXPECT_EQ(said, std::vector<std::string>{});
  const int texelsSeen = expectTexturedKd(
    mesh, [&](int column, int row, int c) { return srgbDecoded(rgba[std::size_t(4 * (row * 4 + column) + c)]); });
  EXPECT_EQ(texelsSeen, 18);
}

// One grey channel is a grey: each channel of kd takes it.
TEST_F(TextureFiles, AOneChannelTextureIsAGrey)
{
  const std::vector<unsigned char> grey = { 0, 40, 90, 128, 160, 200, 230, 255 };
  writeGreyTga((folder / "texture.tga").string(), grey);
  std::vector<std::string> said;
  vtkSmartPointer<vtkPolyData> mesh = readParts("texture.tga", said);
  EXPECT_EQ(
    expectTexturedKd(mesh, [&](int column, int row, int) { return srgbDecoded(grey[std::size_t(row * 4 + column)]); }),
    18);
}

/// A 4 x 2 Portable Float Map of RGB float32 texels, written byte by byte (little-endian, the
/// bottom row first, as the format has it); `rgb` holds each texel's R, G and B, rows from the
/// bottom.
void writePfm(const std::string& path, const std::vector<float>& rgb)
{
  std::ofstream out(path, std::ios::binary);
  out << "PF\n4 2\n-1.0\n";
  out.write(reinterpret_cast<const char*>(rgb.data()), std::streamsize(rgb.size() * sizeof(float)));
}

// A floating-point texture with values no reflectance can take: negative ones and NaNs become 0
// and values above 1 become 1 in kd, and the message counts them and gives the extremes.
TEST_F(TextureFiles, NegativeAndNotANumberTexelsAreClampedAndSaid)
{
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const std::vector<float> rgb = { 0.25f, -0.5f, 0.75f, nan, 0.5f, 0.125f, 1.5f, 0.0f, 1.0f, 0.375f, 0.625f, -2.0f,
    0.5f, 0.5f, 0.5f, 0.0625f, nan, 0.875f, 0.3f, 0.2f, 0.1f, 1.0f, 1.0f, 1.0f };
  writePfm((folder / "texture.pfm").string(), rgb);
  std::vector<std::string> said;
  vtkSmartPointer<vtkPolyData> mesh = readParts("texture.pfm", said);
  EXPECT_EQ(said,
    std::vector<std::string>{ "part 'tex': its texture has 5 texel values outside [0, 1] (as low as -2, as high as "
                              "1.5, 2 NaNs): clamped into it, since the texture multiplies kd, a reflectance" });
  const int texelsSeen = expectTexturedKd(mesh,
    [&](int column, int row, int c)
    {
      const float value = rgb[std::size_t(3 * (row * 4 + column) + c)];
      return std::isnan(value) ? 0.0 : std::clamp(double(value), 0.0, 1.0);
    });
  EXPECT_EQ(texelsSeen, 18);
}

// A header that declares more texels than ShadeLab takes (8193 x 8192, over its 8192 x 8192), or
// more than its file can hold, is refused before a texel is read, and the part keeps its Kd.
TEST_F(TextureFiles, ATextureLargerThanTheBoundOrItsFileIsRefused)
{
  for (const auto& [width, height, bytes] :
    { std::make_tuple(8193, 8192, std::size_t(1) << 21), std::make_tuple(100, 100, std::size_t(64)) })
  {
    const std::string size = std::to_string(width) + " x " + std::to_string(height);
    SCOPED_TRACE(size);
    {
      std::ofstream out(folder / "texture.pfm", std::ios::binary);
      out << "PF\n" << width << " " << height << "\n-1.0\n" << std::string(bytes, '\0');
    }
    std::vector<std::string> said;
    vtkSmartPointer<vtkPolyData> mesh = readParts("texture.pfm", said);
    ASSERT_EQ(said.size(), 1u);
    EXPECT_NE(said[0].find("its header declares " + size +
                " texels, which ShadeLab does not take (at most 8192 x 8192, and no more than the file can hold)"),
      std::string::npos)
      << said[0];
    expectUntexturedKd(mesh);
  }
}

TEST_F(TextureFiles, ATextureNeitherReaderTakesLeavesTheDiffuseColour)
{
  file("texture.hdr", "not an image");
  std::vector<std::string> said;
  vtkSmartPointer<vtkPolyData> mesh = readParts("texture.hdr", said);
  ASSERT_EQ(said.size(), 1u);
  const std::string start = "material 'tex' names the texture " + (folder / "texture.hdr").string() +
    ", which neither VTK nor OpenImageIO could read (cannot read as an image: ";
  EXPECT_EQ(said[0].substr(0, start.size()), start) << said[0];
  const std::string end = "): shaded with its diffuse colour alone";
  EXPECT_EQ(said[0].substr(said[0].size() - end.size()), end) << said[0];
  expectUntexturedKd(mesh);
}
}
