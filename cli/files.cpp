#include "files.h"

#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <tuple>

#include "crestline/error.h"

namespace crestline::cli {

void write_file_atomically(const std::string& path, const std::string& text) {
  write_file_atomically(path, [&text](const io::TextSink& sink) { sink(text); });
}

void write_file_atomically(const std::string& path, const std::function<void(const io::TextSink&)>& write) {
  const std::string temporary = path + ".tmp";
  auto fail = [&](const char* what) {
    const std::string reason = std::strerror(errno);
    std::remove(temporary.c_str());
    throw Error(ErrorKind::Io, std::string(what) + " (" + reason + ").");
  };
  errno = 0;
  {
    std::ofstream out(temporary, std::ios::binary | std::ios::trunc);
    if (!out) fail("the file cannot be created");
    try {
      write([&out](std::string_view piece) { out.write(piece.data(), static_cast<std::streamsize>(piece.size())); });
    } catch (...) {
      out.close();
      std::remove(temporary.c_str());
      throw;
    }
    out.close();
    if (!out) fail("the file cannot be written");
  }
  if (std::rename(temporary.c_str(), path.c_str()) != 0) fail("the file cannot be replaced");
}

uint64_t max_weights_bytes(size_t vertices) { return 100 * uint64_t(vertices) + (uint64_t(1) << 20); }

std::vector<double> read_vertex_weights(const std::string& path, const TriangleSoup& soup, const Mesh& mesh) {
  // A regular file only (/dev/zero or a pipe would never end), and never
  // more than max_weights_bytes: a number per line needs far fewer.
  std::error_code error;
  const auto status = std::filesystem::status(path, error);
  if (error || !std::filesystem::exists(status)) throw Error(ErrorKind::Io, "the weights file cannot be opened.");
  if (!std::filesystem::is_regular_file(status))
    throw Error(ErrorKind::Io, "the weights file is not a regular file (a folder, device or pipe).");
  std::ifstream file(path, std::ios::binary);
  if (!file) throw Error(ErrorKind::Io, "the weights file cannot be opened.");
  const uint64_t limit = max_weights_bytes(soup.vertex_count());
  std::string text;
  char chunk[1 << 16];
  while (file.read(chunk, sizeof chunk) || file.gcount() > 0) {
    text.append(chunk, size_t(file.gcount()));
    if (text.size() > limit)
      throw Error(ErrorKind::TooLarge, "the weights file is longer than " + std::to_string(limit) +
                                           " bytes, the most read for a mesh of " +
                                           std::to_string(soup.vertex_count()) + " vertices.");
  }
  std::istringstream in(text);
  std::vector<double> weights;
  std::string line;
  for (size_t number = 1; std::getline(in, line); ++number) {
    const size_t start = line.find_first_not_of(" \t\r");
    if (start == std::string::npos || line[start] == '#') continue;
    char* end = nullptr;
    const double value = std::strtod(line.c_str() + start, &end);
    const bool rest_blank = line.find_first_not_of(" \t\r", end - line.c_str()) == std::string::npos;
    if (end == line.c_str() + start || !rest_blank || !std::isfinite(value) || value < 0)
      throw Error(ErrorKind::InvalidInput, "line " + std::to_string(number) + " is not a finite non-negative number.");
    weights.push_back(value);
  }
  // One weight per input vertex, in the file's order, unless the count is
  // the repaired mesh's only (the order of --with-mesh's surface, which
  // reads back numbered the same). Repair renumbers the vertices by first
  // use, so even with equal counts the file's order is not the mesh's.
  if (weights.size() != soup.vertex_count()) {
    if (weights.size() == mesh.vertex_count()) return weights;
    throw Error(ErrorKind::InvalidInput, "it has " + std::to_string(weights.size()) + " weights but the mesh has " +
                                             std::to_string(soup.vertex_count()) + " vertices (" +
                                             std::to_string(mesh.vertex_count()) + " after repair).");
  }
  // Repair keeps one of each group of welded vertices at its position, so
  // positions identify them.
  using Key = std::tuple<double, double, double>;
  std::map<Key, double> by_position;
  for (size_t v = 0; v < soup.vertex_count(); ++v) {
    const double* p = &soup.positions[3 * v];
    by_position.emplace(Key{p[0], p[1], p[2]}, weights[v]);
  }
  std::vector<double> mapped(mesh.vertex_count());
  for (size_t v = 0; v < mesh.vertex_count(); ++v) {
    const Vec3& p = mesh.positions[v];
    const auto it = by_position.find(Key{p.x(), p.y(), p.z()});
    if (it == by_position.end())
      throw Error(ErrorKind::InvalidInput, "the mesh repair moved vertices, so give one weight per repaired vertex (" +
                                               std::to_string(mesh.vertex_count()) + ").");
    mapped[v] = it->second;
  }
  return mapped;
}

}  // namespace crestline::cli
