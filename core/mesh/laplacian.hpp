#pragma once
// Discrete Laplace operators on a triangle mesh. The cotangent Laplacian is the stiffness matrix of
// linear finite elements (Pinkall-Polthier 1993, Desbrun et al. 1999): symmetric positive
// semidefinite for any triangulation, zero on linear functions, so a flat mesh is its fixed point.
#include "core/mesh/mesh.hpp"

#include <Eigen/Sparse>

namespace egg {

// L with L_ij = -(cot alpha_ij + cot beta_ij) / 2 for every edge ij (one cotangent on a boundary
// edge) and L_ii = -sum_j L_ij. Then x^T L x is the Dirichlet energy of the piecewise linear x.
// Cotangents of faces with near-zero area are clamped to +-1e8 (validate.hpp rejects such faces).
Eigen::SparseMatrix<double> cotanLaplacian(const TriMesh& mesh);

// The same structure with every edge weight 1/sqrt(3) (the cotangent weight of an equilateral
// mesh), so both operators agree on a regular mesh and differ only where the mesh is irregular.
Eigen::SparseMatrix<double> uniformLaplacian(const TriMesh& mesh);

// Lumped mass: a third of the area of every incident face [m^2].
Eigen::VectorXd barycentricVertexAreas(const TriMesh& mesh);

// Mixed Voronoi areas (Meyer et al. 2003, Fig. 4): Voronoi region inside non-obtuse triangles,
// half / quarter of the triangle at / next to an obtuse angle. They tile the surface exactly and
// are the area over which L x = 2 H n A holds to second order (curvature, fairing).
Eigen::VectorXd mixedVoronoiAreas(const TriMesh& mesh);

}  // namespace egg
