#include "core/materials/materials.hpp"

#include "core/errors.hpp"

#include <gtest/gtest.h>

namespace egg {
namespace {

TEST(Materials, ThesisTable32SpecificModuli) {
  // lambda = E / rho in 10^6 m^2/s^2: limewood 18.2, birch plywood 6.15, poplar plywood 17.7.
  EXPECT_NEAR(
      materialByName("limewood").youngsModulusPa / materialByName("limewood").densityKgM3 / 1e6,
      18.2, 0.05);
  EXPECT_NEAR(materialByName("birch_plywood").youngsModulusPa /
                  materialByName("birch_plywood").densityKgM3 / 1e6,
              6.15, 0.01);
  EXPECT_NEAR(materialByName("poplar_plywood").youngsModulusPa /
                  materialByName("poplar_plywood").densityKgM3 / 1e6,
              17.7, 0.05);
}

TEST(Materials, EveryEntryIsPhysical) {
  for (const auto& m : materialCatalog()) {
    EXPECT_GT(m.youngsModulusPa, 1e8) << m.name;
    EXPECT_GT(m.shearModulusPa, 0.0) << m.name;
    EXPECT_LT(m.shearModulusPa, m.youngsModulusPa / 2.0) << m.name;  // Poisson ratio > 0 bound
    EXPECT_GT(m.densityKgM3, 100.0) << m.name;
    EXPECT_GT(m.bendingStrengthPa, 1e6) << m.name;
    EXPECT_LT(m.bendingStrengthPa, m.youngsModulusPa / 50.0)
        << m.name;  // strain at failure below 2 %
    EXPECT_GT(m.shearStrengthPa, 1e6) << m.name;
    EXPECT_FALSE(m.source.empty()) << m.name;
  }
}

TEST(Materials, TheIssueSixteenMaterialsAreThere) {
  for (const char* name : {"limewood", "birch_plywood", "poplar_plywood", "gfrp", "steel_s235"}) {
    EXPECT_NO_THROW(materialByName(name)) << name;
  }
  EXPECT_DOUBLE_EQ(materialByName("steel_s235").bendingStrengthPa, 235e6);
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
