#pragma once
// The deployed grid as a CalculiX beam model (issue 37; the thesis asks for FE beyond the rod
// model for large grids, 3.7.1): every lamella as quadratic beam elements (B32R) along its deployed
// centreline with its rectangular section turned as the lamella is, bolts as short steel beams
// between the two lamellas' centrelines, supports as the anchors the rod simulation held. The model
// is stress-free in its deployed shape: the deployment's bending stress is added in the check
// (structural_check.hpp), not carried by ccx. docs/verification.md states every modelling choice.
#include <Eigen/Core>

#include <array>
#include <string>
#include <vector>

namespace egg::verification {

struct FeMaterial {
  std::string name;  // *MATERIAL name (letters, digits, underscores)
  double youngsModulusPa = 0.0;
  // 0 by default: ccx expands a beam into 20-node bricks, which a nonzero nu stiffens like a plate
  // (a 250 x 40 mm strip by ~4 %, measured); the rods of the simulation have no such effect.
  double poissonRatio = 0.0;
  double densityKgM3 = 0.0;
  double bendingStrengthPa = 0.0;  // f_m: the utilisation's limit (0 for the bolts' steel)
};

// A deployed lamella: its centreline vertices (uniform in rest arc length, as the rod simulation
// discretises it) and at each the unit lamella normal (the thickness direction).
struct FeLamella {
  std::string name;   // NSET/ELSET name, e.g. P2_L7 (patch 2, lamella 7)
  std::string group;  // ELSET collecting it with others (the patch, "P2"); empty: none
  int material = 0;   // index into FeModel::materials
  double restLengthM = 0.0;
  double widthM = 0.0;
  double thicknessM = 0.0;
  std::vector<Eigen::Vector3d> centreline;
  std::vector<Eigen::Vector3d> normals;
};

// A point of a lamella by rest arc length from its first end (0 .. restLengthM).
struct FeAt {
  int lamella = -1;
  double sM = 0.0;
};

// A bolt between two lamellas' centrelines (lower: layer 0, upper: layer 1).
struct FeBolt {
  std::string name;  // e.g. C12 or J3 (a join between patches)
  FeAt lower, upper;
};

enum class SupportKind {
  // Translations fixed at the lamella's node (only the directions in `fixed`); rotations free.
  // Only at a node no other beam meets.
  Pin,
  // Translations fixed and rotations about every axis across `axis` held; free about `axis`:
  // the rod simulation's anchor (a point and the surface normal, Section 2.4.6 / 3.5.3).
  Hinge,
  // Everything fixed (a hinge about `axis` plus the rotation about it held through `secondAxis`).
  Clamp,
};
const char* toString(SupportKind kind);

struct FeSupport {
  std::string name;
  FeAt at;
  SupportKind kind = SupportKind::Hinge;
  Eigen::Vector3d axis = Eigen::Vector3d::UnitZ();        // Hinge, Clamp
  Eigen::Vector3d secondAxis = Eigen::Vector3d::UnitY();  // Clamp: across axis
  std::array<bool, 3> fixed{true, true, true};            // Pin: x, y, z
};

struct FeModel {
  std::vector<FeMaterial> materials;
  std::vector<FeLamella> lamellas;
  std::vector<FeBolt> bolts;
  std::vector<FeSupport> supports;
  double boltDiameterM = 0.012;                                 // M12 through bolts
  FeMaterial boltMaterial{"BOLT_STEEL", 210e9, 0.3, 0.0, 0.0};  // massless, as in the simulation
  double gravityMPerS2 = 9.81;
  void validate() const;  // throws InvalidInput naming the lamella/bolt/support
};

// The mesh ccx gets: node and element ids are 1-based indices into these vectors.
struct FeMesh {
  enum class Part { Lamella, Bolt, SupportArm };
  struct Element {
    std::array<int, 3> nodes{};  // end, middle, end (B32R order)
    Part part = Part::Lamella;
    int owner = -1;                // lamella, bolt or support index
    Eigen::Vector3d sectionAxis1;  // the section's 1-axis (lamella: its normal, thickness t)
    double lengthM = 0.0;          // along the element's three nodes
    std::array<double, 2> sM{};    // lamellas: rest arc length of its two end nodes
  };
  std::vector<Eigen::Vector3d> nodes;
  std::vector<Element> elements;
  std::vector<std::vector<int>> lamellaNodes;  // per lamella: its end nodes in order
  std::vector<std::vector<int>> vertexNodes;   // per lamella, per centreline vertex: node or 0
  std::vector<std::array<int, 2>> boltNodes;   // per bolt: lower, upper lamella node
  std::vector<int> supportNodes;               // per support: the lamella node it holds
  std::vector<int> reactionNodes;              // nodes with *BOUNDARY (arm ends, pins)
  std::vector<int> reactionSupport;            // per reaction node: its support
};

// Nodes at every centreline vertex, bolt and support (a vertex closer than 0.3 edge to a bolt or
// support gives way to it, so no element is shorter than 0.3 edges), 3-node elements between.
FeMesh buildMesh(const FeModel& model);

// The model without steps: nodes, elements, sets by lamella/group/bolt/support, materials, one
// *BEAM SECTION per lamella element (the section turns with the lamella; ccx 2.20 ignores *NORMAL
// on beams, measured), boundary conditions.
std::string modelInp(const FeModel& model, const FeMesh& mesh);

}  // namespace egg::verification
