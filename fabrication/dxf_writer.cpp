#include "fabrication/dxf_writer.hpp"

#include "core/errors.hpp"
#include "core/io/atomic_file.hpp"
#include "fabrication/stroke_text.hpp"

#include <dl_dxf.h>
#include <dl_writer_ascii.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
#include <sstream>
#include <vector>

namespace egg::fabrication {
namespace {

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

}  // namespace

std::string toDxf(const Drawing& d, DxfVersion version) {
  const bool r12 = version == DxfVersion::R12;
  // dxflib writes only to a named file: write into a private temporary file and read it back, so
  // that the caller places the text atomically (core/io/atomic_file.hpp).
  const auto tmp =
      std::filesystem::temp_directory_path() / ("egg_dxf_" + temporarySuffix() + ".dxf");
  {
    DL_Dxf dxf;
    std::unique_ptr<DL_WriterA> dw(
        dxf.out(tmp.string().c_str(), r12 ? DL_Codes::AC1009 : DL_Codes::AC1015));
    if (!dw) throw WriteError("cannot write a temporary DXF file " + tmp.string());
    dxf.writeHeader(*dw);
    if (!r12) {  // R12 knows neither; its readers take the numbers as they are (millimetres)
      dw->dxfString(9, "$INSUNITS");
      dw->dxfInt(70, 4);  // millimetres
      dw->dxfString(9, "$MEASUREMENT");
      dw->dxfInt(70, 1);  // metric
    }
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
    dw->close();
  }
  std::ifstream in(tmp, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  std::error_code ignored;
  std::filesystem::remove(tmp, ignored);
  if (!in) throw WriteError("cannot read back the temporary DXF file " + tmp.string());
  return r12 ? text.str() : withObjectOwners(text.str());
}

}  // namespace egg::fabrication
