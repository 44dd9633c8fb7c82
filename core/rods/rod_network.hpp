#pragma once
// Input of the rod simulation (Section 2.5): the lamellas of a grid as straight elastic rods, the
// bolts that join them, the notches the bolts may slide in, and the anchors/supports that hold the
// deployed grid in place. The grid stage (core/egg) fills it from its members, connections,
// notches and anchors; nothing here depends on how the grid was designed.
//
// Units: metres, pascals, kilograms per cubic metre. Arc lengths `s` are measured along the
// straight (planar, as cut) lamella from its first end, so 0 <= s <= length_m.
#include <Eigen/Core>

#include <optional>
#include <vector>

namespace egg::rods {

// Rectangular lamella section w x t (width in the surface's tangent plane, thickness along the
// surface normal). Stiffnesses follow from it (rod_model.hpp): EI weak = E w t^3/12,
// EI strong = E t w^3/12, GJ with J = w t^3/3 (thin strip).
struct CrossSection {
  double widthM = 0.25;
  double thicknessM = 0.04;
};

// Linear elastic, isotropic material.
struct Material {
  double youngsModulusPa = 10.0e9;  // E
  double shearModulusPa = 0.6e9;    // G (wood is far softer in shear than E/2.6)
  double densityKgM3 = 500.0;       // only used when the simulation adds gravity
};

// One lamella: straight at rest (it is cut straight, Section 2.3.1), of the given planar length.
struct Rod {
  double lengthM = 0.0;
  CrossSection section;
  Material material;
  // The two families lie in two layers bolted face to face: layer 0 below, layer 1 on top (along
  // the surface normal). The design surface is the contact plane between the layers, so a rod's
  // centreline lies t/2 below (layer 0) or above (layer 1) the surface.
  int layer = 0;
  // Initial deployed guess: a polyline ON the design surface (e.g. the traced geodesic), from
  // s = 0 to s = length_m (its own length may differ slightly; it is reparametrised
  // proportionally), and the unit surface normal at each of its points (same size, pointing to
  // the side of layer 1). The simulation resamples both onto its own vertices.
  std::vector<Eigen::Vector3d> guess;
  std::vector<Eigen::Vector3d> guessNormals;
};

// The elongated hole (notch, Section 2.4.5) of one rod at a bolt: the bolt may slide from
// s - before_m to s + after_m along the rod. The grid's notch length l = s - s_bar gives
// after_m = l when l > 0, before_m = -l when l < 0. Both zero (default): a plain hole.
struct Notch {
  double beforeM = 0.0;
  double afterM = 0.0;
};

// A bolt joining rod a (in layer 0) and rod b (in layer 1) where they cross (Section 2.5, E_q).
// The rods may rotate about the common normal; with notches enabled the bolt may slide along
// each rod within its notch (E_n), with pseudo-friction (E_p).
struct Connection {
  int rodA = -1;
  double sAM = 0.0;  // bolt position along rod a in the planar grid
  int rodB = -1;
  double sBM = 0.0;  // bolt position along rod b in the planar grid
  Notch notchA;      // notch in rod a (zero: plain hole)
  Notch notchB;      // notch in rod b
  // Where a sliding bolt starts along rod a / rod b: a previous equilibrium's position (the joined
  // run starts every bolt where its patch's own run left it, startFrom in simulation.hpp). Empty:
  // where the two guess curves cross within the notch. Ignored for a plain hole.
  std::optional<double> startAM, startBM;
};

// A point of a rod held at a point of the design surface with the lamella normal along the given
// surface normal: the anchors of Section 2.4.6 (E_a) and the supports of Section 3.5.3 (a point
// and its tangent plane, given by the plane's normal) are the same constraint.
struct Anchor {
  int rod = -1;
  double sM = 0.0;           // where along the rod
  Eigen::Vector3d position;  // on the design surface
  Eigen::Vector3d normal;    // unit surface normal there (towards layer 1)
};

struct RodNetwork {
  std::vector<Rod> rods;
  std::vector<Connection> connections;
  std::vector<Anchor> anchors;
};

// Throws InvalidInput naming the offending rod/connection/anchor (bad indices, lengths,
// positions or notches outside a rod, negative notch lengths, both rods in the same layer,
// guess polylines with fewer than 2 points or mismatched normals).
void validateNetwork(const RodNetwork& network);

}  // namespace egg::rods
