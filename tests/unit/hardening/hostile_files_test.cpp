// Hostile and unusual files of issue 18: a JSON nested 20,000 deep, buffer
// URIs leading out of the model's folder, devices and folders given as
// files, integers that wrapped when narrowed, spec violations that were
// accepted, valid OBJ that was refused, and messages that echoed kilobytes
// or internal names. Every refusal is one sentence starting with the file.
#include <unistd.h>

#include <catch2/catch.hpp>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>

#include "crestline/error.h"
#include "crestline/io/read_mesh.h"

using namespace crestline;
namespace fs = std::filesystem;

namespace {

std::vector<uint8_t> bytes_of(const std::string& text) { return {text.begin(), text.end()}; }

// The error reading `text` as `name` gives (fails when there is none).
Error refusal(const std::string& name, const std::string& text) {
  INFO(name);
  try {
    io::read_mesh_bytes(name, bytes_of(text));
  } catch (const Error& e) {
    INFO(e.what());
    CHECK(std::string(e.what()).rfind(name + ": ", 0) == 0);
    CHECK(std::string(e.what()).size() < 240);
    return e;
  }
  FAIL("read without an error");
  return Error(ErrorKind::Io, "");
}

bool contains(const Error& e, const std::string& part) { return std::string(e.what()).find(part) != std::string::npos; }

// One triangle; `buffer` is the buffers entry, `extra` is spliced into the
// top-level object.
std::string triangle_gltf(const std::string& buffer, const std::string& extra = "", const std::string& indices = "") {
  return R"({"asset":{"version":"2.0"},"buffers":[)" + buffer + R"(],
    "bufferViews":[{"buffer":0,"byteLength":36}],
    "accessors":[{"bufferView":0,"componentType":5126,"count":3,"type":"VEC3"}],
    "meshes":[{"primitives":[{"attributes":{"POSITION":0})" +
         indices + R"(}]}],"nodes":[{"mesh":0}])" + extra + "}";
}

// Three float vertices of a right triangle.
std::vector<uint8_t> triangle_buffer() {
  std::vector<uint8_t> out;
  for (float c : {0.f, 0.f, 0.f, 1.f, 0.f, 0.f, 0.f, 1.f, 0.f}) {
    const auto* b = reinterpret_cast<const uint8_t*>(&c);
    out.insert(out.end(), b, b + 4);
  }
  return out;
}

// A GLB of `json` (space-padded to 4 bytes) and, unless empty, a BIN chunk of `bin`.
std::string glb_of(std::string json, const std::vector<uint8_t>& bin = {}) {
  while (json.size() % 4) json += ' ';
  std::string glb = "glTF";
  auto u32 = [&](size_t v) {
    const auto word = uint32_t(v);
    glb.append(reinterpret_cast<const char*>(&word), 4);
  };
  u32(2), u32(20 + json.size() + (bin.empty() ? 0 : 8 + bin.size())), u32(json.size()), u32(0x4E4F534A);
  glb += json;
  if (!bin.empty()) u32(bin.size()), u32(0x004E4942), glb.append(bin.begin(), bin.end());
  return glb;
}

std::string data_uri_buffer() {
  // base64 of triangle_buffer(), 36 bytes.
  return R"({"byteLength":36,"uri":"data:application/octet-stream;base64,AAAAAAAAAAAAAAAAAACAPwAAAAAAAAAAAAAAAAAAgD8AAAAA"})";
}

// A scratch folder: model/ holds the glTF, secret.bin sits beside model/.
struct Scratch {
  fs::path root;
  Scratch() {
    root = fs::temp_directory_path() / ("crestline-hostile-" + std::to_string(::getpid()));
    fs::remove_all(root);
    fs::create_directories(root / "model" / "sub");
    write(root / "secret.bin", triangle_buffer());
  }
  ~Scratch() { fs::remove_all(root); }
  static void write(const fs::path& path, const std::vector<uint8_t>& bytes) {
    std::ofstream(path, std::ios::binary)
        .write(reinterpret_cast<const char*>(bytes.data()), std::streamsize(bytes.size()));
  }
  // Writes model/NAME with one buffer at `uri` and reads it.
  TriangleSoup read(const std::string& name, const std::string& uri, int byte_length = 36) const {
    const fs::path path = root / "model" / name;
    write(path,
          bytes_of(triangle_gltf(R"({"byteLength":)" + std::to_string(byte_length) + R"(,"uri":")" + uri + "\"}")));
    return io::read_mesh(path.string());
  }
  Error refusal(const std::string& name, const std::string& uri, int byte_length = 36) const {
    try {
      read(name, uri, byte_length);
    } catch (const Error& e) {
      INFO(e.what());
      CHECK(std::string(e.what()).rfind(name + ": ", 0) == 0);
      return e;
    }
    FAIL(name << " read without an error");
    return Error(ErrorKind::Io, "");
  }
};

}  // namespace

TEST_CASE("glTF JSON nested 20,000 deep is refused before tinygltf recurses", "[hardening][hostile]") {
  // Natively this overflowed the stack inside tinygltf (SIGSEGV).
  const std::string deep = std::string(20000, '[') + std::string(20000, ']');
  const Error e = refusal("deep.gltf", triangle_gltf(data_uri_buffer(), R"(,"extras":)" + deep));
  CHECK(e.kind() == ErrorKind::InvalidInput);
  CHECK(contains(e, "nests deeper than 64 levels"));
  // Brackets inside strings do not count; 50 levels of extras are fine.
  const std::string fifty =
      std::string(50, '[') + R"("[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[")" + std::string(50, ']');
  CHECK(io::read_mesh_bytes("fine.gltf", bytes_of(triangle_gltf(data_uri_buffer(), R"(,"extras":)" + fifty)))
            .triangle_count() == 1);
}

TEST_CASE("buffer URIs resolve only to regular files inside the model's folder", "[hardening][hostile]") {
  const Scratch scratch;
  Scratch::write(scratch.root / "model" / "sub" / "in.bin", triangle_buffer());
  CHECK(scratch.read("ok.gltf", "sub/in.bin").triangle_count() == 1);
  CHECK(scratch.read("encoded.gltf", "sub%2Fin.bin").triangle_count() == 1);
  // Out of the folder by "..", even when it comes back in, and by absolute paths.
  CHECK(contains(scratch.refusal("up.gltf", "../secret.bin"), "'../secret.bin' leads out of the model's folder"));
  CHECK(contains(scratch.refusal("zero.gltf", "../../../../../../../../dev/zero"), "leads out of the model's folder"));
  CHECK(contains(scratch.refusal("back.gltf", "sub/../sub/in.bin"), "leads out"));
  CHECK(contains(scratch.refusal("encoded-up.gltf", "%2E%2E/secret.bin"), "leads out"));
  CHECK(contains(scratch.refusal("abs.gltf", "/dev/zero"), "'/dev/zero' is not a relative path"));
  CHECK(contains(scratch.refusal("scheme.gltf", "file:///dev/zero"), "is not a relative path"));
  // In memory (the page, the WASM CLI) the same URIs are refused, whatever
  // companions come with the file, so one file gives one outcome.
  for (const char* uri : {"../secret.bin", "/dev/zero"}) {
    INFO(uri);
    try {
      io::read_mesh_bytes(
          "memory.gltf", bytes_of(triangle_gltf(R"({"byteLength":36,"uri":")" + std::string(uri) + "\"}")),
          {io::NamedBuffer{"secret.bin", triangle_buffer()}, io::NamedBuffer{"zero", triangle_buffer()}});
      FAIL("read without an error");
    } catch (const Error& e) {
      CHECK(contains(e, "only files in the model's folder are read"));
    }
  }
  // A link inside the folder that leads out of it.
  fs::create_symlink(scratch.root / "secret.bin", scratch.root / "model" / "link.bin");
  CHECK(
      contains(scratch.refusal("link.gltf", "link.bin"), "'link.bin' is a link that leads out of the model's folder"));
  fs::create_symlink("/dev/zero", scratch.root / "model" / "zero.bin");
  CHECK(contains(scratch.refusal("devlink.gltf", "zero.bin"), "leads out"));
  // A folder is not a buffer (it was "basic_filebuf::underflow error").
  const Error folder = scratch.refusal("folder.gltf", "sub");
  CHECK(contains(folder, "'sub' is not a regular file"));
  // Never more than the declared byteLength: a longer file is cut to it.
  std::vector<uint8_t> longer = triangle_buffer();
  longer.resize(1 << 20, 7);
  Scratch::write(scratch.root / "model" / "long.bin", longer);
  CHECK(scratch.read("long.gltf", "long.bin").triangle_count() == 1);
  // A shorter one is refused with both sizes.
  CHECK(contains(scratch.refusal("short.gltf", "sub/in.bin", 48), "has 36 bytes but the glTF declares 48"));
}

TEST_CASE("a device or a folder given as the mesh is refused in one sentence", "[hardening][hostile]") {
  auto message = [](const std::string& path) {
    try {
      io::read_mesh(path);
    } catch (const Error& e) {
      CHECK(e.kind() == ErrorKind::Io);
      return std::string(e.what());
    }
    FAIL(path << " read without an error");
    return std::string();
  };
  CHECK(message("/dev/zero") == "zero: this is a device, pipe or socket, not a regular file.");
  const Scratch scratch;
  CHECK(message((scratch.root / "model").string()) == "model: this is a folder, not a file.");
  CHECK(message((scratch.root / "absent.obj").string()) ==
        "absent.obj: the file cannot be opened (No such file or directory).");
}

TEST_CASE("integers read from files are range-checked in 64 bits", "[hardening][hostile]") {
  const std::string square = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n";
  // 4294967299 wrapped to 3 in the index parser and gave a valid face.
  Error e = refusal("wrap.obj", square + "f 1 2 4294967299\n");
  CHECK(e.kind() == ErrorKind::InvalidInput);
  CHECK(std::string(e.what()) ==
        "wrap.obj: the face on line 5 uses vertex index '4294967299', which is out of range (at most 2147483647).");
  CHECK(contains(refusal("digits.obj", square + "f 1 2 12345678901234567890/1/1\n"), "'12345678901234567890'"));
  CHECK(contains(refusal("negative.obj", square + "f -1 -2 -4294967299\n"), "'-4294967299'"));
  // atoi read "1e300" as 1 (a degenerate face) and "x" as 0.
  CHECK(std::string(refusal("float.obj", square + "f 1 2 1e300\n").what()) ==
        "float.obj: the face on line 5 has the vertex index '1e300', which is not a whole number.");
  CHECK(contains(refusal("word.obj", square + "f 1 2 x\n"), "'x', which is not a whole number"));
  // glTF: byteOffset 2^63 became 0 in the 32-bit WASM build.
  std::string offset = triangle_gltf(data_uri_buffer());
  offset.replace(offset.find(R"("buffer":0,)"), 11, R"("buffer":0,"byteOffset":9223372036854775808,)");
  CHECK(std::string(refusal("offset.gltf", offset).what()) ==
        "offset.gltf: the glTF property bufferViews[0].byteOffset is 9223372036854775808; it must be an integer "
        "from 0 to 2147483647.");
  std::string count = triangle_gltf(data_uri_buffer());
  count.replace(count.find(R"("count":3)"), 9, R"("count":4294967299)");
  CHECK(contains(refusal("count.gltf", count), "accessors[0].count is 4294967299"));
  std::string huge = triangle_gltf(data_uri_buffer());
  huge.replace(huge.find(R"("count":3)"), 9, R"("count":1e300)");
  CHECK(contains(refusal("huge.gltf", huge), "accessors[0].count is 1e+300;"));  // not 301 digits
  // An integer written as a float is refused (as tinygltf would), shown as written.
  std::string written = triangle_gltf(data_uri_buffer());
  written.replace(written.find(R"("count":3)"), 9, R"("count":3.0)");
  CHECK(contains(refusal("float-count.gltf", written), "accessors[0].count is 3.0;"));
}

TEST_CASE("glTF spec violations are refused in one sentence", "[hardening][hostile]") {
  // "indices": -7 was read as "no indices".
  const Error indices = refusal("indices.gltf", triangle_gltf(data_uri_buffer(), "", R"(,"indices":-7)"));
  CHECK(std::string(indices.what()) ==
        "indices.gltf: the glTF property meshes[0].primitives[0].indices is -7; it must be an integer from 0 to "
        "2147483647.");
  std::string old = triangle_gltf(data_uri_buffer());
  old.replace(old.find("2.0"), 3, "1.0");
  const Error version = refusal("old.gltf", old);
  CHECK(version.kind() == ErrorKind::Unsupported);
  CHECK(std::string(version.what()) == "old.gltf: the glTF asset version is '1.0'; Crestline reads glTF 2.0.");
}

TEST_CASE("OBJ with a UTF-8 byte-order mark or line continuations is read", "[hardening][hostile]") {
  const std::string obj = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\n";
  const TriangleSoup plain = io::read_mesh_bytes("plain.obj", bytes_of(obj));
  // The mark hid the first `v` line ("face 1 refers to vertex 4 ...").
  const TriangleSoup bom = io::read_mesh_bytes("bom.obj", bytes_of("\xEF\xBB\xBF" + obj));
  CHECK(bom.positions == plain.positions);
  CHECK(bom.indices == plain.indices);
  // "f 1 2 \\\n 3 4" was "uses vertex index 0"; CRLF too.
  const TriangleSoup joined =
      io::read_mesh_bytes("joined.obj", bytes_of("v 0 0 0\nv 1 0 \\\n 0\nv 1 1 0\nv 0 1 0\nf 1 2 \\\r\n 3 \\\n4\n"));
  CHECK(joined.positions == plain.positions);
  CHECK(joined.indices == plain.indices);
  // Line numbers in messages stay those of the file.
  CHECK(contains(refusal("later.obj", "v 0 0 \\\n0\nv 1 0 0\nv 0 1 0\nf 1 2 99999999999\n"), "on line 5"));
}

TEST_CASE("reader messages quote at most about 60 characters and no internal names", "[hardening][hostile]") {
  // A broken data URI of 20 KB was echoed whole.
  const std::string uri = "data:application/octet-stream;base64," + std::string(20000, '!');
  const Error broken = refusal("broken.gltf", triangle_gltf(R"({"byteLength":36,"uri":")" + uri + "\"}"));
  CHECK(std::string(broken.what()).size() < 200);
  const Error missing =
      refusal("missing.gltf", triangle_gltf(R"({"byteLength":36,"uri":")" + std::string(5000, 'x') + "\"}"));
  CHECK(contains(missing, "'" + std::string(57, 'x') + "...'"));
  // FLOAT indices read as truncated numbers gave "all triangles are degenerate".
  std::string floats = triangle_gltf(data_uri_buffer(), "", R"(,"indices":1)");
  floats.replace(floats.find(R"(,"type":"VEC3"}])"), 16,
                 R"(,"type":"VEC3"},{"bufferView":0,"componentType":5126,"count":3,"type":"SCALAR"}])");
  CHECK(std::string(refusal("float.gltf", floats).what()) ==
        "float.gltf: mesh 0 primitive 0 has indices of component type 5126 (FLOAT); indices must be unsigned "
        "bytes, shorts or ints.");
  // Hexadecimal coordinates were read as 0 (then "degenerate").
  CHECK(std::string(refusal("hex.obj", "v 0 0 0\nv 0x1p0 0 0\nv 0 1 0\nf 1 2 3\n").what()) ==
        "hex.obj: the vertex on line 2 has the hexadecimal number '0x1p0', which OBJ does not allow.");
  // A ten-digit exponent overflowed the int of the parser before (undefined
  // behaviour, found by the fuzzer); still refused, in normals as in
  // positions, as no double needs one. Leading zeros are fine.
  CHECK(std::string(refusal("exp.obj", "v 0 0 0\nvn 1e2147483648 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n").what()) ==
        "exp.obj: line 2 has the number '1e2147483648', whose exponent is out of range.");
  CHECK(std::string(refusal("exp.obj", "v 0 0 0\nv 1E-9999999999 0 0\nv 0 1 0\nf 1 2 3\n").what()) ==
        "exp.obj: line 2 has the number '1E-9999999999', whose exponent is out of range.");
  CHECK_NOTHROW(io::read_mesh_bytes("zeros.obj", bytes_of("v 0 0 0\nv 1e0000000000000 0 0\nv 0 1 0\nf 1 2 3\n")));
  // A GLB whose first buffer has no BIN chunk named our internal file.
  const Error chunk = refusal("nobin.glb", glb_of(triangle_gltf(R"({"byteLength":36})")));
  CHECK(!contains(chunk, "crestline-"));
}

TEST_CASE("GLB: accessors read the BIN chunk in place, within the buffer's byteLength", "[hardening][hostile]") {
  // The chunk is padded past the buffer (here by 8 bytes): the padding is no part of it.
  std::vector<uint8_t> bin = triangle_buffer();
  bin.resize(44, 0x7F);
  const TriangleSoup soup =
      io::read_mesh_bytes("padded.glb", bytes_of(glb_of(triangle_gltf(R"({"byteLength":36})"), bin)));
  CHECK(soup.positions == std::vector<double>{0, 0, 0, 1, 0, 0, 0, 1, 0});
  std::string past = triangle_gltf(R"({"byteLength":36})");
  const std::string view = R"("buffer":0,"byteLength":36})";
  past.replace(past.find(view), view.size(), R"("buffer":0,"byteLength":36,"byteOffset":4})");
  CHECK(std::string(refusal("past.glb", glb_of(past, bin)).what()) ==
        "past.glb: bufferView 0 reaches past the end of its buffer.");
  // A chunk shorter than the buffer is refused as before.
  bin.resize(32);
  CHECK(std::string(refusal("short.glb", glb_of(triangle_gltf(R"({"byteLength":36})"), bin)).what()) ==
        "short.glb: the GLB BIN chunk has 32 bytes but the glTF declares 36.");
}
