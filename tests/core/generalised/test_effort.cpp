// Effort energy of grid members (Sections 4.6.1, 4.6.3): Euler's theorem, the closed-form effort
// of helices on a cylinder, and kappa_n read off sphere and cylinder meshes.
#include "core/generalised/effort.hpp"

#include "core/errors.hpp"
#include "samples/generators/samples.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

namespace egg::generalised {
namespace {

TEST(Effort, NormalCurvatureFollowsEulersTheorem) {
  const PrincipalCurvature c{0.5, -0.2, Eigen::Vector3d::UnitX()};
  for (double phi : {0.0, 0.3, M_PI / 4, 1.2, M_PI / 2}) {
    const Eigen::Vector3d t(std::cos(phi), std::sin(phi), 0.0);
    const double expected =
        0.5 * std::cos(phi) * std::cos(phi) - 0.2 * std::sin(phi) * std::sin(phi);
    EXPECT_NEAR(normalCurvature(c, t), expected, 1e-15);
    EXPECT_NEAR(normalCurvature(c, 3.0 * t), expected, 1e-15);  // the tangent's length is not used
    EXPECT_NEAR(normalCurvature({0.5, -0.2, -Eigen::Vector3d::UnitX()}, t), expected, 1e-15);
  }
  EXPECT_THROW(normalCurvature(c, Eigen::Vector3d::Zero()), InvalidInput);
}

// A helix on a cylinder of radius R whose tangent makes the angle phi with the circumference has
// kappa_n = cos^2(phi) / R all along, so E_c = cos^4(phi) / R^2 (Eq. 4.10); here with the
// polyline's own tangents (memberTangents), as grid members are evaluated.
TEST(Effort, AHelixOnACylinderHasTheClosedFormEffort) {
  const double radius = 2.0, length = 6.0;
  for (double phi : {0.0, 0.4, M_PI / 4, 1.1, M_PI / 2}) {
    std::vector<Eigen::Vector3d> points;
    std::vector<double> thetas;
    const int n = 400;
    for (int j = 0; j <= n; ++j) {
      const double s = length * j / n, theta = s * std::cos(phi) / radius;
      points.emplace_back(s * std::sin(phi), radius * std::sin(theta), radius * std::cos(theta));
      thetas.push_back(theta);
    }
    const auto tangents = memberTangents(points);
    std::vector<double> kappaN;
    for (int j = 0; j <= n; ++j) {
      const Eigen::Vector3d circumferential(0.0, std::cos(thetas[j]), -std::sin(thetas[j]));
      kappaN.push_back(normalCurvature({1.0 / radius, 0.0, circumferential}, tangents[j]));
    }
    const double expected = std::pow(std::cos(phi), 4) / (radius * radius);
    EXPECT_NEAR(memberEffort(points, kappaN), expected, 1e-4 / (radius * radius)) << phi;
  }
}

double interiorKappaN(const TriMesh& mesh, const CurvatureField& field, int face,
                      const Eigen::Vector3d& direction) {
  return normalCurvatureAt(mesh, field, {face, Eigen::Vector3d::Constant(1.0 / 3.0)}, direction);
}

// Faces with no vertex on the boundary or next to it (the fits there are one-sided).
std::vector<int> innerFaces(const TriMesh& mesh, const CurvatureField& field) {
  std::vector<int> faces;
  for (auto f : mesh.faces()) {
    bool inner = true;
    for (auto v : mesh.fv_range(f)) {
      for (auto w : mesh.vv_range(v)) inner = inner && !field.onBoundary[w.idx()];
      inner = inner && !field.onBoundary[v.idx()];
    }
    if (inner) faces.push_back(f.idx());
  }
  return faces;
}

TEST(Effort, OnASphereMeshEveryDirectionBendsByOneOverTheRadius) {
  const TriMesh mesh = samples::generateSample("sphere", {{"radius", 10.0}, {"extent", 7.0}}, 0.7);
  const CurvatureField field = computeCurvature(mesh);
  const std::vector<int> faces = innerFaces(mesh, field);
  ASSERT_GT(faces.size(), 100u);
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (size_t k = 0; k < faces.size(); k += faces.size() / 40) {
    const Eigen::Vector3d direction(u(rng), u(rng), u(rng));  // projected by normalCurvatureAt
    EXPECT_NEAR(interiorKappaN(mesh, field, faces[k], direction), 0.1, 0.002) << faces[k];
  }
}

TEST(Effort, OnACylinderMeshTheAxisIsStraightAndTheCircumferenceBent) {
  const double radius = 4.0;
  const TriMesh mesh = samples::generateSample(
      "cylinder", {{"radius", radius}, {"length", 10.0}, {"angle", 2.0}}, 0.4);
  const CurvatureField field = computeCurvature(mesh);
  const std::vector<int> faces = innerFaces(mesh, field);
  ASSERT_GT(faces.size(), 100u);
  for (size_t k = 0; k < faces.size(); k += faces.size() / 20) {
    const auto f = mesh.face_handle(faces[k]);
    Eigen::Vector3d centre = Eigen::Vector3d::Zero();
    for (auto v : mesh.fv_range(f)) {
      const auto& p = mesh.point(v);
      centre += Eigen::Vector3d(p[0], p[1], p[2]) / 3.0;
    }
    const double theta = std::atan2(centre.y(), centre.z());
    const Eigen::Vector3d axial = Eigen::Vector3d::UnitX();
    const Eigen::Vector3d around(0.0, std::cos(theta), -std::sin(theta));
    EXPECT_NEAR(interiorKappaN(mesh, field, faces[k], axial), 0.0, 0.02 / radius);
    EXPECT_NEAR(interiorKappaN(mesh, field, faces[k], around), 1.0 / radius, 0.02 / radius);
    EXPECT_NEAR(interiorKappaN(mesh, field, faces[k], axial + around), 0.5 / radius, 0.02 / radius);
  }
}

TEST(Effort, GridEffortEnergyIsMinusTheSpreadOfTheMembersEfforts) {
  EXPECT_DOUBLE_EQ(gridEffortEnergy({1.0, 2.0, 3.0}), -2.0);
  EXPECT_DOUBLE_EQ(gridEffortEnergy({0.5, 0.5}), 0.0);
  EXPECT_DOUBLE_EQ(gridEffortEnergy({0.7}), 0.0);
  // Spreading the efforts apart lowers the energy: least- and most-effort members are favoured.
  EXPECT_LT(gridEffortEnergy({0.0, 1.0, 2.0}), gridEffortEnergy({0.9, 1.0, 1.1}));
}

TEST(Effort, BadMembersNameThePoints) {
  try {
    memberTangents({Eigen::Vector3d::Zero(), Eigen::Vector3d::UnitX(), Eigen::Vector3d::UnitX()});
    FAIL() << "no error";
  } catch (const InvalidInput& e) {
    EXPECT_NE(std::string(e.what()).find("points 1 and 2"), std::string::npos) << e.what();
  }
  EXPECT_THROW(memberEffort({Eigen::Vector3d::Zero()}, {0.0}), InvalidInput);
}

}  // namespace
}  // namespace egg::generalised
