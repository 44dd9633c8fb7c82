#pragma once
// The sample meshing pipeline: boundary sampling, Delaunay refinement of the domain, isotropic
// remeshing measured in 3D.
#include "core/mesh/mesh.hpp"
#include "samples/generators/surface_spec.hpp"

namespace egg::samples::detail {

// Rough 3D area of the surface (coarse mesh), used to refuse absurd edge lengths before meshing.
double estimateArea(const SurfaceSpec& spec);

// 3D length of all boundary loops (dense polylines), for the same guard.
double boundaryLength(const SurfaceSpec& spec);

// Triangulates the surface with 3D edges of about `edgeLength`; boundary curve ends and required
// points are vertices, every vertex lies on the analytic surface. `expectedTriangles` (from
// estimateArea) bounds the refinement: far more vertices than that throws InvalidInput.
TriangleSoup meshSurface(const SurfaceSpec& spec, double edgeLength, double expectedTriangles);

}  // namespace egg::samples::detail
