#pragma once
// Lamella materials: stiffness and weight drive the deployed shape (Section 3.5.2: the specific
// modulus lambda = E / rho decides how far a scaled-up grid sags), so the simulation and the
// stress check read them from one table.
#include <string>
#include <vector>

namespace egg {

struct MaterialProperties {
  std::string name;  // scene key (lamella.material)
  std::string description;
  double youngsModulusPa = 0;  // E along the lamella
  double shearModulusPa = 0;   // G, for the torsion stiffness G J
  double densityKgM3 = 0;      // rho, for self-weight
  double bendingStrengthPa =
      0;  // f_m along the lamella: the stress check's limit for sigma = E kappa t / 2 (3.5.2)
  double shearStrengthPa = 0;  // f_v: the limit for the torsion shear stress G theta' t
  std::string source;          // where the numbers come from
};

// Every known material, in a stable order.
const std::vector<MaterialProperties>& materialCatalog();

// The material called `name`. Throws InvalidInput naming it and listing the known ones.
const MaterialProperties& materialByName(const std::string& name);

}  // namespace egg
