#include "fireswarm/server/mbtiles.hpp"

#include <gtest/gtest.h>

#include "web_test_support.hpp"

namespace fireswarm::server {
namespace {

using testing::Sql;
using testing::WriteMbTiles;

class MbTilesTest : public testing::ScratchTest {};

TEST_F(MbTilesTest, GivesTilesByXyzAddressWithTheTmsRowFlipped) {
  const auto file = dir_ / "map.mbtiles";
  WriteMbTiles(file, std::string("PNG\0tile", 8));
  const MbTiles tiles(file);
  // Stored at TMS row 0 of zoom 1 (the south): XYZ row 2^1 - 1 - 0 = 1.
  ASSERT_TRUE(tiles.Tile(1, 0, 1).has_value());
  EXPECT_EQ(*tiles.Tile(1, 0, 1), std::string("PNG\0tile", 8));
  EXPECT_FALSE(tiles.Tile(1, 0, 0).has_value());
  EXPECT_FALSE(tiles.Tile(1, 1, 1).has_value());
  EXPECT_FALSE(tiles.Tile(1, 0, 2).has_value()) << "outside zoom 1's 2 x 2 grid";
  EXPECT_FALSE(tiles.Tile(-1, 0, 0).has_value());
  EXPECT_FALSE(tiles.Tile(40, 0, 0).has_value());
}

TEST_F(MbTilesTest, MetadataAsJsonWithNumbersWhereTheSpecHasThem) {
  const auto file = dir_ / "map.mbtiles";
  WriteMbTiles(file, "x");
  const MbTiles tiles(file);
  const nlohmann::json metadata = tiles.MetadataJson();
  EXPECT_EQ(metadata.at("format"), "png");
  EXPECT_EQ(metadata.at("name"), "test");
  EXPECT_EQ(metadata.at("minzoom"), 0);
  EXPECT_EQ(metadata.at("maxzoom"), 1);
  EXPECT_EQ(metadata.at("bounds"), nlohmann::json::array({-180.0, -85.0, 0.0, 0.0}));
  EXPECT_EQ(tiles.ContentType(), "image/png");
}

TEST_F(MbTilesTest, ContentTypeFollowsTheFormat) {
  const auto file = dir_ / "map.mbtiles";
  WriteMbTiles(file, "x");
  Sql(file, "UPDATE metadata SET value = 'jpg' WHERE name = 'format';");
  EXPECT_EQ(MbTiles(file).ContentType(), "image/jpeg");
}

TEST_F(MbTilesTest, RefusesFilesThatAreNotMbTilesNamingThem) {
  const auto text = Write("notes.mbtiles", std::string(2048, 'x'));
  const auto no_tiles = dir_ / "empty.mbtiles";
  Sql(no_tiles, "CREATE TABLE other (a INTEGER);");
  const auto missing = dir_ / "missing.mbtiles";
  for (const auto& file : {text, no_tiles, missing}) {
    try {
      const MbTiles tiles(file);
      ADD_FAILURE() << file << " was taken";
    } catch (const std::runtime_error& e) {
      EXPECT_NE(std::string(e.what()).find(file.string()), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find("MBTiles"), std::string::npos) << e.what();
    }
  }
}

}  // namespace
}  // namespace fireswarm::server
