#include "core/materials/materials.hpp"

#include "core/errors.hpp"

#include <gtest/gtest.h>

namespace egg {
namespace {

TEST(Materials, ThesisTable32SpecificModuli) {
  // lambda = E / rho in 10^6 m^2/s^2: limewood 18.2, birch plywood 6.15, poplar plywood 17.7.
  EXPECT_NEAR(materialByName("limewood").youngs_modulus_pa / materialByName("limewood").density_kg_m3 / 1e6, 18.2, 0.05);
  EXPECT_NEAR(materialByName("birch_plywood").youngs_modulus_pa / materialByName("birch_plywood").density_kg_m3 / 1e6,
              6.15, 0.01);
  EXPECT_NEAR(materialByName("poplar_plywood").youngs_modulus_pa / materialByName("poplar_plywood").density_kg_m3 / 1e6,
              17.7, 0.05);
}

TEST(Materials, EveryEntryIsPhysical) {
  for (const auto& m : materialCatalog()) {
    EXPECT_GT(m.youngs_modulus_pa, 1e8) << m.name;
    EXPECT_GT(m.shear_modulus_pa, 0.0) << m.name;
    EXPECT_LT(m.shear_modulus_pa, m.youngs_modulus_pa / 2.0) << m.name;  // Poisson ratio > 0 bound
    EXPECT_GT(m.density_kg_m3, 100.0) << m.name;
    EXPECT_GT(m.bending_strength_pa, 1e6) << m.name;
    EXPECT_LT(m.bending_strength_pa, m.youngs_modulus_pa / 50.0) << m.name;  // strain at failure below 2 %
    EXPECT_GT(m.shear_strength_pa, 1e6) << m.name;
    EXPECT_FALSE(m.source.empty()) << m.name;
  }
}

TEST(Materials, TheIssueSixteenMaterialsAreThere) {
  for (const char* name : {"limewood", "birch_plywood", "poplar_plywood", "gfrp", "steel_s235"}) {
    EXPECT_NO_THROW(materialByName(name)) << name;
  }
  EXPECT_DOUBLE_EQ(materialByName("steel_s235").bending_strength_pa, 235e6);
}

TEST(Materials, UnknownNameListsTheKnownOnes) {
  try {
    materialByName("balsa");
    FAIL();
  } catch (const InvalidInput& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("balsa"), std::string::npos);
    EXPECT_NE(what.find("poplar_plywood"), std::string::npos);
  }
}

}  // namespace
}  // namespace egg
