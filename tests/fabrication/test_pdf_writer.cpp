#include "fabrication/pdf_writer.hpp"

#include "tests/support/fabrication_hand_grid.hpp"

#include <gtest/gtest.h>

#include <fstream>

namespace egg::fabrication {
namespace {

TEST(PdfWriter, OnePagePerDrawingAtTrueSize) {
  ASSERT_TRUE(testing::haveTool("pdfinfo"))
      << "pdfinfo missing: run scripts/install-deps.sh (poppler-utils)";
  std::vector<Drawing> pages(3);
  for (auto& p : pages) {
    p.widthMm = 254.0;   // 720 pt
    p.heightMm = 127.0;  // 360 pt
    p.circles.push_back({Layer::Cut, {10.0, 10.0}, 2.0});
    p.slots.push_back({Layer::Cut, {30.0, 20.0}, {40.0, 25.0}, 2.0});
    p.polylines.push_back({Layer::Engrave, {{1, 1}, {50, 1}}, false});
    p.texts.push_back({Layer::Label, {60.0, 20.0}, 3.0, "P0-U1", TextAlign::Centre});
  }
  const auto dir = testing::scratchDir("pdf_writer");
  std::ofstream(dir / "sheets.pdf", std::ios::binary) << toPdf(pages);
  const auto run = testing::runTool("pdfinfo " + (dir / "sheets.pdf").string());
  ASSERT_EQ(run.status, 0) << run.output;
  EXPECT_NE(run.output.find("Pages:           3"), std::string::npos) << run.output;
  EXPECT_NE(run.output.find("720 x 360 pts"), std::string::npos) << run.output;
}

}  // namespace
}  // namespace egg::fabrication
