#include "fabrication/assembly_drawings.hpp"

#include "tests/support/fabrication_hand_grid.hpp"
#include "tests/support/tool_run.hpp"

#include <fmt/format.h>
#include <gtest/gtest.h>

#include <fstream>
#include <map>
#include <regex>
#include <set>
#include <sstream>

namespace egg::fabrication {
namespace {

// A patch whose u lamellas converge to a 2 m side on the left and open to 30 m on the right, as
// at a corner of the Great Court's patches: 24 u and 61 v lamellas, 1,464 connections, so that
// at the page's scale the connections on the left are closer than their ids are long.
AssemblyPatch convergingPatch() {
  AssemblyPatch p;
  p.patchId = 3;
  constexpr int kU = 24, kV = 61;
  const auto uAt = [](int i, double x) {
    const double t = static_cast<double>(i) / (kU - 1);
    return 2.0 * t + (30.0 * t - 2.0 * t) * x / 60.0;
  };
  for (int i = 0; i < kU; ++i) {
    AssemblyMember m;
    m.id = "P3-U" + std::to_string(i);
    m.planarStart = {0.0, uAt(i, 0.0)};
    m.planarEnd = {60.0, uAt(i, 60.0)};
    m.deployed = {{0.0, uAt(i, 0.0), 0.0}, {30.0, uAt(i, 30.0), 6.0}, {60.0, uAt(i, 60.0), 0.0}};
    p.members.push_back(m);
  }
  for (int j = 0; j < kV; ++j) {
    const double x = 60.0 * j / (kV - 1);
    AssemblyMember m;
    m.id = "P3-V" + std::to_string(j);
    m.isU = false;
    m.planarStart = {x, 0.0};
    m.planarEnd = {x, uAt(kU - 1, x)};
    m.deployed = {{x, 0.0, 0.0}, {x, uAt(kU - 1, x), 6.0 * (1.0 - std::abs(x - 30.0) / 30.0)}};
    p.members.push_back(m);
  }
  for (int i = 0; i < kU; ++i) {
    for (int j = 0; j < kV; ++j) {
      const double x = 60.0 * j / (kV - 1);
      AssemblyConnection c;
      c.id = "P3-C" + std::to_string(i) + "-" + std::to_string(j);
      c.planar = {x, uAt(i, x)};
      c.spatial = {x, uAt(i, x), 6.0 * (1.0 - std::abs(x - 30.0) / 30.0)};
      if ((i + j) % 3 == 0) c.slideU = {0.05, 0.0};
      if ((i + j) % 4 == 0) c.slideV = {0.0, -0.05};
      p.connections.push_back(c);
    }
  }
  return p;
}

struct Word {
  double x0, y0, x1, y1;
  std::string text;
};

// The words of every page, with their boxes in points, as pdftotext -bbox reads them: an
// independent reader's idea of where the text is.
std::vector<std::vector<Word>> pdfWords(const std::filesystem::path& pdf) {
  const auto run = test::runTool("pdftotext -bbox " + pdf.string() + " -");
  std::vector<std::vector<Word>> pages;
  const std::regex word(
      R"re(<word xMin="([0-9.]+)" yMin="([0-9.]+)" xMax="([0-9.]+)" yMax="([0-9.]+)">([^<]*)</word>)re");
  std::istringstream lines(run.output);
  for (std::string line; std::getline(lines, line);) {
    if (line.find("<page ") != std::string::npos) pages.emplace_back();
    std::smatch m;
    if (!pages.empty() && std::regex_search(line, m, word))
      pages.back().push_back(
          {std::stod(m[1]), std::stod(m[2]), std::stod(m[3]), std::stod(m[4]), m[5]});
  }
  return pages;
}

// The patch pages of a converging grid: no two ids overlap as a PDF reader sees them, on the
// overview (1:200), the detail pages and the deployed view. On the overview and the deployed view
// every lamella id is there and every connection id is either there or counted as left out in the
// title band; the detail pages (1:100) carry nearly all that the overview left out. Before the
// layout the ids were drawn where they fell: 403 pairs overlapped on the planar page and 1,024 on
// the deployed one.
TEST(AssemblyDrawings, GeneralisedPatchesComeAfterThePatchesTheyBoltTo) {
  // P2 (a generalised patch, issue 41) bolts to P0's and P1's boundary lamellas: though it stands
  // on the most supports, it is deployed after both. P0 and P1 share a side; P1 has more supports.
  std::vector<AssemblyPatch> patches(3);
  patches[0].patchId = 2;
  patches[0].boltedTo = {0, 1};
  patches[1].patchId = 0;
  patches[2].patchId = 1;
  std::vector<Support> supports;
  for (int p : {2, 2, 2, 2, 1, 1, 0}) {
    Support s;
    s.patchId = p;
    supports.push_back(s);
  }
  SharedBoundary side;
  side.patchA = 0, side.patchB = 1;
  std::vector<std::string> reasons;
  EXPECT_EQ(assemblyOrder(patches, supports, {side}, &reasons), (std::vector<int>{1, 0, 2}));
  ASSERT_EQ(reasons.size(), 3u);
  EXPECT_EQ(reasons[0].rfind("P1 first", 0), 0u) << reasons[0];
  EXPECT_EQ(reasons[1].rfind("P0 after P1", 0), 0u) << reasons[1];
  EXPECT_EQ(
      reasons[2],
      "P2 after P0, P1: its member ends bolt to their boundary lamellas, which stand already");
}

TEST(AssemblyDrawings, IdsNeverOverlapWhereTheGridConvergesAndDetailPagesCarryTheRest) {
  FabricationResult r;
  r.assembly.push_back(convergingPatch());
  const auto dir = testing::scratchDir("assembly_drawings");
  std::ofstream(dir / "assembly.pdf", std::ios::binary) << assemblyPdf(r);
  const auto pages = pdfWords(dir / "assembly.pdf");
  const std::regex id(R"(P3-[UVC][0-9-]+)");
  std::set<std::string> connectionsAnywhere;
  int overviews = 0, details = 0, deployed = 0;
  for (size_t page = 0; page < pages.size(); ++page) {
    SCOPED_TRACE("page " + std::to_string(page + 1));
    std::vector<Word> ids;
    std::string band;
    for (const auto& w : pages[page]) {
      if (std::regex_match(w.text, id))
        ids.push_back(w);
      else
        band += w.text + " ";
    }
    if (band.find("patch P3:") == std::string::npos) continue;  // text pages, support plan
    int overlaps = 0;
    for (size_t a = 0; a < ids.size(); ++a)
      for (size_t b = a + 1; b < ids.size(); ++b) {
        const double dx = std::min(ids[a].x1, ids[b].x1) - std::max(ids[a].x0, ids[b].x0);
        const double dy = std::min(ids[a].y1, ids[b].y1) - std::max(ids[a].y0, ids[b].y0);
        if (dx > 0.05 && dy > 0.05) {
          if (++overlaps <= 3) ADD_FAILURE() << ids[a].text << " overlaps " << ids[b].text;
        }
      }
    EXPECT_EQ(overlaps, 0);
    std::map<std::string, int> seen;
    int connections = 0;
    for (const auto& w : ids) {
      ++seen[w.text];
      if (w.text.rfind("P3-C", 0) == 0) ++connections, connectionsAnywhere.insert(w.text);
    }
    if (band.find("bolted: detail") != std::string::npos) {
      ++details;
      EXPECT_NE(band.find("scale 1:100"), std::string::npos) << band;
      continue;
    }
    band.find("deployed") != std::string::npos ? ++deployed : ++overviews;
    for (const auto& m : r.assembly[0].members) EXPECT_GT(seen[m.id], 0) << m.id;
    std::smatch left;
    const int leftOut =
        std::regex_search(band, left, std::regex(R"(([0-9]+) of 1464 connection ids left out)"))
            ? std::stoi(left[1])
            : 0;
    EXPECT_EQ(connections + leftOut, 1464) << band;
    EXPECT_GT(connections, 700);  // most of them fit even here
  }
  EXPECT_EQ(overviews, 1);
  EXPECT_EQ(deployed, 1);
  EXPECT_GE(details, 2);
  // Every page an ISO A3 (the default paper), detail pages included.
  const auto info = test::runTool("pdfinfo -f 1 -l " + std::to_string(pages.size()) + " " +
                                  (dir / "assembly.pdf").string());
  int a3 = 0, sized = 0;
  std::istringstream lines(info.output);
  for (std::string line; std::getline(lines, line);) {
    if (line.rfind("Page ", 0) != 0 || line.find(" size:") == std::string::npos) continue;
    ++sized;
    if (line.find("(A3)") != std::string::npos) ++a3;
  }
  EXPECT_EQ(sized, static_cast<int>(pages.size())) << info.output;
  EXPECT_EQ(a3, sized) << info.output;
  // The overview is the key to them: each detail's window outlined and tagged.
  std::string overview;
  for (const auto& w : pages[1]) overview += w.text + " ";
  EXPECT_NE(overview.find(fmt::format("dashed: the {} detail pages that follow", details)),
            std::string::npos)
      << overview;
  for (int k = 1; k <= details; ++k)
    EXPECT_NE(overview.find(fmt::format("detail {} ", k)), std::string::npos) << k;
  EXPECT_GE(connectionsAnywhere.size(), 1450u);  // of 1,464 (1,453 when written)
}

}  // namespace
}  // namespace egg::fabrication
