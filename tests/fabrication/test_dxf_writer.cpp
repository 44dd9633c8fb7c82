#include "fabrication/dxf_writer.hpp"

#include "tests/support/fabrication_hand_grid.hpp"
#include "tests/support/tool_run.hpp"

#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

namespace egg::fabrication {
namespace {

TEST(DxfWriter, R2000InMillimetresOneColourPerLayerPassesEzdxfAudit) {
  Drawing d;
  d.widthMm = 120.0;
  d.heightMm = 80.0;
  d.circles.push_back({Layer::Cut, {10.0, 20.0}, 1.5});
  d.slots.push_back({Layer::Cut, {30.0, 20.0}, {40.0, 20.0}, 2.0});
  d.polylines.push_back({Layer::Cut, {{0, 0}, {100, 0}, {100, 40}, {0, 40}}, true});
  d.polylines.push_back({Layer::Engrave, {{50, 5}, {60, 5}}, false});
  d.texts.push_back({Layer::Label, {70.0, 20.0}, 3.0, "P0-U1", TextAlign::Centre});
  d.texts.push_back({Layer::Label, {12.0, 20.0}, 2.1, "P0-C1-0", TextAlign::Left});
  const auto dir = testing::scratchDir("dxf_writer");
  std::ofstream(dir / "sample.dxf") << toDxf(d);
  const auto dxf = testing::readDxf(dir / "sample.dxf");
  ASSERT_TRUE(dxf.contains("entities"));
  EXPECT_EQ(dxf["audit_errors"], 0);
  EXPECT_EQ(dxf["audit_fixes"], 0);
  EXPECT_EQ(dxf["insunits"], 4);  // millimetres
  EXPECT_EQ(dxf["version"], "AC1015");
  for (const char* layer : {"CUT", "ENGRAVE", "LABEL", "REFERENCE", "TOOLPATH"}) {
    EXPECT_NE(std::find(dxf["layers"].begin(), dxf["layers"].end(), layer), dxf["layers"].end())
        << layer;
  }
  int circles = 0, polylines = 0, texts = 0;
  for (const auto& e : dxf["entities"]) {
    if (e["type"] == "CIRCLE") {
      ++circles;
      EXPECT_EQ(e["layer"], "CUT");
      EXPECT_NEAR(e["centre"][0].get<double>(), 10.0, 1e-9);
      EXPECT_NEAR(e["centre"][1].get<double>(), 20.0, 1e-9);
      EXPECT_NEAR(e["radius"].get<double>(), 1.5, 1e-9);
    } else if (e["type"] == "LWPOLYLINE") {
      ++polylines;
      if (e["points"].size() == 4 && e["points"][1][2].get<double>() == 1.0) {
        // The slot: corners (30,18), (40,18) bulge 1, (40,22), (30,22) bulge 1; closed.
        EXPECT_TRUE(e["closed"].get<bool>());
        EXPECT_NEAR(e["points"][0][0].get<double>(), 30.0, 1e-9);
        EXPECT_NEAR(e["points"][0][1].get<double>(), 18.0, 1e-9);
        EXPECT_NEAR(e["points"][2][0].get<double>(), 40.0, 1e-9);
        EXPECT_NEAR(e["points"][2][1].get<double>(), 22.0, 1e-9);
        EXPECT_DOUBLE_EQ(e["points"][3][2].get<double>(), 1.0);
      }
    } else if (e["type"] == "TEXT") {
      ++texts;
    }
  }
  EXPECT_EQ(circles, 1);
  // The slot, the outline, the mark and the labels' strokes: P0-U1 6, P0-C1-0 8.
  EXPECT_EQ(polylines, 3 + 6 + 8);
  EXPECT_EQ(texts, 0);  // labels are single-stroke polylines, no TEXT
  // One colour per layer: CUT 1, ENGRAVE 5, LABEL 3, REFERENCE 8, TOOLPATH 6.
  EXPECT_EQ(dxf["layer_colours"]["CUT"], 1);
  EXPECT_EQ(dxf["layer_colours"]["ENGRAVE"], 5);
  EXPECT_EQ(dxf["layer_colours"]["LABEL"], 3);
  EXPECT_EQ(dxf["layer_colours"]["REFERENCE"], 8);
  EXPECT_EQ(dxf["layer_colours"]["TOOLPATH"], 6);
}

TEST(DxfWriter, R12ForOldCamSoftwarePassesEzdxfAudit) {
  Drawing d;
  d.widthMm = 120.0;
  d.heightMm = 80.0;
  d.circles.push_back({Layer::Cut, {10.0, 20.0}, 1.5});
  d.slots.push_back({Layer::Cut, {30.0, 20.0}, {40.0, 20.0}, 2.0});
  d.polylines.push_back({Layer::Cut, {{0, 0}, {100, 0}, {100, 40}, {0, 40}}, true});
  d.texts.push_back({Layer::Label, {70.0, 20.0}, 3.0, "P0-U1", TextAlign::Centre});
  const auto dir = testing::scratchDir("dxf_writer_r12");
  std::ofstream(dir / "r12.dxf") << toDxf(d, DxfVersion::R12);
  const auto dxf = testing::readDxf(dir / "r12.dxf");
  ASSERT_TRUE(dxf.contains("entities"));
  EXPECT_EQ(dxf["version"], "AC1009");
  EXPECT_EQ(dxf["audit_errors"], 0);
  EXPECT_EQ(dxf["layer_colours"]["LABEL"], 3);
  int circles = 0, polylines = 0, bulgedSlots = 0, other = 0;
  for (const auto& e : dxf["entities"]) {
    if (e["type"] == "CIRCLE") {
      ++circles;
    } else if (e["type"] == "POLYLINE") {
      ++polylines;
      if (e["points"].size() == 4 && e["points"][1][2] == 1.0 && e["closed"]) ++bulgedSlots;
    } else {
      ++other;
    }
  }
  EXPECT_EQ(circles, 1);
  EXPECT_EQ(polylines, 2 + 6);  // slot, outline, 6 strokes of P0-U1
  EXPECT_EQ(bulgedSlots, 1);
  EXPECT_EQ(other, 0);  // no LWPOLYLINE (R2000) and no TEXT
}

// The ink of a greyscale PGM page (pdftoppm -gray): the bounding box of the pixels darker than
// light grey, in pixels {x0, y0, x1, y1}, and the page's size. Empty box: {w, h, -1, -1}.
struct PageInk {
  int width = 0, height = 0;
  int x0 = 0, y0 = 0, x1 = -1, y1 = -1;
};
PageInk readPgmInk(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::string magic;
  int maxValue = 0;
  PageInk ink;
  in >> magic >> ink.width >> ink.height >> maxValue;
  in.get();
  std::vector<unsigned char> pixels(static_cast<size_t>(ink.width) * ink.height);
  in.read(reinterpret_cast<char*>(pixels.data()), static_cast<std::streamsize>(pixels.size()));
  if (magic != "P5" || maxValue != 255 || !in) return {};
  ink.x0 = ink.width, ink.y0 = ink.height;
  for (int y = 0; y < ink.height; ++y) {
    for (int x = 0; x < ink.width; ++x) {
      if (pixels[static_cast<size_t>(y) * ink.width + x] > 200) continue;
      ink.x0 = std::min(ink.x0, x), ink.x1 = std::max(ink.x1, x);
      ink.y0 = std::min(ink.y0, y), ink.y1 = std::max(ink.y1, y);
    }
  }
  return ink;
}

// LibreCAD's print with none of its own options (librecad dxf2pdf, as File > Print takes the
// drawing's page set-up) puts the whole 13.5 x 2.5 m sheet on the scene's A3, landscape, at 1:50
// (the largest standard scale inside a 10 mm border: 13500 / 400 = 33.75 -> 50), centred: the
// sheet's outline spans 270 x 50 mm from (75, 123.5) mm, in both DXF versions. Without the page
// set-up it printed an A4 portrait page at 1:1, the sheet's corner.
TEST(DxfWriter, LibreCadPrintsTheWholeSheetCentredOnTheScenesPaper) {
  if (!test::haveTool("librecad"))
    GTEST_SKIP() << "librecad is not installed (scripts/install-deps.sh)";
  Drawing d;
  d.widthMm = 13500.0;
  d.heightMm = 2500.0;
  d.polylines.push_back({Layer::Reference, {{0, 0}, {13500, 0}, {13500, 2500}, {0, 2500}}, true});
  d.polylines.push_back({Layer::Cut, {{100, 100}, {13400, 100}, {13400, 580}, {100, 580}}, true});
  d.circles.push_back({Layer::Cut, {500.0, 340.0}, 9.0});
  const auto dir = testing::scratchDir("dxf_writer_librecad");
  for (const DxfVersion version : {DxfVersion::R2000, DxfVersion::R12}) {
    SCOPED_TRACE(version == DxfVersion::R12 ? "R12" : "R2000");
    std::ofstream(dir / "sheet.dxf") << toDxf(d, version, PaperSize::A3);
    const auto print = test::runTool(
        "cd " + dir.string() + " && QT_QPA_PLATFORM=offscreen XDG_RUNTIME_DIR=" + dir.string() +
        " timeout 60 librecad dxf2pdf sheet.dxf");
    ASSERT_EQ(print.status, 0) << print.output;
    const auto info = test::runTool("pdfinfo " + (dir / "sheet.pdf").string());
    EXPECT_NE(info.output.find("Page size:       1191 x 842 pts (A3)"), std::string::npos)
        << info.output;
    // 5 pixels per millimetre (127 dpi).
    const auto render = test::runTool("pdftoppm -gray -r 127 -singlefile " +
                                      (dir / "sheet.pdf").string() + " " + (dir / "page").string());
    ASSERT_EQ(render.status, 0) << render.output;
    const PageInk ink = readPgmInk(dir / "page.pgm");
    ASSERT_GT(ink.x1, 0) << "nothing printed";
    constexpr double kPxPerMm = 127.0 / 25.4;
    EXPECT_NEAR(ink.width / kPxPerMm, 420.0, 1.0);
    EXPECT_NEAR(ink.x0 / kPxPerMm, 75.0, 1.5);
    EXPECT_NEAR(ink.x1 / kPxPerMm, 345.0, 1.5);
    EXPECT_NEAR(ink.y0 / kPxPerMm, 123.5, 1.5);
    EXPECT_NEAR(ink.y1 / kPxPerMm, 173.5, 1.5);
  }
}

TEST(DxfWriter, EmptyDrawingIsStillAValidFile) {
  Drawing d;
  d.widthMm = 10.0;
  d.heightMm = 10.0;
  const auto dir = testing::scratchDir("dxf_writer_empty");
  std::ofstream(dir / "empty.dxf") << toDxf(d);
  const auto dxf = testing::readDxf(dir / "empty.dxf");
  EXPECT_EQ(dxf["audit_errors"], 0);
  EXPECT_EQ(dxf["audit_fixes"], 0);
  EXPECT_EQ(dxf["entities"].size(), 0u);
}

}  // namespace
}  // namespace egg::fabrication
