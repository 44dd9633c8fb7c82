#pragma once
// The 3D model of the whole structure (issue 38) as plain data: the design surface, every lamella
// along its deployed centreline with its section, the bolts and the supports, all in site
// coordinates (metres, z up). The pipeline fills it (pipeline/model_stage.cpp); the writers of
// this folder turn it into glTF (glb_writer.hpp), Rhino 3dm (rhino_writer.hpp) and OBJ/STL
// (mesh_writers.hpp). Nothing here depends on how the grid was designed or deployed.
#include <Eigen/Core>

#include <map>
#include <string>
#include <vector>

namespace egg::exporter {

// Where the lamellas' centrelines come from, best first.
enum class CentrelineSource { JoinedSimulation, PatchSimulation, Grid };
// "joined simulation", "patch simulation", "grid (simulation off)".
const char* toString(CentrelineSource source);

struct ModelLamella {
  std::string id;  // "P<patch>-U<index>" / "P<patch>-V<index>", as on the cut sheets
  int patch = 0;
  char family = 'U';  // 'U' or 'V'
  int index = 0;
  bool boundary = false;
  double lengthM = 0.0;         // cut (planar) length, overhangs excluded
  double spatialLengthM = 0.0;  // the geodesic on the design surface
  std::string sheet;            // cut sheet of its first segment ("sheet_03"), empty if not cut
  int layer = 0;                // 0 below the design surface, 1 above (rod_network.hpp)
  // Centreline (m), the lamella's unit normal (the wide face's normal, towards layer 1) and the
  // distance of its contact side to the design surface at every point (m).
  std::vector<Eigen::Vector3d> centreline;
  std::vector<Eigen::Vector3d> normals;
  std::vector<double> deviationM;
};

struct ModelBolt {
  std::string id;  // "P<patch>-C<connection>"
  int patch = 0;
  Eigen::Vector3d position = Eigen::Vector3d::Zero();  // on the contact plane of the two layers
  Eigen::Vector3d axis = Eigen::Vector3d::UnitZ();     // unit, along the lamellas' normal
};

// A closed triangle mesh in site coordinates (metres).
struct ModelMesh {
  std::vector<Eigen::Vector3d> vertices;
  std::vector<Eigen::Vector3i> triangles;  // counter-clockwise seen from outside
};

struct ModelSupport {
  std::string id;  // "S001"
  int patch = 0;
  std::string connection;  // the connection it holds ("P0-C12")
  std::string kind;        // "block" or "bracket" (a bracket is listed, not modelled)
  Eigen::Vector3d position = Eigen::Vector3d::Zero();
  ModelMesh solid;  // empty for a bracket
};

struct StructureModel {
  std::string name;  // the scene's name
  ModelMesh surface;
  double widthM = 0.0, thicknessM = 0.0;  // lamella section
  double boltDiameterM = 0.0;
  CentrelineSource source = CentrelineSource::Grid;
  std::vector<int> patches;            // patch ids with lamellas, ascending
  std::vector<ModelLamella> lamellas;  // patch by patch, u then v
  std::vector<ModelBolt> bolts;
  std::vector<ModelSupport> supports;
  std::string supportsNote;  // why there are no supports (fabrication off), empty otherwise
  double maxDeviationM() const;
  // Throws InvalidInput naming the lamella/bolt/support whose data is inconsistent (mismatched
  // sizes, fewer than two points, zero normal, non-finite coordinates).
  void validate() const;
};

// The solid ribbon of one lamella: its w x t rectangle swept along the centreline (width across,
// in the plane of the wide face; thickness along the normal), with flat sides and end caps; per
// vertex the lamella point it belongs to (for colours). Four sides of two vertices per station
// and two caps: 8 n + 8 vertices, 8 (n - 1) + 4 triangles for n points.
struct Ribbon {
  ModelMesh mesh;
  std::vector<Eigen::Vector3d> normals;  // per vertex, unit (flat sides)
  std::vector<int> station;              // per vertex, index into the centreline
};
Ribbon ribbonOf(const ModelLamella& lamella, double widthM, double thicknessM);

// A bolt as a closed hexagonal prism of `diameterM` through both layers (2 t long).
ModelMesh boltSolid(const ModelBolt& bolt, double diameterM, double lengthM);
// Every bolt of the model as its solid (through both layers), merged into one mesh per patch:
// the OBJ and the 3dm write a patch's bolts as one object. Ordered by patch id.
std::map<int, ModelMesh> boltMeshesByPatch(const StructureModel& model);

// The colour of a deviation on the model's scale: 0 dark blue through green to yellow at maxM
// (viridis end points; a model without deviation is all one colour). Linear RGB in 0..1.
Eigen::Vector3d deviationColour(double deviationM, double maxM);

}  // namespace egg::exporter
