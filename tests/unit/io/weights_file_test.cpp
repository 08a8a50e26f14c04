// The CLI's --weights file (cli/files.cpp): a regular file only, and a
// bounded read (/dev/zero was read until memory ran out, 8.5 GB).
#include <unistd.h>

#include <catch2/catch.hpp>
#include <filesystem>
#include <fstream>

#include "../../../cli/files.h"
#include "crestline/error.h"
#include "crestline/mesh/repair.h"

using namespace crestline;

TEST_CASE("the weights file of --weights is read only if regular, and only up to a bound", "[io][weights][hardening]") {
  TriangleSoup soup;
  soup.positions = {0, 0, 0, 1, 0, 0, 0, 1, 0};
  soup.indices = {0, 1, 2};
  const Mesh mesh = repair_mesh(soup).mesh;
  auto refusal = [&](const std::string& path) {
    try {
      cli::read_vertex_weights(path, soup, mesh);
    } catch (const Error& e) {
      return e;
    }
    FAIL(path << " read without an error");
    return Error(ErrorKind::Io, "");
  };
  const Error zero = refusal("/dev/zero");
  CHECK(zero.kind() == ErrorKind::Io);
  CHECK(std::string(zero.what()) == "the weights file is not a regular file (a folder, device or pipe).");
  CHECK(refusal("/tmp").kind() == ErrorKind::Io);
  const std::filesystem::path path =
      std::filesystem::temp_directory_path() / ("crestline-weights-" + std::to_string(::getpid()) + ".txt");
  { std::ofstream(path) << "1\n0.5\n2\n"; }
  CHECK(cli::read_vertex_weights(path.string(), soup, mesh) == std::vector<double>{1, 0.5, 2});
  // Comments beyond 100 bytes per vertex + 1 MiB: refused, not read on.
  {
    std::ofstream out(path);
    out << "1\n0.5\n2\n";
    const std::string comment = "#" + std::string(1000, '-') + "\n";
    while (out.tellp() <= std::streamoff(cli::max_weights_bytes(3))) out << comment;
  }
  const Error big = refusal(path.string());
  CHECK(big.kind() == ErrorKind::TooLarge);
  CHECK(std::string(big.what()) ==
        "the weights file is longer than 1048876 bytes, the most read for a mesh of 3 vertices.");
  std::filesystem::remove(path);
}

TEST_CASE("a weights file follows the input's vertices through repair's renumbering", "[io][weights]") {
  // Four vertices the triangles first use in the order 3, 1, 2, 0: repair
  // numbers them so; the weights, one per input vertex, go with positions.
  TriangleSoup soup;
  soup.positions = {0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 1, 0};
  soup.indices = {3, 1, 2, 0, 2, 1};
  const Mesh mesh = repair_mesh(soup).mesh;
  REQUIRE(mesh.vertex_count() == 4);
  CHECK(mesh.positions[0] == Vec3(1, 1, 0));  // renumbered: else this test proves nothing
  const std::filesystem::path path =
      std::filesystem::temp_directory_path() / ("crestline-weights-order-" + std::to_string(::getpid()) + ".txt");
  { std::ofstream(path) << "10\n11\n12\n13\n"; }
  const std::vector<double> weights = cli::read_vertex_weights(path.string(), soup, mesh);
  std::filesystem::remove(path);
  REQUIRE(weights.size() == 4);
  for (uint32_t v = 0; v < 4; ++v) {
    uint32_t input = 0;
    while (Vec3(soup.positions[3 * input], soup.positions[3 * input + 1], soup.positions[3 * input + 2]) !=
           mesh.positions[v])
      ++input;
    CHECK(weights[v] == 10 + input);
  }
}
