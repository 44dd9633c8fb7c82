// Generalised patches in the quad layout's cut-offs (issue 41): see infill.hpp.
#include "patching/infill.hpp"

#include "core/errors.hpp"
#include "core/geodesic/boundary_connections.hpp"
#include "core/timing.hpp"

#include <fmt/core.h>

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <map>
#include <numeric>
#include <set>
#include <string>

namespace egg::patching {
namespace {

// The faces as a mesh of their own, and each of its vertices' layout-mesh vertex.
TriMesh infillExtract(const TriMesh& mesh, const std::vector<int>& faces,
                      std::vector<int>& layoutVertex) {
  TriangleSoup soup;
  std::map<int, int> index;
  layoutVertex.clear();
  for (int f : faces) {
    std::array<int, 3> triangle{};
    const auto ids = faceVertices(mesh, f);
    for (int k = 0; k < 3; ++k) {
      auto [it, added] = index.emplace(ids[k], static_cast<int>(soup.vertices.size()));
      if (added) {
        soup.vertices.push_back(toEigen(mesh.point(TriMesh::VertexHandle(ids[k]))));
        layoutVertex.push_back(ids[k]);
      }
      triangle[k] = it->second;
    }
    soup.triangles.push_back(triangle);
  }
  return meshFromSoup(soup);
}

double infillLoopLength(const TriMesh& mesh, const std::vector<int>& loop) {
  double length = 0.0;
  for (size_t i = 0; i < loop.size(); ++i) {
    length += (toEigen(mesh.point(TriMesh::VertexHandle(loop[i]))) -
               toEigen(mesh.point(TriMesh::VertexHandle(loop[(i + 1) % loop.size()]))))
                  .norm();
  }
  return length;
}

// A ring (two boundary loops) cut into disks at its necks: the outer loop's local minima of the
// distance to the inner loop (within a sixteenth of the loop either way) that are narrower than
// the ring's mean width. Faces go to the sector about the inner loop's centre that their centroid
// lies in. Returns the face groups (indices into `faces`), or a reason in `failure`.
std::vector<std::vector<int>> infillSplitRing(const TriMesh& piece,
                                              const std::vector<std::vector<int>>& loops,
                                              std::string& failure) {
  const bool firstOuter = infillLoopLength(piece, loops[0]) >= infillLoopLength(piece, loops[1]);
  const auto& outer = loops[firstOuter ? 0 : 1];
  const auto& inner = loops[firstOuter ? 1 : 0];
  const auto at = [&](int v) { return toEigen(piece.point(TriMesh::VertexHandle(v))); };
  const int n = static_cast<int>(outer.size());
  std::vector<double> width(n, INFINITY);
  std::vector<int> nearest(n, -1);
  for (int i = 0; i < n; ++i) {
    for (int v : inner) {
      const double d = (at(outer[i]) - at(v)).norm();
      if (d < width[i]) width[i] = d, nearest[i] = v;
    }
  }
  const double mean = std::accumulate(width.begin(), width.end(), 0.0) / n;
  const int window = std::max(3, n / 16);
  std::vector<int> necks;
  for (int i = 0; i < n; ++i) {
    if (!(width[i] < mean)) continue;
    bool minimum = true;
    for (int k = -window; k <= window && minimum; ++k) {
      const int j = ((i + k) % n + n) % n;
      // Ties go to the first index, so a flat neck counts once.
      minimum = width[j] > width[i] || (width[j] == width[i] && (k >= 0));
    }
    if (minimum) necks.push_back(i);
  }
  if (necks.size() < 2) {
    failure = "a ring round a hole with fewer than two necks cannot be split into disks";
    return {};
  }
  // Sectors about the inner loop's centre, in the plane of least squares through it.
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();
  for (int v : inner) centre += at(v) / static_cast<double>(inner.size());
  Eigen::Matrix3d scatter = Eigen::Matrix3d::Zero();
  for (int v : inner) scatter += (at(v) - centre) * (at(v) - centre).transpose();
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eigen(scatter);
  const Eigen::Vector3d e1 = eigen.eigenvectors().col(2), e2 = eigen.eigenvectors().col(1);
  const auto angleOf = [&](const Eigen::Vector3d& p) {
    return std::atan2(e2.dot(p - centre), e1.dot(p - centre));
  };
  std::vector<double> cuts;
  for (int i : necks) cuts.push_back(angleOf(0.5 * (at(outer[i]) + at(nearest[i]))));
  std::sort(cuts.begin(), cuts.end());
  std::vector<std::vector<int>> groups(cuts.size());
  for (auto fh : piece.faces()) {
    Eigen::Vector3d c = Eigen::Vector3d::Zero();
    for (int v : faceVertices(piece, fh.idx())) c += at(v) / 3.0;
    const double a = angleOf(c);
    // The sector [cuts[k], cuts[k+1]); below the first cut: the last sector (it wraps round).
    int k = static_cast<int>(std::upper_bound(cuts.begin(), cuts.end(), a) - cuts.begin()) - 1;
    if (k < 0) k = static_cast<int>(cuts.size()) - 1;
    groups[k].push_back(fh.idx());
  }
  return groups;
}

// Lines per family so that the layout's spacing matches the quad grids': the larger side of the
// piece's plan box over the spacing.
int infillLines(const generalised::GridDomain& domain, const InfillOptions& options) {
  Eigen::AlignedBox2d box;
  for (const auto& p : domain.projectedBoundary()) box.extend(p);
  const double extent = box.sizes().maxCoeff();
  return std::clamp(static_cast<int>(std::lround(extent / options.memberSpacingM)),
                    options.minLines, options.maxLines);
}

void infillDesign(const PatchLayout& layout, const std::set<int>& sideVertices,
                  const InfillOptions& options, InfillPiece& piece) {
  const Stopwatch clock;
  try {
    const generalised::GridDomain domain(piece.mesh);
    piece.precomputeSeconds = domain.precomputeSeconds();
    auto optimisation = options.optimisation;
    // At the quad grids' spacing first; a narrow piece (a strip along a curved edge) may take a
    // grid only with fewer lines, whose members then cross inside it.
    for (int lines = infillLines(domain, options);;
         lines = std::max(options.minLines, lines * 3 / 4)) {
      optimisation.lines = {lines, lines};
      try {
        piece.optimisation = generalised::optimiseGrid(domain, optimisation);
        break;
      } catch (const InvalidInput&) {
        if (lines == options.minLines) throw;
      }
    }
    piece.design =
        generalised::designGeneralisedGrid(domain, piece.optimisation->layout, options.design);
    // The optimiser judged the angles at the field crossings; the traced ones decide.
    if (piece.design->minCrossingAngleRad < options.optimisation.minCrossingAngleRad) {
      throw InvalidInput(fmt::format(
          "left as a cut-off: its best grid has lamellas crossing at {:.1f} degrees, below the "
          "{:.1f} a bolt needs",
          piece.design->minCrossingAngleRad * 180.0 / M_PI,
          options.optimisation.minCrossingAngleRad * 180.0 / M_PI));
    }
    const TriMesh& layoutMesh = layout.mesh.mesh;
    const auto holdOf = [&](int sample) {
      const int v = piece.layoutVertex[domain.vertex(sample)];
      if (layoutMesh.is_boundary(TriMesh::VertexHandle(v))) return AnchorHold::DesignBoundary;
      return sideVertices.count(v) ? AnchorHold::PatchSide : AnchorHold::Cut;
    };
    std::set<int> anchors;  // the pieces of a split member share their anchor on the bay
    for (const auto& m : piece.optimisation->layout.members) {
      anchors.insert({m.start, m.end});
      piece.memberEndHolds.push_back({holdOf(m.start), holdOf(m.end)});
    }
    for (int sample : anchors) {
      switch (holdOf(sample)) {
        case AnchorHold::DesignBoundary: ++piece.anchorsOnDesignBoundary; break;
        case AnchorHold::PatchSide: ++piece.anchorsOnPatchSides; break;
        case AnchorHold::Cut: ++piece.anchorsOnCuts; break;
      }
    }
  } catch (const InvalidInput& e) {
    piece.failure = e.what();
    piece.optimisation.reset();
    piece.design.reset();
    piece.memberEndHolds.clear();
  }
}

}  // namespace

const char* toString(AnchorHold hold) {
  switch (hold) {
    case AnchorHold::DesignBoundary: return "design_boundary";
    case AnchorHold::PatchSide: return "patch_side";
    case AnchorHold::Cut: return "cut";
  }
  return "?";
}

void InfillOptions::validate() const {
  if (!(minAreaM2 >= 0.0)) throw InvalidInput("InfillOptions.min_area_m2 must be >= 0");
  if (!(memberSpacingM > 0.0) || !std::isfinite(memberSpacingM))
    throw InvalidInput("InfillOptions.member_spacing_m must be positive");
  if (minLines < 2 || maxLines < minLines)
    throw InvalidInput("InfillOptions: need 2 <= min_lines <= max_lines");
  optimisation.validate();
  design.validate();
}

InfillResult infillCutOffs(const PatchLayout& layout, const Coverage& coverage,
                           const InfillOptions& options) {
  options.validate();
  const Stopwatch clock;
  const TriMesh& layoutMesh = layout.mesh.mesh;
  std::set<int> sideVertices;
  for (const auto& chain : layout.mesh.chains) sideVertices.insert(chain.begin(), chain.end());
  InfillResult result;
  for (size_t c = 0; c < coverage.cutOffs.size(); ++c) {
    const auto& cut = coverage.cutOffs[c];
    if (cut.areaM2 < options.minAreaM2) {
      InfillPiece piece;
      piece.cutOff = static_cast<int>(c);
      piece.layoutFaces = cut.faces;
      piece.areaM2 = cut.areaM2;
      piece.failure = fmt::format(
          "left as a cut-off: {:.2f} m^2 is below the {:.2f} m^2 a generalised patch needs",
          cut.areaM2, options.minAreaM2);
      result.pieces.push_back(std::move(piece));
      continue;
    }
    std::vector<std::vector<int>> groups = {cut.faces};
    std::vector<int> layoutVertex;
    const TriMesh whole = infillExtract(layoutMesh, cut.faces, layoutVertex);
    const auto loops = geodesic::boundaryLoops(whole);
    std::string failure;
    if (loops.size() == 2) {
      groups.clear();
      for (const auto& group : infillSplitRing(whole, loops, failure)) {
        std::vector<int> faces;
        for (int f : group) faces.push_back(cut.faces[f]);
        groups.push_back(std::move(faces));
      }
    } else if (loops.size() != 1) {
      failure = fmt::format("the cut-off has {} boundary loops (a region round several holes)",
                            loops.size());
    }
    if (!failure.empty()) {
      InfillPiece piece;
      piece.cutOff = static_cast<int>(c);
      piece.layoutFaces = cut.faces;
      piece.areaM2 = cut.areaM2;
      piece.failure = failure;
      result.pieces.push_back(std::move(piece));
      continue;
    }
    for (auto& faces : groups) {
      InfillPiece piece;
      piece.cutOff = static_cast<int>(c);
      piece.layoutFaces = std::move(faces);
      piece.mesh = infillExtract(layoutMesh, piece.layoutFaces, piece.layoutVertex);
      piece.areaM2 = surfaceArea(piece.mesh);
      result.pieces.push_back(std::move(piece));
    }
  }
  // The pieces are independent; each one's optimisation is parallel inside (TBB).
  for (auto& piece : result.pieces) {
    if (!piece.failure.empty()) continue;
    infillDesign(layout, sideVertices, options, piece);
    if (piece.design) result.designedAreaM2 += piece.areaM2;
  }
  result.seconds = clock.seconds();
  return result;
}

}  // namespace egg::patching
