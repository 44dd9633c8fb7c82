#include "fabrication/pdf_writer.hpp"

#include "fabrication/pdf_pages.hpp"

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
  std::ofstream(dir / "sheets.pdf", std::ios::binary) << toPdf(pages, SheetPdf::TrueSize);
  const auto run = testing::runTool("pdfinfo " + (dir / "sheets.pdf").string());
  ASSERT_EQ(run.status, 0) << run.output;
  EXPECT_NE(run.output.find("Pages:           3"), std::string::npos) << run.output;
  EXPECT_NE(run.output.find("720 x 360 pts"), std::string::npos) << run.output;
}

Drawing bigSheet() {
  Drawing d;
  d.title = "lamella sheet L01 (1 of 1)";
  d.widthMm = 2500.0;
  d.heightMm = 1250.0;
  d.polylines.push_back({Layer::Cut, {{10, 10}, {2490, 10}, {2490, 260}, {10, 260}}, true});
  d.texts.push_back({Layer::Label, {1250.0, 135.0}, 30.0, "P0-U1", TextAlign::Centre});
  return d;
}

TEST(PdfWriter, FittedSheetOnALandscapeIsoPageWithItsScalePrinted) {
  ASSERT_TRUE(testing::haveTool("pdfinfo") && testing::haveTool("pdftotext"));
  const auto dir = testing::scratchDir("pdf_writer_fit");
  std::ofstream(dir / "fit.pdf", std::ios::binary)
      << toPdf({bigSheet(), bigSheet()}, SheetPdf::Fit, PaperSize::A3);
  const auto info = testing::runTool("pdfinfo " + (dir / "fit.pdf").string());
  EXPECT_NE(info.output.find("Pages:           2"), std::string::npos) << info.output;
  EXPECT_NE(info.output.find("1190.55 x 841.89 pts (A3)"), std::string::npos) << info.output;
  // A3 landscape less borders and title band: 400 x 263 mm; 2500 / 400 = 6.25, 1250 / 263 = 4.75:
  // the next standard scale is 1:10.
  EXPECT_DOUBLE_EQ(fittingScale({2500.0, 1250.0}, {400.0, 263.0}), 10.0);
  EXPECT_DOUBLE_EQ(fittingScale({1000.0, 100.0}, {400.0, 263.0}), 2.5);
  EXPECT_DOUBLE_EQ(fittingScale({100.0, 100.0}, {400.0, 263.0}), 1.0);
  const auto text = testing::runTool("pdftotext " + (dir / "fit.pdf").string() + " -");
  EXPECT_NE(text.output.find("scale 1:10"), std::string::npos) << text.output;
  EXPECT_NE(text.output.find("lamella sheet L01"), std::string::npos) << text.output;
}

TEST(PdfWriter, TiledSheetAtOneToOneOverIsoPages) {
  ASSERT_TRUE(testing::haveTool("pdfinfo"));
  // A4 landscape's drawing area is 277 x 176 mm: 2500 x 1250 takes 10 x 8 = 80 pages; portrait
  // (190 x 263) 14 x 5 = 70, the fewer.
  EXPECT_EQ(tilePageCount(bigSheet(), PaperSize::A4), 70);
  const auto dir = testing::scratchDir("pdf_writer_tile");
  std::ofstream(dir / "tile.pdf", std::ios::binary)
      << toPdf({bigSheet()}, SheetPdf::Tile, PaperSize::A4);
  const auto info = testing::runTool("pdfinfo " + (dir / "tile.pdf").string());
  EXPECT_NE(info.output.find("Pages:           70"), std::string::npos) << info.output;
  EXPECT_NE(info.output.find("(A4)"), std::string::npos) << info.output;
  const auto text = testing::runTool("pdftotext -f 1 -l 1 " + (dir / "tile.pdf").string() + " -");
  EXPECT_NE(text.output.find("scale 1:1"), std::string::npos) << text.output;
  EXPECT_NE(text.output.find("row 1 of 5, column 1 of 14"), std::string::npos) << text.output;
}

}  // namespace
}  // namespace egg::fabrication
