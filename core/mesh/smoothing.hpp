#pragma once
// Implicit fairing (Desbrun, Meyer, Schroeder and Barr 1999): one backward-Euler step of mean
// curvature flow with the cotangent Laplacian, (M + t L) X' = M X, boundary vertices held fixed.
// Section 2.3.3 smooths a patch "with cotangent weights iteratively until eta falls below eta_max"
// (the P1 fallback when a Gaussian-curvature peak leaves an area no shortest geodesic reaches);
// the caller repeats smoothMeshStep and re-measures eta. The implicit step is stable for any
// strength, and the cotangent weights move vertices only normal to the surface (a flat region
// stays put), unlike uniform weights, which also slide vertices tangentially.
#include "core/mesh/mesh.hpp"

#include <functional>
#include <vector>

namespace egg {

enum class LaplacianWeights {
  Cotangent,  // mean curvature flow (the thesis' choice)
  Uniform,    // umbrella operator, for comparison only: drifts vertices tangentially
};

enum class FairingSolver {
  Auto,               // Cholesky up to 100 000 free vertices, conjugate gradients beyond
  Cholesky,           // sparse LDL^T (Eigen SimplicialLDLT): exact, fast for patch-sized meshes
  ConjugateGradient,  // Jacobi-preconditioned CG, warm-started at the current positions: the
                      // system is well conditioned for moderate strengths, so it scales linearly
};

struct SmoothingOptions {
  // Time step t of one step, in units of the squared mean edge length (dimensionless). About
  // strength / 4 of the way to the neighbours' average per step on a regular mesh.
  double strength = 1.0;
  // Which Laplacian.
  LaplacianWeights weights = LaplacianWeights::Cotangent;
  // Keep boundary vertices where they are (the patch boundary is a traced geodesic).
  bool fixBoundary = true;
  // Further vertices to keep fixed (e.g. patch corners), by index.
  std::vector<int> fixedVertices;
  // Linear solver of the implicit step.
  FairingSolver solver = FairingSolver::Auto;
  // Relative residual at which conjugate gradients stop.
  double cgTolerance = 1e-12;

  void validate() const;  // throws InvalidInput naming the field
};

struct SmoothingResult {
  TriMesh mesh;                    // the smoothed mesh (same connectivity)
  double maxDisplacementM = 0.0;   // largest vertex move of this step
  double meanDisplacementM = 0.0;  // mean over all vertices (fixed ones count as 0)
  int fixedVertices = 0;           // vertices held in place
  double timeStepM2 = 0.0;         // t in metres squared
  bool usedCholesky = true;        // which solver ran
  int iterations = 0;     // conjugate-gradient iterations (largest of x, y, z; 0 for Cholesky)
  double residual = 0.0;  // relative residual of the solve (CG estimate; 0 for Cholesky)
  double seconds = 0.0;
};

// One implicit fairing step. Throws InvalidInput for bad options or an empty mesh, SolverFailure if
// the (symmetric positive definite) system cannot be factorised.
SmoothingResult smoothMeshStep(const TriMesh& mesh, const SmoothingOptions& options = {});

struct SmoothingLoopResult {
  TriMesh mesh;                           // the mesh after the last step (the input if none ran)
  int steps = 0;                          // steps taken
  bool satisfied = false;                 // `done` returned true (possibly before any step)
  std::vector<double> maxDisplacementM;   // per step
  std::vector<double> meanDisplacementM;  // per step
  double totalMaxDisplacementM = 0.0;     // largest distance of any vertex from its start
  double seconds = 0.0;
};

// Section 2.3.3's loop: checks `done` on the input, then alternates one smoothMeshStep and a check,
// at most `maxSteps` times (e.g. done = "eta <= eta_max" with eta recomputed on the new mesh).
// Not satisfied after maxSteps is reported, not thrown: the caller decides (split the patch).
SmoothingLoopResult smoothUntil(const TriMesh& mesh,
                                const std::function<bool(const TriMesh&)>& done, int maxSteps,
                                const SmoothingOptions& options = {});

}  // namespace egg
