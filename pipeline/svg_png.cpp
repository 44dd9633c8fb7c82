#include "pipeline/svg_png.hpp"

#include "core/errors.hpp"

#include <cairo.h>
#include <gio/gio.h>
#include <librsvg/rsvg.h>

#include <cmath>
#include <memory>
#include <system_error>

namespace egg::pipeline {

void writePngFromSvg(const std::string& svgText, const std::filesystem::path& path, int widthPx) {
  if (widthPx <= 0 || widthPx > 20000)
    throw InvalidInput("PNG preview " + path.string() + ": width " + std::to_string(widthPx) +
                       " px out of range");
  GError* error = nullptr;
  // RSVG_HANDLE_FLAG_UNLIMITED: libxml2's default limits refuse a document above 10 MB, which the
  // K map of a 140k-face mesh is (issue 40); the figures are our own, not untrusted input.
  std::unique_ptr<GInputStream, void (*)(void*)> stream(
      g_memory_input_stream_new_from_data(svgText.data(), static_cast<gssize>(svgText.size()),
                                          nullptr),
      g_object_unref);
  std::unique_ptr<RsvgHandle, void (*)(void*)> handle(
      rsvg_handle_new_from_stream_sync(stream.get(), nullptr, RSVG_HANDLE_FLAG_UNLIMITED, nullptr,
                                       &error),
      g_object_unref);
  if (!handle) {
    const std::string why = error ? error->message : "unknown";
    if (error) g_error_free(error);
    throw InvalidInput("PNG preview " + path.string() + ": the SVG cannot be read: " + why);
  }
  // The aspect ratio: the intrinsic size in pixels when the SVG states one, else its viewBox.
  double w = 0.0, h = 0.0;
  if (!rsvg_handle_get_intrinsic_size_in_pixels(handle.get(), &w, &h) || w <= 0.0 || h <= 0.0) {
    gboolean hasWidth = FALSE, hasHeight = FALSE, hasViewBox = FALSE;
    RsvgLength lw, lh;
    RsvgRectangle viewBox;
    rsvg_handle_get_intrinsic_dimensions(handle.get(), &hasWidth, &lw, &hasHeight, &lh, &hasViewBox,
                                         &viewBox);
    if (!hasViewBox || viewBox.width <= 0.0 || viewBox.height <= 0.0)
      throw InvalidInput("PNG preview " + path.string() +
                         ": the SVG has neither a size in pixels nor a viewBox");
    w = viewBox.width;
    h = viewBox.height;
  }
  const int heightPx = std::max(1, static_cast<int>(std::lround(widthPx * h / w)));
  std::unique_ptr<cairo_surface_t, void (*)(cairo_surface_t*)> surface(
      cairo_image_surface_create(CAIRO_FORMAT_ARGB32, widthPx, heightPx), cairo_surface_destroy);
  std::unique_ptr<cairo_t, void (*)(cairo_t*)> cr(cairo_create(surface.get()), cairo_destroy);
  cairo_set_source_rgb(cr.get(), 1.0, 1.0, 1.0);  // a white page, as in the browser
  cairo_paint(cr.get());
  const RsvgRectangle viewport{0.0, 0.0, static_cast<double>(widthPx),
                               static_cast<double>(heightPx)};
  if (!rsvg_handle_render_document(handle.get(), cr.get(), &viewport, &error)) {
    const std::string why = error ? error->message : "unknown";
    if (error) g_error_free(error);
    throw InvalidInput("PNG preview " + path.string() + ": the SVG cannot be drawn: " + why);
  }
  cairo_surface_flush(surface.get());
  // Written next to the target and renamed, so a reader never sees half a PNG.
  std::filesystem::path tmp = path;
  tmp += ".tmp";
  if (cairo_surface_write_to_png(surface.get(), tmp.c_str()) != CAIRO_STATUS_SUCCESS) {
    std::error_code ignore;
    std::filesystem::remove(tmp, ignore);
    throw WriteError("cannot write PNG preview " + path.string());
  }
  std::error_code renameError;
  std::filesystem::rename(tmp, path, renameError);
  if (renameError)
    throw WriteError("cannot write PNG preview " + path.string() + ": " + renameError.message());
}

}  // namespace egg::pipeline
