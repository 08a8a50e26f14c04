// The OBJ reader's own parse (core/src/io/read_obj.cpp): coordinates
// correctly rounded, the line ends, comments and attribute forms it reads,
// and messages that name the line of the face at fault.
#include <catch2/catch.hpp>
#include <cstdlib>
#include <cstring>
#include <random>
#include <string>
#include <tuple>
#include <vector>

#include "crestline/error.h"
#include "crestline/io/read_mesh.h"
#include "crestline/numerics/parallel.h"
#include "read_test_bytes.h"

using crestline::Error;
using crestline::ErrorKind;
using crestline::TriangleSoup;
using crestline::io::read_mesh_bytes;
using crestline::testing::bytes_of;

namespace {

TriangleSoup read_text(const std::string& text, const crestline::io::ReadOptions& options = {}) {
  return read_mesh_bytes("t.obj", bytes_of(text), {}, options);
}

std::string refusal(const std::string& text, const crestline::io::ReadOptions& options = {}) {
  try {
    read_text(text, options);
  } catch (const Error& e) {
    return e.what();
  }
  FAIL("read without an error: " << text);
  return "";
}

const std::string square = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n";

}  // namespace

TEST_CASE("OBJ: coordinates are the nearest doubles to their decimal text", "[io][obj]") {
  // Each number is the x of one vertex. The expected values are exact binary
  // constants; tinyobjloader's sum of digit x 10^-k missed several by a few
  // units in the last place.
  struct Case {
    const char* text;
    double expected;
  };
  const Case cases[] = {
      {"0.1", 0.1},
      {"-0.30000000000000004", -0.30000000000000004},
      {"0.1234567890123456789", 0x1.f9add3746f65fp-4},
      {"9007199254740993", 9007199254740992.0},                          // 2^53 + 1: a tie, to even
      {"1.00000000000000011102230246251565404236316680908203125", 1.0},  // 1 + 2^-53: a tie, to even
      {"1.00000000000000011102230246251565404236316680908203126", 1.0 + 0x1p-52},
      {"2.2250738585072011e-308", 0x0.fffffffffffffp-1022},  // the largest subnormal
      {"4.9406564584124654e-324", 0x1p-1074},                // the smallest
      {"1.7976931348623157e308", 0x1.fffffffffffffp+1023},
      {"7.038531e-26", 0x1.5c87fbp-84},
      {"+1.5", 1.5},
      {".5", 0.5},
      {"5.", 5.0},
      {"-.25e-3", -0.00025},
      {"1E2", 100.0},
      {"123456789012345678901234567890e-20", 1234567890.1234567},
  };
  std::string text;
  for (const Case& c : cases) text += std::string("v ") + c.text + " 0 0\n";
  text += "f 1 2 3\n";
  const TriangleSoup soup = read_text(text);
  REQUIRE(soup.vertex_count() == std::size(cases));
  for (size_t i = 0; i < std::size(cases); ++i) {
    INFO(cases[i].text);
    CHECK(soup.positions[3 * i] == cases[i].expected);
    CHECK(soup.positions[3 * i] == std::strtod(cases[i].text, nullptr));  // glibc's strtod rounds correctly
  }
}

TEST_CASE("OBJ: line ends, comments, attributes and short vertex lines", "[io][obj]") {
  const std::vector<double> xyz = {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0};
  const std::vector<uint32_t> two = read_text(square + "f 1 2 3 4\n").indices;  // ear-clipped
  REQUIRE(two.size() == 6);
  // LF, CRLF, a lone CR (classic Mac OS) and a mix of them.
  for (const char* end : {"\n", "\r\n", "\r"}) {
    std::string text = square + "f 1 2 3 4\n";
    for (size_t at = 0; (at = text.find('\n', at)) != std::string::npos; at += std::string(end).size()) {
      text.replace(at, 1, end);
    }
    INFO(text);
    const TriangleSoup soup = read_text(text);
    CHECK(soup.positions == xyz);
    CHECK(soup.indices == two);
  }
  // Comments after the data, tabs, texture and normal indices, w and
  // colours after x y z, and lines that give no geometry.
  const TriangleSoup rich = read_text(
      "# a comment\n\nmtllib m.mtl\no box\ng side\ns 1\nusemtl red\n"
      "v 0 0 0 1\t# corner\n\tv 1 0 0 0.5 0.25 1\nv  1\t1 0\nv 0 1 0 # last\n"
      "vt 0 0\nvt 1e-3 1\nvn 0 0 1\nvp 0.5\nl 1 2\np 3\n"
      "f 1/1/1 2/2/1 3//1 4/1 # a quad\n");
  CHECK(rich.positions == xyz);
  CHECK(rich.indices == two);
  CHECK(rich.notes.empty());
  // Missing coordinates are 0, as are words that hold no number.
  const TriangleSoup partial = read_text("v 1\nv 0 2\nv x 0 3\nf 1 2 3\n");
  CHECK(partial.positions == std::vector<double>{1, 0, 0, 0, 2, 0, 0, 0, 3});
  // A face of fewer than three corners is skipped with a note; "f" alone is no face.
  const TriangleSoup short_faces = read_text(square + "f 1 2\nf\nf 3\nf 1 2 3\n");
  CHECK(short_faces.triangle_count() == 1);
  REQUIRE(short_faces.notes.size() == 1);
  CHECK(short_faces.notes[0] == "2 faces with fewer than 3 vertices were skipped.");
}

TEST_CASE("OBJ: a face's index errors name its line; vertices are bounded", "[io][obj][hardening]") {
  CHECK(refusal(square + "\nf 1 2 0\n") ==
        "t.obj: the face on line 6 uses vertex index 0, which does not exist (OBJ indices start at 1, negative ones "
        "count back from 4).");
  CHECK(refusal(square + "f -1 -2 -5\n") ==
        "t.obj: the face on line 5 uses vertex index -5, which does not exist (OBJ indices start at 1, negative ones "
        "count back from 4).");
  // A face may refer to a vertex that comes later, not to one that never does.
  CHECK(read_text("f 1 2 3\n" + square).triangle_count() == 1);
  CHECK(refusal("f 1 2 3\nf 2 3 9\n" + square) ==
        "t.obj: the face on line 2 refers to vertex 9 but the file has 4 vertices.");
  // Lines end at a lone CR as at LF; a continuation keeps the file's numbering.
  CHECK(refusal("v 0 0 0\rv 1 0 0\r\nv 0 1 0\rf 1 2 x\r") ==
        "t.obj: the face on line 4 has the vertex index 'x', which is not a whole number.");
  CHECK(refusal("v 0 0 \\\n0\nv 1 0 0\nv 0 1 0\nf 1 2 \\\n 0\n") ==
        "t.obj: the face on line 5 uses vertex index 0, which does not exist (OBJ indices start at 1, negative ones "
        "count back from 3).");
  // Vertices are bounded like glTF accessors: 3 x the triangle limit + 3.
  crestline::io::ReadOptions options;
  options.max_triangles = 1;
  std::string six;
  for (int k = 0; k < 6; ++k) six += "v 0 0 " + std::to_string(k) + "\n";
  CHECK(read_text(six + "f 1 2 3\n", options).vertex_count() == 6);
  try {
    read_text(six + "v 1 1 1\nf 1 2 3\n", options);
    FAIL("seven vertices read");
  } catch (const Error& e) {
    CHECK(e.kind() == ErrorKind::TooLarge);
    CHECK(std::string(e.what()) == "t.obj: the file has more than 6 vertices.");
  }
}

TEST_CASE("OBJ: plain triangles read as the general face parse reads them", "[io][obj][hardening]") {
  // read_obj takes `f a b c` (positive indices without sign or leading zero,
  // of vertices already read) by a shorter path. The same text with a
  // leading zero on every index takes the general one: both must give the
  // same soup, or both refuse the file the same way.
  std::mt19937 random(5);
  auto pick = [&](std::initializer_list<const char*> words) {
    return std::string(words.begin()[random() % words.size()]);
  };
  size_t plain = 0;
  for (int trial = 0; trial < 3000; ++trial) {
    std::string text = trial % 2 ? square + square : square, zeros = text;
    const int lines = 1 + int(random() % 6);
    for (int l = 0; l < lines; ++l) {
      if (random() % 3 == 0) {
        const std::string v = "v " + std::to_string(random() % 7) + " " + std::to_string(l) + " 1\n";
        text += v, zeros += v;
        continue;
      }
      std::string face = "f", face_zeros = "f";
      const int corners = 2 + int(random() % 3);
      for (int c = 0; c < corners; ++c) {
        const std::string gap = pick({" ", "\t", "  ", " \t"});
        const std::string index = std::to_string(1 + random() % 9);
        const std::string suffix = random() % 3 ? "" : pick({"/1", "/1/2", "//3", "/x#", "a", "#", "#c", "9"});
        face += gap + index + suffix, face_zeros += gap + "0" + index + suffix;
      }
      std::string end = pick({"\n", "\r\n", "\r", " \n", " # c\n", "\t#\n", "", "x\n", "\n", "\n"});
      if (end.empty() && l + 1 < lines) end = "\n";  // the file's end only on its last line
      text += face + end, zeros += face_zeros + end;
    }
    INFO(text);
    std::string error, error_zeros;
    TriangleSoup soup, soup_zeros;
    try {
      soup = read_text(text);
    } catch (const Error& e) {
      error = std::to_string(int(e.kind()));
    }
    try {
      soup_zeros = read_text(zeros);
    } catch (const Error& e) {
      error_zeros = std::to_string(int(e.kind()));
    }
    CHECK(error == error_zeros);
    CHECK(soup.indices == soup_zeros.indices);
    CHECK(soup.positions == soup_zeros.positions);
    CHECK(soup.notes == soup_zeros.notes);
    plain += error.empty();
  }
  CHECK(plain > 200);  // enough files read, not only refused
  // The messages too, where the index text itself is not quoted.
  CHECK(refusal(square + "f 1 2 3\nf 2 3 9\n") ==
        "t.obj: the face on line 6 refers to vertex 9 but the file has 4 vertices.");
  CHECK(refusal(square + "f 1 2 3#\n") ==
        "t.obj: the face on line 5 has the vertex index '3#', which is not a whole "
        "number.");
  CHECK(read_text(square + "f 1 2 3 # c").indices == std::vector<uint32_t>{0, 1, 2});
  CHECK(read_text(square + "f 4/1 2/2/2 3//3\t#\n").indices == std::vector<uint32_t>{3, 1, 2});
}

TEST_CASE("OBJ: a large file reads in parts on every thread to the same soup or the same message", "[io][obj]") {
  // A 64 × 64 grid copied until the text passes 2.5 MB (parts, and 2^15
  // vertices and more for finish_soup's parts), then each variant below:
  // what one thread reads (one pass) is what two and three threads read,
  // soup or message.
  auto grid = [](const std::string& end_of_line) {
    std::string text = "# a grid\r\n" + std::string("mtllib none.mtl") + end_of_line;
    size_t base = 0;
    while (text.size() < (size_t{5} << 19)) {
      for (int y = 0; y < 64; ++y)
        for (int x = 0; x < 64; ++x)
          text += "v " + std::to_string(x * 0.1) + " " + std::to_string(y * 0.3) + " " + std::to_string(base % 7) +
                  end_of_line;
      text += "vn 0 0 1" + end_of_line + "vt 0.5 0.5" + end_of_line + end_of_line;
      for (int y = 0; y + 1 < 64; ++y)
        for (int x = 0; x + 1 < 64; ++x) {
          const size_t v = base + size_t(64 * y + x) + 1;
          text += "f " + std::to_string(v) + "/1/1 " + std::to_string(v + 1) + " " + std::to_string(v + 65) +
                  "  # a comment" + end_of_line;
          text += "f\t" + std::to_string(v) + " " + std::to_string(v + 65) + " " + std::to_string(v + 64) + end_of_line;
        }
      base += 64 * 64;
    }
    return text;
  };
  const std::string lf = grid("\n");
  auto with = [](std::string text, double where, const std::string& line) {
    const size_t at = text.find('\n', size_t(where * double(text.size()))) + 1;
    return text.insert(at, line);
  };
  struct Variant {
    const char* name;
    std::string text;
    crestline::io::ReadOptions options;
  };
  crestline::io::ReadOptions few;
  few.max_triangles = 20000;
  const std::vector<Variant> variants = {
      {"plain (parts)", lf, {}},
      {"CRLF (parts)", grid("\r\n"), {}},
      {"a lone CR for every line end (one part)", grid("\r"), {}},
      {"a quad near the end", with(lf, 0.9, "f 1 2 66 65\n"), {}},
      {"relative indices in the middle", with(lf, 0.5, "f -1 -2 -3\n"), {}},
      {"a face ahead of its vertices", with(lf, 0.1, "f 1 2 6000\n"), {}},
      {"a face beyond every vertex", with(lf, 0.8, "f 1 2 999999\n"), {}},
      {"a short face", with(lf, 0.6, "f 1 2\n"), {}},
      {"an index of 0", with(lf, 0.7, "f 0 1 2\n"), {}},
      {"two problems: the first one is named", with(with(lf, 0.9, "v 0x1 0 0\n"), 0.3, "f 1 2 x\n"), {}},
      {"a huge exponent late", with(lf, 0.95, "v 1e99999999999 0 0\n"), {}},
      {"too many triangles", lf, few},
      {"a continuation line", with(lf, 0.4, "f 1 2 \\\n 3\n"), {}},
      {"non-finite vertices (a note with their count)", with(with(lf, 0.7, "v 1 inf 2\n"), 0.3, "v nan 1 2\n"), {}},
  };
  auto read = [](const Variant& variant) {
    try {
      const TriangleSoup soup = read_text(variant.text, variant.options);
      std::vector<uint64_t> bits(soup.positions.size());  // NaN too
      std::memcpy(bits.data(), soup.positions.data(), 8 * bits.size());
      return std::make_tuple(bits, soup.indices, soup.notes, std::string());
    } catch (const Error& e) {
      return std::make_tuple(std::vector<uint64_t>(), std::vector<uint32_t>(), std::vector<std::string>(),
                             std::string(e.what()));
    }
  };
  const int before = crestline::max_threads();
  for (const Variant& variant : variants) {
    INFO(variant.name);
    crestline::set_max_threads(1);
    const auto one = read(variant);
    if (variant.name == variants[0].name)
      CHECK(std::get<1>(one).size() == 3 * 2 * 63 * 63 * (std::get<0>(one).size() / 3 / 4096));
    if (std::string(variant.name).rfind("non-finite", 0) == 0)
      CHECK(std::get<2>(one) ==
            std::vector<std::string>{"2 vertices have NaN or infinite coordinates; their triangles are dropped."});
    for (int threads : {2, 3}) {
      crestline::set_max_threads(threads);
      CHECK(read(variant) == one);
    }
  }
  crestline::set_max_threads(before);
}
