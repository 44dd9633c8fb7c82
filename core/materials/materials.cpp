#include "core/materials/materials.hpp"

#include "core/errors.hpp"

namespace egg {

const std::vector<MaterialProperties>& materialCatalog() {
  // E and rho of the three timbers are the thesis' measured values (Table 3.2). Their shear moduli
  // are not given there; timber's G along the grain is about E/16 (EN 338 mean values, e.g. C24:
  // E = 11 GPa, G = 0.69 GPa), which we use for them. Strengths (f_m bending, f_v shear) are not in
  // the thesis either; they are literature values, conservative (characteristic where a standard
  // gives one), and only feed the stress check's ratio:
  //  - limewood: Tilia cordata, bending strength 85 MPa, shear 8 MPa (lower end of the ranges in
  //    Wagenfuehr, Holzatlas, 6th ed. 2007; Wood Handbook FPL-GTR-190 gives 60 MPa for basswood).
  //  - birch plywood with the face grain across the lamella: thin 3-ply birch, f_m across the face
  //    grain 10 MPa, panel shear 9.5 MPa (Handbook of Finnish Plywood, Finnish Forest Industries
  //    Federation 2002, characteristic values of 3-ply panels).
  //  - poplar plywood, face grain along: f_m 40 MPa, panel shear 5 MPa (EN 12369-1 class values as
  //    declared by poplar plywood producers; an estimate for the thesis' 3 mm 3-ply board).
  //  - GFRP: pultruded profile grade E23 of EN 13706-3 (E >= 23 GPa, flexural strength >= 240 MPa,
  //    interlaminar shear >= 25 MPa), G ~ 3 GPa and rho ~ 1850 kg/m^3 (typical pultrusion
  //    datasheets).
  //  - spruce C24: EN 338:2016 (f_m,k 24 MPa, f_v,k 4.0 MPa).
  //  - steel S235: EN 1993-1-1 3.2.6 (E, G), f_y = 235 MPa, shear f_y / sqrt(3) (von Mises).
  static const std::vector<MaterialProperties> catalog{
      {"poplar_plywood",
       "poplar plywood, face grain along the lamella (the thesis' showcase model)", 7.6e9,
       7.6e9 / 16.0, 430.0, 40e6, 5e6,
       "thesis Table 3.2 (E, rho); G = E/16 after EN 338; f_m, f_v after EN 12369-1 (estimate)"},
      {"birch_plywood",
       "birch plywood with the face grain across the lamella (the thesis' failed model)", 4.0e9,
       4.0e9 / 16.0, 650.0, 10e6, 9.5e6,
       "thesis Table 3.2 (E, rho); G = E/16 after EN 338; f_m, f_v: Handbook of Finnish Plywood"},
      {"limewood", "solid lime wood (the thesis' small-scale prototype)", 9.1e9, 9.1e9 / 16.0,
       500.0, 85e6, 8e6,
       "thesis Table 3.2 (E, rho); G = E/16 after EN 338; f_m, f_v: Wagenfuehr, Holzatlas (lower "
       "bounds)"},
      {"gfrp", "glass-fibre reinforced polymer, pultruded strip (EN 13706 grade E23)", 23.0e9,
       3.0e9, 1850.0, 240e6, 25e6,
       "EN 13706-3 grade E23 minima (E, f_m, interlaminar shear); G, rho typical pultrusion "
       "datasheets"},
      {"spruce_c24", "structural softwood strength class C24", 11.0e9, 0.69e9, 420.0, 24e6, 4.0e6,
       "EN 338:2016 mean values (E, G), characteristic f_m,k, f_v,k"},
      {"steel_s235", "structural steel S235", 210.0e9, 81.0e9, 7850.0, 235e6,
       235e6 / 1.7320508075688772, "EN 1993-1-1 3.2.6; f_y = 235 MPa, shear f_y / sqrt(3)"},
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
