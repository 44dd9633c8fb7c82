#include "fabrication/dxf_writer.hpp"

#include "core/errors.hpp"
#include "fabrication/pdf_pages.hpp"
#include "fabrication/stroke_text.hpp"

#include <dl_dxf.h>
#include <dl_writer_ascii.h>

#include <algorithm>
#include <array>
#include <charconv>
#include <cstdio>
#include <map>
#include <memory>
#include <sstream>
#include <string_view>
#include <vector>

namespace egg::fabrication {
namespace {

// dxflib's DL_WriterA writes to a named file and flushes after every real: ~20,000 write calls
// of 30 bytes per Great Court sheet, through a temporary file that then has to be read back. This
// writer keeps the text in memory instead (no temporary file at all), in the same ASCII layout:
// the group code right-aligned in three columns on its own line, the value on the next. DL_Dxf
// takes a DL_WriterA&, and the group-value functions are virtual in dxflib's DL_Writer, so
// overriding them here catches every line dxflib writes. The base class is constructed with an
// empty file name, which opens nothing (its stream stays closed and unused).
class MemoryDxfWriter final : public DL_WriterA {
 public:
  explicit MemoryDxfWriter(DL_Codes::version version) : DL_WriterA("", version) {
    text_.reserve(1 << 20);
  }
  void dxfReal(int gc, double value) const override {
    // Shortest round-trip decimal in fixed notation (CAM readers do not all take exponents),
    // locale-independent, with a decimal point always.
    char buffer[400];
    auto [end, ec] =
        std::to_chars(buffer, buffer + sizeof buffer - 2, value, std::chars_format::fixed);
    if (ec != std::errc()) throw WriteError("a DXF number out of range");
    if (std::find(buffer, end, '.') == end) {
      *end++ = '.';
      *end++ = '0';
    }
    line(gc, std::string_view(buffer, static_cast<size_t>(end - buffer)));
  }
  void dxfInt(int gc, int value) const override { line(gc, std::to_string(value)); }
  void dxfHex(int gc, int value) const override {
    char buffer[16];
    std::snprintf(buffer, sizeof buffer, "%X", static_cast<unsigned>(value));
    line(gc, buffer);
  }
  void dxfString(int gc, const char* value) const override { line(gc, value ? value : ""); }
  void dxfString(int gc, const std::string& value) const override { line(gc, value); }
  std::string take() { return std::move(text_); }

 private:
  void line(int gc, std::string_view value) const {
    if (gc < 10)
      text_ += "  ";
    else if (gc < 100)
      text_ += ' ';
    text_ += std::to_string(gc);
    text_ += '\n';
    text_ += value;
    text_ += '\n';
  }
  mutable std::string text_;
};

DL_Attributes attributesOf(Layer layer) {
  // Colour and line type BYLAYER (256): the layer decides, as CAM software expects.
  return DL_Attributes(layerName(layer), 256, -1, "BYLAYER", 1.0);
}

void writePolyline(DL_Dxf& dxf, DL_WriterA& dw, Layer layer,
                   const std::vector<Eigen::Vector2d>& points, const std::vector<double>& bulges,
                   bool closed) {
  dxf.writePolyline(dw, DL_PolylineData(static_cast<int>(points.size()), 0, 0, closed ? 1 : 0),
                    attributesOf(layer));
  for (size_t i = 0; i < points.size(); ++i) {
    dxf.writeVertex(
        dw, DL_VertexData(points[i].x(), points[i].y(), 0.0, bulges.empty() ? 0.0 : bulges[i]));
  }
  dxf.writePolylineEnd(dw);
}

void writeEntities(DL_Dxf& dxf, DL_WriterA& dw, const Drawing& d) {
  for (const auto& c : d.circles) {
    dxf.writeCircle(dw, DL_CircleData(c.centre.x(), c.centre.y(), 0.0, c.radius),
                    attributesOf(c.layer));
  }
  for (const auto& s : d.slots) {
    // Counter-clockwise: straight side, half circle (bulge 1) around b, straight side, half circle
    // around a.
    writePolyline(dxf, dw, s.layer, slotCorners(s), {0.0, 1.0, 0.0, 1.0}, true);
  }
  for (const auto& p : d.polylines) {
    if (p.points.size() >= 2) writePolyline(dxf, dw, p.layer, p.points, {}, p.closed);
  }
  for (const auto& t : d.texts) {
    // Single-stroke outlines (stroke_text.hpp), not TEXT: no CAM tool needs a font, and importers
    // that drop TEXT keep every label.
    for (const auto& stroke : placedStrokes(t)) writePolyline(dxf, dw, t.layer, stroke, {}, false);
  }
}

// dxflib's OBJECTS boilerplate (the root dictionary, groups, layouts, ...) carries no owner handles
// (group code 330 after the handle), which every reader has to repair: ezdxf's audit counts 13
// fixes per file. Each object is owned by the dictionary whose entries (350/360) name it; the root
// dictionary by nobody ("0"). The owner goes right after the object's handle, where DXF puts it.
std::string withObjectOwners(const std::string& text) {
  std::vector<std::string> lines;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  const auto code = [&](size_t i) {
    return lines[i].find_first_not_of(' ') == std::string::npos
               ? std::string()
               : lines[i].substr(lines[i].find_first_not_of(' '));
  };
  size_t begin = lines.size(), end = lines.size();
  for (size_t i = 0; i + 1 < lines.size(); i += 2) {
    if (code(i) == "2" && lines[i + 1] == "OBJECTS") begin = i + 2;
    if (begin < lines.size() && i >= begin && code(i) == "0" && lines[i + 1] == "ENDSEC") {
      end = i;
      break;
    }
  }
  if (begin >= end) return text;
  std::map<std::string, std::string> ownerOf;
  std::string current, root;
  for (size_t i = begin; i + 1 < end; i += 2) {
    const std::string c = code(i);
    if (c == "0") current.clear();
    if (c == "5" && current.empty()) {
      current = lines[i + 1];
      if (root.empty()) root = current;
    }
    if ((c == "350" || c == "360") && !current.empty()) ownerOf.emplace(lines[i + 1], current);
  }
  std::string out;
  out.reserve(text.size() + 256);
  bool handleSeen = false;
  for (size_t i = 0; i < lines.size(); ++i) {
    out += lines[i];
    out += '\n';
    if (i < begin || i >= end || (i - begin) % 2 != 0) continue;
    const std::string c = code(i);
    if (c == "0") handleSeen = false;
    if (c == "5" && !handleSeen && i + 1 < end) {
      handleSeen = true;
      const std::string& handle = lines[i + 1];
      out += lines[i + 1] + "\n";
      ++i;
      const auto owner = ownerOf.find(handle);
      out += "330\n" +
             (handle == root           ? std::string("0")
              : owner != ownerOf.end() ? owner->second
                                       : root) +
             "\n";
    }
  }
  return out;
}

// The page a CAD program prints on when nothing else is chosen. LibreCAD (and AutoCAD's
// paper-space defaults) read the paper's limits ($PLIMMIN/$PLIMMAX), the scale of model space on
// it ($PSVPSCALE) and where the model's origin falls on the paper ($PINSBASE). Without them
// LibreCAD prints an A4 portrait page at 1:1, the corner of a 13.5 m sheet (issue 38). Here the
// scene's paper, turned to the sheet's shape, at the largest standard scale that fits inside a
// 10 mm border, the sheet centred: the print matches the fitted sheets.pdf page.
void writePrintSetup(DL_WriterA& dw, const Drawing& d, PaperSize paper) {
  const std::array<double, 2> portrait = paperSizeMm(paper);
  const bool landscape = d.widthMm >= d.heightMm;
  const double pw = landscape ? portrait[1] : portrait[0];
  const double ph = landscape ? portrait[0] : portrait[1];
  constexpr double kBorderMm = 10.0;
  const double n = fittingScale({std::max(d.widthMm, 1e-3), std::max(d.heightMm, 1e-3)},
                                {pw - 2.0 * kBorderMm, ph - 2.0 * kBorderMm});
  dw.dxfString(9, "$PINSBASE");
  dw.dxfReal(10, 0.5 * (pw - d.widthMm / n));
  dw.dxfReal(20, 0.5 * (ph - d.heightMm / n));
  dw.dxfReal(30, 0.0);
  dw.dxfString(9, "$PLIMMIN");
  dw.dxfReal(10, 0.0);
  dw.dxfReal(20, 0.0);
  dw.dxfString(9, "$PLIMMAX");
  dw.dxfReal(10, pw);
  dw.dxfReal(20, ph);
  // AutoCAD 2000's variable, written in R12 files too: LibreCAD reads it in either, and R12
  // readers skip a header variable they do not know (ezdxf's audit passes).
  dw.dxfString(9, "$PSVPSCALE");
  dw.dxfReal(40, 1.0 / n);
}

}  // namespace

std::string toDxf(const Drawing& d, DxfVersion version, PaperSize paper) {
  const bool r12 = version == DxfVersion::R12;
  DL_Dxf dxf;
  const DL_Codes::version dxfVersion = r12 ? DL_Codes::AC1009 : DL_Codes::AC1015;
  // DL_Dxf keeps the version its entity writers follow private, set only by out(): an empty file
  // name sets it and opens nothing (out() returns null when the file does not open).
  if (dxf.out("", dxfVersion) != nullptr) throw WriteError("dxflib opened a file with no name");
  auto dw = std::make_unique<MemoryDxfWriter>(dxfVersion);
  {
    dxf.writeHeader(*dw);
    if (!r12) {  // R12 knows neither; its readers take the numbers as they are (millimetres)
      dw->dxfString(9, "$INSUNITS");
      dw->dxfInt(70, 4);  // millimetres
      dw->dxfString(9, "$MEASUREMENT");
      dw->dxfInt(70, 1);  // metric
    }
    writePrintSetup(*dw, d, paper);
    dw->dxfString(9, "$EXTMIN");
    dw->dxfReal(10, 0.0);
    dw->dxfReal(20, 0.0);
    dw->dxfReal(30, 0.0);
    dw->dxfString(9, "$EXTMAX");
    dw->dxfReal(10, d.widthMm);
    dw->dxfReal(20, d.heightMm);
    dw->dxfReal(30, 0.0);
    dw->sectionEnd();

    dw->sectionTables();
    dxf.writeVPort(*dw);
    dw->tableLinetypes(3);
    dxf.writeLinetype(*dw, DL_LinetypeData("BYBLOCK", "", 0, 0, 0.0));
    dxf.writeLinetype(*dw, DL_LinetypeData("BYLAYER", "", 0, 0, 0.0));
    dxf.writeLinetype(*dw, DL_LinetypeData("CONTINUOUS", "Solid line", 0, 0, 0.0));
    dw->tableEnd();
    dw->tableLayers(1 + static_cast<int>(std::size(kLayers)));
    dxf.writeLayer(*dw, DL_LayerData("0", 0), DL_Attributes("", 7, -1, "CONTINUOUS", 1.0));
    for (Layer layer : kLayers) {
      dxf.writeLayer(*dw, DL_LayerData(layerName(layer), 0),
                     DL_Attributes("", layerAci(layer), -1, "CONTINUOUS", 1.0));
    }
    dw->tableEnd();
    dw->tableStyle(1);
    dxf.writeStyle(*dw, DL_StyleData("Standard", 0, 0.0, 1.0, 0.0, 0, 2.5, "txt", ""));
    dw->tableEnd();
    dxf.writeView(*dw);
    dxf.writeUcs(*dw);
    dw->tableAppid(1);
    dxf.writeAppid(*dw, "ACAD");
    dw->tableEnd();
    dxf.writeDimStyle(*dw, 2.5, 0.625, 0.625, 0.625, 2.5);
    if (!r12) {  // block records and layout blocks are AutoCAD 2000's; R12 has neither
      dxf.writeBlockRecord(*dw);
      dw->tableEnd();
    }
    dw->sectionEnd();

    dw->sectionBlocks();
    if (!r12) {
      dxf.writeBlock(*dw, DL_BlockData("*Model_Space", 0, 0.0, 0.0, 0.0));
      dxf.writeEndBlock(*dw, "*Model_Space");
      dxf.writeBlock(*dw, DL_BlockData("*Paper_Space", 0, 0.0, 0.0, 0.0));
      dxf.writeEndBlock(*dw, "*Paper_Space");
      dxf.writeBlock(*dw, DL_BlockData("*Paper_Space0", 0, 0.0, 0.0, 0.0));
      dxf.writeEndBlock(*dw, "*Paper_Space0");
    }
    dw->sectionEnd();

    dw->sectionEntities();
    writeEntities(dxf, *dw, d);
    dw->sectionEnd();
    if (!r12) {
      dxf.writeObjects(*dw);
      dxf.writeObjectsEnd(*dw);
    }
    dw->dxfEOF();
  }
  std::string text = dw->take();
  return r12 ? text : withObjectOwners(text);
}

}  // namespace egg::fabrication
