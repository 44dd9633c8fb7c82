#pragma once
// Isotropic remeshing in the parameter domain, measured in 3D (Botsch & Kobbelt 2004: split long
// edges, collapse short ones, flip toward Delaunay, tangential smoothing). Every vertex stays an
// exact evaluation of the surface map, so remeshing never moves a vertex off the analytic surface.
#include "core/mesh/mesh.hpp"
#include "samples/generators/surface_spec.hpp"

#include <array>
#include <vector>

namespace egg::samples::detail {

struct RemeshOptions {
  double targetEdge = 1.0;  // wanted 3D edge length (m)
  int iterations = 6;       // split / collapse / flip / smooth rounds
  int finalSmoothing = 4;   // extra flip + smooth rounds without changing the vertex count
};

struct DomainMesh {
  std::vector<Vec2> domain;                   // parameter-domain position of every vertex
  std::vector<bool> locked;                   // never moved nor removed (corners, samples, spots)
  std::vector<std::array<int, 3>> triangles;  // counter-clockwise in the domain
};

// Remeshes `input` (a valid, counter-clockwise domain triangulation). Boundary vertices never move;
// unlocked boundary vertices may be collapsed into a boundary neighbour. Returns the 3D soup,
// oriented by spec.reverseOrientation.
TriangleSoup remeshInDomain(const SurfaceSpec& spec, const DomainMesh& input,
                            const RemeshOptions& options);

}  // namespace egg::samples::detail
