#include "fireswarm/server/mbtiles.hpp"

#include <sqlite3.h>

#include <mutex>
#include <sstream>
#include <stdexcept>
#include <vector>

namespace fireswarm::server {
namespace {

constexpr int kMaxZoom = 30;  // 2^30 tiles a side: beyond any real tile set

// A prepared statement, finalized when it goes.
struct Statement {
  sqlite3_stmt* stmt = nullptr;
  ~Statement() { sqlite3_finalize(stmt); }
};

std::vector<double> Numbers(const std::string& text) {
  std::vector<double> numbers;
  std::stringstream in(text);
  std::string item;
  while (std::getline(in, item, ',')) {
    try {
      numbers.push_back(std::stod(item));
    } catch (const std::exception&) {
      return {};
    }
  }
  return numbers;
}

}  // namespace

struct MbTiles::Db {
  sqlite3* handle = nullptr;
  sqlite3_stmt* tile = nullptr;  // SELECT tile_data ... (prepared once)
  std::mutex mutex;              // a statement is used by one thread at a time
  ~Db() {
    sqlite3_finalize(tile);
    sqlite3_close(handle);
  }
};

MbTiles::MbTiles(const std::filesystem::path& file) : path_(file), db_(std::make_unique<Db>()) {
  const std::string name = file.string();
  const auto fail = [&](const std::string& what) {
    throw std::runtime_error(name + ": not a usable MBTiles file: " + what);
  };
  if (sqlite3_open_v2(name.c_str(), &db_->handle, SQLITE_OPEN_READONLY, nullptr) != SQLITE_OK) {
    fail(db_->handle != nullptr ? sqlite3_errmsg(db_->handle) : "cannot open");
  }
  // Preparing reads the schema, so a file that is not SQLite fails here.
  if (sqlite3_prepare_v2(db_->handle,
                         "SELECT tile_data FROM tiles WHERE zoom_level = ?1 AND tile_column = ?2 "
                         "AND tile_row = ?3",
                         -1, &db_->tile, nullptr) != SQLITE_OK) {
    fail(std::string(sqlite3_errmsg(db_->handle)) + " (an MBTiles file has a 'tiles' table)");
  }
  Statement metadata;
  if (sqlite3_prepare_v2(db_->handle, "SELECT name, value FROM metadata", -1, &metadata.stmt,
                         nullptr) == SQLITE_OK) {
    while (sqlite3_step(metadata.stmt) == SQLITE_ROW) {
      const auto* key = sqlite3_column_text(metadata.stmt, 0);
      const auto* value = sqlite3_column_text(metadata.stmt, 1);
      if (key != nullptr && value != nullptr) {
        metadata_[reinterpret_cast<const char*>(key)] = reinterpret_cast<const char*>(value);
      }
    }
  }
}

MbTiles::~MbTiles() = default;

std::optional<std::string> MbTiles::Tile(int z, int x, int y) const {
  if (z < 0 || z > kMaxZoom) return std::nullopt;
  const long long side = 1LL << z;
  if (x < 0 || y < 0 || x >= side || y >= side) return std::nullopt;
  const long long tms_row = side - 1 - y;  // MBTiles rows count from the south
  const std::lock_guard lock(db_->mutex);
  sqlite3_stmt* stmt = db_->tile;
  sqlite3_reset(stmt);
  sqlite3_bind_int(stmt, 1, z);
  sqlite3_bind_int(stmt, 2, x);
  sqlite3_bind_int64(stmt, 3, tms_row);
  const int step = sqlite3_step(stmt);
  if (step == SQLITE_DONE) return std::nullopt;
  if (step != SQLITE_ROW) {
    throw std::runtime_error(path_.string() + ": reading tile " + std::to_string(z) + "/" +
                             std::to_string(x) + "/" + std::to_string(y) + ": " +
                             sqlite3_errmsg(db_->handle));
  }
  const void* data = sqlite3_column_blob(stmt, 0);
  const int size = sqlite3_column_bytes(stmt, 0);
  std::string tile =
      data == nullptr ? std::string()
                      : std::string(static_cast<const char*>(data), static_cast<std::size_t>(size));
  sqlite3_reset(stmt);
  return tile;
}

nlohmann::json MbTiles::MetadataJson() const {
  nlohmann::json json = nlohmann::json::object();
  for (const auto& [key, value] : metadata_) {
    if (key == "minzoom" || key == "maxzoom") {
      try {
        json[key] = std::stoi(value);
        continue;
      } catch (const std::exception&) {
      }
    }
    if (key == "bounds" || key == "center") {
      const std::vector<double> numbers = Numbers(value);
      if (!numbers.empty()) {
        json[key] = numbers;
        continue;
      }
    }
    json[key] = value;
  }
  return json;
}

std::string MbTiles::ContentType() const {
  const auto format = metadata_.find("format");
  const std::string f = format == metadata_.end() ? "png" : format->second;
  if (f == "jpg" || f == "jpeg") return "image/jpeg";
  if (f == "webp") return "image/webp";
  if (f == "pbf") return "application/x-protobuf";
  return "image/png";
}

}  // namespace fireswarm::server
