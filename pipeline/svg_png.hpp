#pragma once
// PNG previews of the report's figures (issue 18, "and PNG previews of the same"): the same SVG
// text the report inlines, rasterised with librsvg + cairo. librsvg stays inside svg_png.cpp.
#include <filesystem>
#include <string>

namespace egg::pipeline {

// Rasterises `svgText` to a PNG `widthPx` wide at `path` (written atomically), the height from the
// SVG's own aspect ratio (width/height attributes, else its viewBox), on a white background.
// Throws InvalidInput when the text is not SVG or has no size, WriteError naming the file.
void writePngFromSvg(const std::string& svgText, const std::filesystem::path& path, int widthPx);

}  // namespace egg::pipeline
