#include "core/materials/materials.hpp"

#include "core/errors.hpp"

namespace egg {

const std::vector<MaterialProperties>& materialCatalog() {
  // E and rho of the three timbers are the thesis' measured values (Table 3.2). Their shear moduli
  // are not given there; timber's G along the grain is about E/16 (EN 338 mean values, e.g. C24:
  // E = 11 GPa, G = 0.69 GPa), which we use for them.
  static const std::vector<MaterialProperties> catalog{
      {"poplar_plywood", "poplar plywood, face grain along the lamella (the thesis' showcase model)", 7.6e9,
       7.6e9 / 16.0, 430.0, "thesis Table 3.2 (E, rho); G = E/16 after EN 338"},
      {"birch_plywood", "birch plywood with the face grain across the lamella (the thesis' failed model)", 4.0e9,
       4.0e9 / 16.0, 650.0, "thesis Table 3.2 (E, rho); G = E/16 after EN 338"},
      {"limewood", "solid lime wood (the thesis' small-scale prototype)", 9.1e9, 9.1e9 / 16.0, 500.0,
       "thesis Table 3.2 (E, rho); G = E/16 after EN 338"},
      {"spruce_c24", "structural softwood strength class C24", 11.0e9, 0.69e9, 420.0, "EN 338:2016 mean values"},
      {"steel_s235", "structural steel S235", 210.0e9, 81.0e9, 7850.0, "EN 1993-1-1 3.2.6"},
  };
  return catalog;
}

const MaterialProperties& materialByName(const std::string& name) {
  for (const auto& m : materialCatalog()) {
    if (m.name == name) return m;
  }
  std::string known;
  for (const auto& m : materialCatalog()) known += (known.empty() ? "" : ", ") + m.name;
  throw InvalidInput("unknown material \"" + name + "\" (known: " + known + ")");
}

}  // namespace egg
