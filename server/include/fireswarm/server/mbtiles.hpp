// Offline map tiles from an MBTiles 1.3 file (SQLite): the `tiles` table keyed by
// zoom_level, tile_column and tile_row in TMS order (row 0 at the south), and the
// `metadata` table of name/value pairs. Read-only.
#pragma once

#include <filesystem>
#include <map>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>

namespace fireswarm::server {

class MbTiles {
 public:
  /// Opens `file` read-only. Throws std::runtime_error naming the file when it
  /// cannot be opened, is not an SQLite database, or has no `tiles` table.
  explicit MbTiles(const std::filesystem::path& file);
  ~MbTiles();
  MbTiles(const MbTiles&) = delete;
  MbTiles& operator=(const MbTiles&) = delete;

  /// The tile at zoom `z`, column `x`, row `y` counted from the north as web
  /// maps do (XYZ; the file's TMS row is 2^z - 1 - y); nullopt when the file has
  /// none or the address is outside the zoom's grid. Throws std::runtime_error
  /// naming the file when a read fails.
  std::optional<std::string> Tile(int z, int x, int y) const;

  /// The metadata table, name -> value (empty when the file has none).
  const std::map<std::string, std::string>& metadata() const { return metadata_; }
  /// The metadata as JSON: every entry as a string, except `minzoom` and
  /// `maxzoom` as integers and `bounds` and `center` as number arrays.
  nlohmann::json MetadataJson() const;
  /// The MIME type of its tiles from `format` (png when not given).
  std::string ContentType() const;
  const std::filesystem::path& path() const { return path_; }

 private:
  struct Db;
  std::filesystem::path path_;
  std::unique_ptr<Db> db_;
  std::map<std::string, std::string> metadata_;
};

}  // namespace fireswarm::server
