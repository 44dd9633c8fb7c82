#include "fabrication/stickers.hpp"

#include "tests/support/fabrication_hand_grid.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace egg::fabrication {
namespace {

TEST(Stickers, ContactHalfLengthOfTwoCrossingStrips) {
  EXPECT_NEAR(contactHalfLengthMm(10.0, M_PI / 2.0), 5.0, 1e-12);  // a square
  EXPECT_NEAR(contactHalfLengthMm(10.0, M_PI / 3.0), 5.0 * std::sqrt(3.0),
              1e-12);  // w (1 + 1/2) / (2 sin 60)
  EXPECT_NEAR(contactHalfLengthMm(10.0, 2.0 * M_PI / 3.0), 5.0 * std::sqrt(3.0), 1e-12);
  EXPECT_NEAR(crossingAngle({1, 0, 0}, {1, 1, 0}), M_PI / 4.0, 1e-15);
}

TEST(Stickers, TwoStickersPerNotchedConnectionCoveringTheSlideRange) {
  const EggGrid grid = testing::handGrid();
  const auto options = testing::handOptions();
  const FabricationPatch patch{0, &grid, std::nullopt};
  const auto plans = planLamellae({patch}, options);
  const auto stickers = planStickers(patch, plans, options);
  // Only (1,1) is notched (the 0.4 mm notch is a plain hole, the boundary notch is dropped).
  ASSERT_EQ(stickers.size(), 2u);
  // Square grid, flat: crossing at 90 deg planar and deployed, contact half-length w/2 = 5 mm.
  const Sticker& u = stickers[0];
  EXPECT_EQ(u.id, "P0-C1-1/P0-U1");
  EXPECT_NEAR(u.planarAngleRad, M_PI / 2.0, 1e-12);
  EXPECT_NEAR(u.deployedAngleRad, M_PI / 2.0, 1e-12);
  EXPECT_NEAR(u.lengthMm, 2 * 2.0 + 5.0 + 2 * 5.0, 1e-12);  // margins + slide + footprint = 19 mm
  EXPECT_NEAR(u.boltXMm, 7.0, 1e-12);
  EXPECT_NEAR(u.slideMm, 5.0, 1e-12);
  EXPECT_NEAR(u.widthMm, 10.0, 1e-12);
  const Sticker& v = stickers[1];
  EXPECT_EQ(v.lamellaId, "P0-V1");
  EXPECT_NEAR(v.lengthMm, 17.0, 1e-12);
  EXPECT_NEAR(v.boltXMm, 10.0, 1e-12);  // the bolt slides 3 mm back towards the start
  EXPECT_NEAR(u.areaM2() + v.areaM2(), (19.0 + 17.0) * 10.0 * 1e-6, 1e-15);
  EXPECT_FALSE(u.clipped);
}

TEST(Stickers, NearlyParallelLamellasStopHalfwayToTheNeighbours) {
  // At 0.1 rad the 10 mm strips overlap over w (1 + cos) / (2 sin) = 99.7 mm either side: the
  // sticker on u1 stops halfway to the holes 100 mm away (x = 55 .. 155 on the strip).
  EggGrid grid = testing::handGrid();
  for (int s = 0; s <= 4; ++s) {
    grid.v[1].spatial[s] = Eigen::Vector3d(0.1 + 0.05 * (s - 2) * std::cos(0.1),
                                           0.1 + 0.05 * (s - 2) * std::sin(0.1), 0.5);
  }
  const auto options = testing::handOptions();
  const FabricationPatch patch{0, &grid, std::nullopt};
  const auto stickers = planStickers(patch, planLamellae({patch}, options), options);
  ASSERT_EQ(stickers.size(), 2u);
  EXPECT_TRUE(stickers[0].clipped);
  EXPECT_NEAR(stickers[0].lengthMm, 100.0, 1e-9);
  EXPECT_NEAR(stickers[0].boltXMm, 50.0, 1e-9);
}

TEST(Stickers, ShearedDeploymentWidensTheSticker) {
  EggGrid grid = testing::handGrid();
  // Shear the spatial v member through (1,1) to 60 deg against u: the footprint grows to 5 sqrt(3).
  auto& v1 = grid.v[1];
  for (int s = 0; s <= 4; ++s) {
    v1.spatial[s] = Eigen::Vector3d(0.1 + 0.05 * (s - 2) * 0.5,
                                    0.1 + 0.05 * (s - 2) * std::sqrt(3.0) / 2.0, 0.5);
  }
  const auto options = testing::handOptions();
  const FabricationPatch patch{0, &grid, std::nullopt};
  const auto stickers = planStickers(patch, planLamellae({patch}, options), options);
  ASSERT_EQ(stickers.size(), 2u);
  EXPECT_NEAR(stickers[0].deployedAngleRad, M_PI / 3.0, 1e-9);
  EXPECT_NEAR(stickers[0].lengthMm, 4.0 + 5.0 + 2.0 * 5.0 * std::sqrt(3.0), 1e-9);
}

}  // namespace
}  // namespace egg::fabrication
