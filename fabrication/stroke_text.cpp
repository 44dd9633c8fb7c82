#include "fabrication/stroke_text.hpp"

#include "core/errors.hpp"

// libhersheyfont is C and its header says so nowhere.
extern "C" {
#include <hersheyfont.h>
}

#include <memory>

namespace egg::fabrication {
namespace {

// Hershey glyphs as libhersheyfont returns them: y up, baseline at 0, capitals 21 units high,
// x from the glyph's left bound, `width` the advance.
constexpr double kCapitalUnits = 21.0;
constexpr const char* kFont = "futural";

struct FontDeleter {
  void operator()(hershey_font* font) const { hershey_font_free(font); }
};

hershey_font& font() {
  // Loaded once (a function-local static is initialised thread-safely) and kept for the process.
  static const std::unique_ptr<hershey_font, FontDeleter> loaded(hershey_font_load(kFont));
  if (!loaded) {
    throw IoError(std::string("cannot load the Hershey font \"") + kFont +
                  "\" (/usr/share/hershey-fonts/" + kFont +
                  ".jhf, Debian package hershey-fonts-data; scripts/install-deps.sh installs it)");
  }
  return *loaded;
}

const hershey_glyph* glyphOf(char c) {
  const hershey_glyph* g = hershey_font_glyph(&font(), static_cast<unsigned char>(c));
  if (g && g->width > 0) return g;
  return hershey_font_glyph(&font(), static_cast<unsigned char>(' '));
}

}  // namespace

std::vector<std::vector<Eigen::Vector2d>> textStrokes(const std::string& text, double heightMm) {
  const double scale = heightMm / kCapitalUnits;
  std::vector<std::vector<Eigen::Vector2d>> strokes;
  double x = 0.0;
  for (char c : text) {
    const hershey_glyph* g = glyphOf(c);
    if (!g) continue;
    for (const hershey_path* p = g->paths; p; p = p->next) {
      std::vector<Eigen::Vector2d> stroke;
      for (unsigned short i = 0; i < p->nverts; ++i)
        stroke.emplace_back(x + scale * p->verts[i].x, scale * p->verts[i].y);
      if (stroke.size() >= 2) strokes.push_back(std::move(stroke));
    }
    x += scale * g->width;
  }
  return strokes;
}

double strokeTextWidthMm(const std::string& text, double heightMm) {
  double units = 0.0;
  for (char c : text) {
    const hershey_glyph* g = glyphOf(c);
    if (g) units += g->width;
  }
  return units * heightMm / kCapitalUnits;
}

std::vector<std::vector<Eigen::Vector2d>> placedStrokes(const DrawText& t) {
  auto strokes = textStrokes(t.text, t.height);
  const double width = strokeTextWidthMm(t.text, t.height);
  const Eigen::Vector2d shift =
      t.anchor - Eigen::Vector2d(t.align == TextAlign::Left ? 0.0 : width / 2.0, t.height / 2.0);
  for (auto& stroke : strokes) {
    for (auto& p : stroke) p += shift;
  }
  return strokes;
}

}  // namespace egg::fabrication
