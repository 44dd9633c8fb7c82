#include "fabrication/dxf_writer.hpp"

#include "tests/support/fabrication_hand_grid.hpp"

#include <gtest/gtest.h>

#include <fstream>

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
