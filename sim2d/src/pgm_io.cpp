// Binary PGM (P5) files: the one place sim2d touches the file system, so
// rendered frames can be looked at with any image viewer.
#include <fstream>
#include <istream>
#include <stdexcept>
#include <string>

#include "fireswarm/sim2d/thermal_image.hpp"

namespace fireswarm::sim2d {
namespace {

constexpr int kMaxGrey = 255;

[[noreturn]] void Fail(const std::string& path, const std::string& problem) {
  throw std::runtime_error("PGM file '" + path + "': " + problem);
}

// The next header number, skipping whitespace and '#' comments.
int ReadHeaderNumber(std::istream& in, const std::string& path, const char* what) {
  in >> std::ws;
  while (in.peek() == '#') {
    std::string comment;
    std::getline(in, comment);
    in >> std::ws;
  }
  int value = 0;
  if (!(in >> value)) Fail(path, std::string("cannot read ") + what);
  return value;
}

}  // namespace

void WritePgm(const std::string& path, const ThermalImage& image) {
  std::ofstream out(path, std::ios::binary);
  if (!out) Fail(path, "cannot open for writing");
  out << "P5\n# fireswarm thermal image, white-hot, t=" << image.capture_time_s << " s\n"
      << image.width_px << " " << image.height_px << "\n"
      << kMaxGrey << "\n";
  out.write(reinterpret_cast<const char*>(image.pixels.data()),
            static_cast<std::streamsize>(image.pixels.size()));
  if (!out) Fail(path, "write failed");
}

ThermalImage ReadPgm(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) Fail(path, "cannot open for reading");
  std::string magic;
  in >> magic;
  if (magic != "P5") Fail(path, "not a binary PGM (magic '" + magic + "', expected 'P5')");
  ThermalImage image;
  image.width_px = ReadHeaderNumber(in, path, "width");
  image.height_px = ReadHeaderNumber(in, path, "height");
  const int max_grey = ReadHeaderNumber(in, path, "maxval");
  if (image.width_px <= 0 || image.height_px <= 0) Fail(path, "width and height must be > 0");
  if (max_grey != kMaxGrey) Fail(path, "maxval " + std::to_string(max_grey) + ", expected 255");
  in.get();  // the single whitespace byte before the raster
  image.pixels.resize(static_cast<std::size_t>(image.width_px) *
                      static_cast<std::size_t>(image.height_px));
  in.read(reinterpret_cast<char*>(image.pixels.data()),
          static_cast<std::streamsize>(image.pixels.size()));
  if (in.gcount() != static_cast<std::streamsize>(image.pixels.size())) {
    Fail(path, "raster is shorter than width * height bytes");
  }
  return image;
}

}  // namespace fireswarm::sim2d
