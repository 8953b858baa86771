// TemperatureField: point temperatures of ground, fire, embers and distractors,
// and radiance integrated over a footprint with exact partial coverage.
#include "fireswarm/sim2d/temperature_field.hpp"

#include <gtest/gtest.h>

#include <string>

#include "temperature_polygon.hpp"

namespace fireswarm::sim2d {
namespace {

FireConfig SmallArea() {
  FireConfig config;
  config.width_m = 200.0;
  config.height_m = 200.0;
  return config;
}

GroundQuad Square(const Vec2& lo, double side_m) {
  return {lo, lo + Vec2(side_m, 0.0), lo + Vec2(side_m, side_m), lo + Vec2(0.0, side_m)};
}

TEST(TemperatureField, RadianceRoundTripsAndGrowsAsFourthPower) {
  for (const double c : {-20.0, 0.0, 25.0, 70.0, 700.0}) {
    EXPECT_NEAR(ApparentCFromRadiance(RadianceFromC(c)), c, 1e-9);
  }
  EXPECT_NEAR(RadianceFromC(0.0), 5.670374419e-8 * std::pow(273.15, 4), 1e-9);
  EXPECT_NEAR(RadianceFromC(273.15) / RadianceFromC(0.0), 16.0, 1e-12);
}

TEST(TemperatureField, PointTemperaturesOfGroundFireAndRock) {
  FireGrid fire(SmallArea(), MakeRng(1, "fire"));
  fire.AddIgnition({Vec2(102.0, 102.0), 0.0});
  fire.AdvanceTo(1.0);
  const TemperatureField field(fire, {{Vec2(50.0, 50.0), 4.0, 55.0}});
  EXPECT_DOUBLE_EQ(field.TemperatureAt(Vec2(150.0, 150.0)), 25.0);
  EXPECT_DOUBLE_EQ(field.TemperatureAt(Vec2(-50.0, 10.0)), 25.0);  // off the grid: ambient
  EXPECT_DOUBLE_EQ(field.TemperatureAt(Vec2(102.0, 102.0)), 700.0);
  EXPECT_DOUBLE_EQ(field.TemperatureAt(Vec2(52.0, 52.0)), 55.0);
  EXPECT_DOUBLE_EQ(field.TemperatureAt(Vec2(50.0, 54.5)), 25.0);
  EXPECT_TRUE(field.AnyHotIn({Vec2(40.0, 40.0), Vec2(47.0, 47.0)}));
  EXPECT_FALSE(field.AnyHotIn({Vec2(0.0, 150.0), Vec2(30.0, 190.0)}));
}

TEST(TemperatureField, BurnedGroundCoolsExponentiallyTowardAmbient) {
  const FireConfig config = SmallArea();
  FireGrid fire(config, MakeRng(1, "fire"));
  fire.AddIgnition({Vec2(102.0, 102.0), 0.0});
  const TemperatureField field(fire, {});
  double previous_c = 1e9;
  for (double dt = 0.0; dt <= 4.0 * config.cooling_tau_s; dt += config.cooling_tau_s) {
    fire.AdvanceTo(config.forest.burn_duration_s + dt);
    const double t_c = field.TemperatureAt(Vec2(102.0, 102.0));
    EXPECT_NEAR(t_c - 25.0, (config.ember_c - 25.0) * std::exp(-dt / config.cooling_tau_s), 1e-9);
    EXPECT_LT(t_c, previous_c);
    previous_c = t_c;
  }
}

TEST(TemperatureField, FootprintAveragesRadianceByCoveredArea) {
  FireConfig config = SmallArea();
  config.jitter_fraction = 0.0;
  FireGrid fire(config, MakeRng(1, "fire"));
  fire.AddIgnition({Vec2(102.0, 102.0), 0.0});  // cell [100, 105]^2
  fire.AdvanceTo(0.0);
  const TemperatureField field(fire, {});
  const double ambient_w = RadianceFromC(25.0);
  const double flame_w = RadianceFromC(700.0);
  // A 20 m footprint holding the whole 5 m cell: 1/16 of it is fire.
  EXPECT_NEAR(field.MeanRadianceOver(Square(Vec2(92.0, 95.0), 20.0)),
              ambient_w + (flame_w - ambient_w) / 16.0, 1e-6);
  // Half the cell inside a 10 m footprint: 12.5 / 100.
  EXPECT_NEAR(field.MeanRadianceOver(Square(Vec2(102.5, 95.0), 10.0)),
              ambient_w + (flame_w - ambient_w) * 0.125, 1e-6);
  // Winding does not matter; a footprint away from the fire is ambient.
  GroundQuad cw = Square(Vec2(92.0, 95.0), 20.0);
  std::swap(cw[1], cw[3]);
  EXPECT_NEAR(field.MeanRadianceOver(cw), ambient_w + (flame_w - ambient_w) / 16.0, 1e-6);
  EXPECT_DOUBLE_EQ(field.MeanRadianceOver(Square(Vec2(10.0, 10.0), 20.0)), ambient_w);
  // The apparent temperature is warmer than ambient but far below the flame.
  const double apparent_c =
      ApparentCFromRadiance(field.MeanRadianceOver(Square(Vec2(92.0, 95.0), 20.0)));
  EXPECT_GT(apparent_c, 100.0);
  EXPECT_LT(apparent_c, 400.0);
}

TEST(TemperatureField, DistractorCoverageMatchesDiscArea) {
  FireGrid fire(SmallArea(), MakeRng(1, "fire"));
  const TemperatureField field(fire, {{Vec2(50.0, 50.0), 3.0, 60.0}});
  const double ambient_w = RadianceFromC(25.0);
  const double rock_w = RadianceFromC(60.0);
  const double disc_m2 = 3.14159265358979 * 9.0;
  EXPECT_NEAR(field.MeanRadianceOver(Square(Vec2(40.0, 40.0), 20.0)),
              ambient_w + (rock_w - ambient_w) * disc_m2 / 400.0, 1e-9 * ambient_w + 1e-6);
}

TEST(TemperatureField, GridSplitOfAFootprintMatchesPerCellClipping) {
  // A rotated 9 m quad over 5 m cells: cut along grid lines vs clipped cell by cell.
  const Vec2 c(12.3, 7.9);
  const double a = 0.4;
  const Vec2 ex(std::cos(a), std::sin(a)), ey(-std::sin(a), std::cos(a));
  const GroundQuad quad = {c - 4.5 * ex - 3.0 * ey, c + 4.5 * ex - 3.0 * ey,
                           c + 4.5 * ex + 3.0 * ey, c - 4.5 * ex + 3.0 * ey};
  std::array<CellOverlap, 16> pieces;
  const int n = SplitQuadIntoCells(quad, Vec2(0.0, 0.0), 5.0, pieces.data(), 16);
  ASSERT_GT(n, 4);
  double total = 0.0;
  for (int i = 0; i < n; ++i) {
    const CellOverlap& piece = pieces[static_cast<std::size_t>(i)];
    const Vec2 lo(piece.col * 5.0, piece.row * 5.0);
    EXPECT_NEAR(piece.area_m2, QuadBoxOverlapAreaM2(quad, lo, lo + Vec2(5.0, 5.0)), 1e-9);
    total += piece.area_m2;
  }
  EXPECT_NEAR(total, 54.0, 1e-9);
  EXPECT_EQ(SplitQuadIntoCells(quad, Vec2(0.0, 0.0), 1.0, pieces.data(), 16), -1);
}

TEST(TemperatureField, HotCellMaskIsExactToACellWhereTheTileIndexIsNot) {
  // One burning cell, (100, 100)-(105, 105), and a rock: the field's 80 m tiles
  // say "maybe" all around the fire; the frame's mask must say so only for
  // boxes that touch the burning cell or the rock's box.
  FireGrid fire(SmallArea(), MakeRng(1, "fire"));
  fire.AddIgnition({Vec2(102.0, 102.0), 0.0});
  fire.AdvanceTo(0.0);
  ASSERT_EQ(fire.burning_count(), 1u);
  const TemperatureField field(fire, {{Vec2(50.0, 50.0), 4.0, 55.0}});
  HotCellMask mask;
  ASSERT_TRUE(mask.Build(field, {Vec2(0.0, 0.0), Vec2(200.0, 200.0)}, 0.0));
  const GroundBox near_fire{Vec2(130.0, 130.0), Vec2(140.0, 140.0)};
  EXPECT_TRUE(field.AnyHotIn(near_fire));
  EXPECT_FALSE(mask.AnyIn(near_fire));
  EXPECT_TRUE(mask.AnyIn({Vec2(104.0, 104.0), Vec2(110.0, 110.0)}));
  EXPECT_FALSE(mask.AnyIn({Vec2(105.5, 100.0), Vec2(110.0, 104.0)}));
  EXPECT_TRUE(mask.AnyIn({Vec2(53.5, 50.0), Vec2(56.0, 51.0)}));   // rock box reaches 54.2 m
  EXPECT_FALSE(mask.AnyIn({Vec2(60.5, 50.0), Vec2(61.0, 51.0)}));  // next cell but one
  EXPECT_FALSE(mask.AnyIn({Vec2(-50.0, -50.0), Vec2(-40.0, -40.0)}));
  // A frame box away from both marks nothing.
  EXPECT_FALSE(mask.Build(field, {Vec2(150.0, 150.0), Vec2(200.0, 200.0)}, 0.0));
  EXPECT_FALSE(mask.AnyIn({Vec2(104.0, 104.0), Vec2(110.0, 110.0)}));
}

TEST(TemperatureField, BadDistractorsAreRejectedNamingTheField) {
  FireGrid fire(SmallArea(), MakeRng(1, "fire"));
  try {
    TemperatureField field(fire, {{Vec2(0, 0), 1.0, 50.0}, {Vec2(0, 0), 0.0, 50.0}});
    ADD_FAILURE() << "zero radius accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("distractors[1].radius_m"), std::string::npos) << e.what();
  }
  try {
    TemperatureField field(fire, {{Vec2(0, 0), 1.0, NAN}});
    ADD_FAILURE() << "NaN temperature accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("distractors[0].temperature_c"), std::string::npos);
  }
}

TEST(TemperatureField, RandomDistractorsAreSunHeatedRock) {
  Rng rng = MakeRng(4, "distractors");
  const GroundBox area{Vec2(0.0, 0.0), Vec2(1000.0, 500.0)};
  const std::vector<Distractor> rocks = RandomDistractors(50, area, rng);
  ASSERT_EQ(rocks.size(), 50U);
  for (const Distractor& d : rocks) {
    EXPECT_GE(d.temperature_c, 40.0);
    EXPECT_LE(d.temperature_c, 70.0);
    EXPECT_GE(d.center_m.x(), 0.0);
    EXPECT_LE(d.center_m.y(), 500.0);
    EXPECT_GE(d.radius_m, 2.0);
  }
  EXPECT_THROW(RandomDistractors(1, area, rng, 70.0, 40.0), std::invalid_argument);
}

}  // namespace
}  // namespace fireswarm::sim2d
