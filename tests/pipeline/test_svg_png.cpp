#include "pipeline/svg_png.hpp"

#include "core/errors.hpp"

#include <cairo.h>
#include <gtest/gtest.h>

#include <unistd.h>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <iterator>
#include <memory>
#include <string>

namespace egg::pipeline {
namespace {

std::filesystem::path tempPng(const std::string& name) {
  return std::filesystem::temp_directory_path() /
         ("egg_svg_png_" + std::to_string(getpid()) + "_" + name + ".png");
}

// The pixel (x, y) of a PNG as 0xRRGGBB (read back with cairo, independent of librsvg).
struct Png {
  std::unique_ptr<cairo_surface_t, void (*)(cairo_surface_t*)> surface{nullptr,
                                                                       cairo_surface_destroy};
  int width() const { return cairo_image_surface_get_width(surface.get()); }
  int height() const { return cairo_image_surface_get_height(surface.get()); }
  uint32_t rgb(int x, int y) const {
    const unsigned char* row = cairo_image_surface_get_data(surface.get()) +
                               y * cairo_image_surface_get_stride(surface.get());
    uint32_t pixel;
    std::memcpy(&pixel, row + 4 * x, 4);
    return pixel & 0xFFFFFFu;
  }
};

Png readPng(const std::filesystem::path& path) {
  Png png;
  png.surface.reset(cairo_image_surface_create_from_png(path.c_str()));
  EXPECT_EQ(cairo_surface_status(png.surface.get()), CAIRO_STATUS_SUCCESS) << path;
  cairo_surface_flush(png.surface.get());
  return png;
}

// Red on the left half, blue on the right, in a 200 x 100 viewBox: rasterised 400 px wide the PNG
// is 400 x 200 with the halves where the SVG puts them.
TEST(SvgPng, RasterisesAtTheAskedWidthWithTheSvgsAspect) {
  const std::string svg = R"(<svg xmlns="http://www.w3.org/2000/svg" viewBox="0 0 200 100">
    <rect x="0" y="0" width="100" height="100" fill="#ff0000"/><rect x="100" y="0" width="100" height="100" fill="#0000ff"/></svg>)";
  const auto path = tempPng("halves");
  writePngFromSvg(svg, path, 400);
  std::ifstream in(path, std::ios::binary);
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  ASSERT_GE(bytes.size(), 24u);
  EXPECT_EQ(bytes.substr(0, 8), std::string("\x89PNG\r\n\x1a\n", 8));
  // IHDR: width and height big-endian at bytes 16..23.
  auto be32 = [&](size_t at) {
    return (uint32_t(uint8_t(bytes[at])) << 24) | (uint32_t(uint8_t(bytes[at + 1])) << 16) |
           (uint32_t(uint8_t(bytes[at + 2])) << 8) | uint32_t(uint8_t(bytes[at + 3]));
  };
  EXPECT_EQ(be32(16), 400u);
  EXPECT_EQ(be32(20), 200u);
  const Png png = readPng(path);
  ASSERT_EQ(png.width(), 400);
  ASSERT_EQ(png.height(), 200);
  EXPECT_EQ(png.rgb(50, 100), 0xFF0000u);
  EXPECT_EQ(png.rgb(350, 100), 0x0000FFu);
  std::filesystem::remove(path);
}

// A pixel size wins over the viewBox for the aspect; what the SVG leaves empty is white.
TEST(SvgPng, UsesThePixelSizeAndAWhitePage) {
  const std::string svg =
      R"(<svg xmlns="http://www.w3.org/2000/svg" width="300" height="100" viewBox="0 0 300 100">
    <circle cx="50" cy="50" r="40" fill="#000000"/></svg>)";
  const auto path = tempPng("circle");
  writePngFromSvg(svg, path, 600);
  const Png png = readPng(path);
  ASSERT_EQ(png.width(), 600);
  ASSERT_EQ(png.height(), 200);
  EXPECT_EQ(png.rgb(100, 100), 0x000000u);
  EXPECT_EQ(png.rgb(500, 100), 0xFFFFFFu);
  std::filesystem::remove(path);
}

TEST(SvgPng, RejectsTextThatIsNotSvgAndBadWidths) {
  const auto path = tempPng("bad");
  EXPECT_THROW(writePngFromSvg("not an svg", path, 100), InvalidInput);
  EXPECT_THROW(writePngFromSvg(R"(<svg xmlns="http://www.w3.org/2000/svg"/>)", path, 100),
               InvalidInput);
  EXPECT_THROW(
      writePngFromSvg(R"(<svg xmlns="http://www.w3.org/2000/svg" viewBox="0 0 1 1"/>)", path, 0),
      InvalidInput);
  EXPECT_FALSE(std::filesystem::exists(path));
}

// Issue 40: the K map of a 140k-face mesh is 12 MB of SVG; libxml2's default limits stop at 10 MB
// ("Premature end of data"), and the finished run was thrown away as bad input.
TEST(SvgPng, DrawsAFigureAboveTenMegabytes) {
  std::string svg =
      R"(<svg xmlns="http://www.w3.org/2000/svg" width="200" height="100" viewBox="0 0 200 100">)";
  // Twelve paths of a megabyte each (a long number: cheap to draw, as heavy to read).
  const std::string d = "M10." + std::string(size_t{1} << 20, '0') + "1,50h1v1z";
  for (int k = 0; k < 12; ++k) svg += "<path fill=\"#000\" d=\"" + d + "\"/>\n";
  svg += R"(<rect x="100" width="100" height="100" fill="#000"/></svg>)";
  const auto path = tempPng("huge");
  writePngFromSvg(svg, path, 200);
  const Png png = readPng(path);
  EXPECT_EQ(png.rgb(150, 50), 0x000000u) << "the element after the 12 MB was drawn";
  std::filesystem::remove(path);
}

TEST(SvgPng, NamesTheFileItCannotWrite) {
  const std::string svg =
      R"(<svg xmlns="http://www.w3.org/2000/svg" viewBox="0 0 10 10"><rect width="5" height="5"/></svg>)";
  const auto path = std::filesystem::path("/nonexistent_egg_dir") / "x.png";
  try {
    writePngFromSvg(svg, path, 10);
    FAIL() << "expected WriteError";
  } catch (const WriteError& e) {
    EXPECT_NE(std::string(e.what()).find("/nonexistent_egg_dir/x.png"), std::string::npos)
        << e.what();
  }
}

}  // namespace
}  // namespace egg::pipeline
