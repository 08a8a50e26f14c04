// io::read_mesh: format detection, dispatch to one reader per format, and
// the helpers every reader shares (messages, header-claim checks, files,
// the final soup checks).
#include "crestline/io/read_mesh.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <limits>
#include <new>

#include "../mesh/parts.h"
#include "crestline/numerics/uninitialised.h"
#include "readers.h"

namespace crestline::io {
namespace detail {

void fail(ErrorKind kind, const Input& in, const std::string& problem) { throw Error(kind, in.name + ": " + problem); }

void check_claim(const Input& in, const ReadOptions& options, uint64_t count, uint64_t min_bytes_each,
                 size_t bytes_left, const char* what) {
  if (count > options.max_triangles) {
    fail(ErrorKind::TooLarge, in,
         "the header claims " + std::to_string(count) + " " + what + ", more than the limit of " +
             std::to_string(options.max_triangles) + ".");
  }
  if (min_bytes_each > 0 && count > bytes_left / min_bytes_each) {
    fail(ErrorKind::InvalidInput, in,
         "the header claims " + std::to_string(count) + " " + what + " but only " + std::to_string(bytes_left) +
             " bytes follow it.");
  }
}

std::string basename_of(const std::string& path) {
  const size_t slash = path.find_last_of("/\\");
  return slash == std::string::npos ? path : path.substr(slash + 1);
}

static std::string directory_of(const std::string& path) {
  const size_t slash = path.find_last_of("/\\");
  return slash == std::string::npos ? std::string(".") : path.substr(0, slash);
}

std::string quote(std::string_view text) {
  if (text.size() <= kMaxQuoted) return "'" + std::string(text) + "'";
  return "'" + std::string(text.substr(0, kMaxQuoted - 3)) + "...'";
}

namespace {

// Closes a file descriptor on every way out.
struct FileDescriptor {
  int fd;
  ~FileDescriptor() {
    if (fd >= 0) ::close(fd);
  }
};

}  // namespace

namespace {

// Not zero-filled before the read (crestline/numerics/uninitialised.h).
using FileBytes = UninitialisedVector<uint8_t>;

template <typename Bytes>
Bytes read_bytes(const std::string& path, const std::string& display_name, uint64_t max_bytes) {
  // O_NONBLOCK: opening a named pipe would otherwise wait for a writer.
  const FileDescriptor file{::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC)};
  if (file.fd < 0) {
    throw Error(ErrorKind::Io, display_name + ": the file cannot be opened (" + std::strerror(errno) + ").");
  }
  struct stat status {};
  if (::fstat(file.fd, &status) != 0) {
    throw Error(ErrorKind::Io, display_name + ": the file cannot be read (" + std::strerror(errno) + ").");
  }
  if (S_ISDIR(status.st_mode)) throw Error(ErrorKind::Io, display_name + ": this is a folder, not a file.");
  if (!S_ISREG(status.st_mode)) {
    throw Error(ErrorKind::Io, display_name + ": this is a device, pipe or socket, not a regular file.");
  }
  const uint64_t size = std::min<uint64_t>(uint64_t(std::max<off_t>(status.st_size, 0)), max_bytes);
  if (size > std::numeric_limits<size_t>::max() / 2) {
    throw Error(ErrorKind::TooLarge,
                display_name + ": the file is too large to read (" + std::to_string(size) + " bytes).");
  }
  Bytes bytes;
  try {
    bytes.resize(size_t(size));
  } catch (const std::bad_alloc&) {
    throw Error(ErrorKind::TooLarge,
                display_name + ": there is not enough memory to read the file (" + std::to_string(size) + " bytes).");
  }
  size_t done = 0;
  while (done < bytes.size()) {  // the size from fstat bounds the read even if the file grows
    const ssize_t n = ::read(file.fd, bytes.data() + done, bytes.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) {
      throw Error(ErrorKind::Io, display_name + ": the file cannot be read (" + std::strerror(errno) + ").");
    }
    if (n == 0) break;  // shrank meanwhile
    done += size_t(n);
  }
  bytes.resize(done);
  return bytes;
}

}  // namespace

std::vector<uint8_t> read_file(const std::string& path, const std::string& display_name, uint64_t max_bytes) {
  return read_bytes<std::vector<uint8_t>>(path, display_name, max_bytes);
}

namespace {

// True when `path` (canonical) is `folder` (canonical) or lies inside it.
bool is_inside(const std::filesystem::path& path, const std::filesystem::path& folder) {
  auto p = path.begin();
  for (auto f = folder.begin(); f != folder.end(); ++f, ++p) {
    if (f->empty()) continue;  // a trailing separator
    if (p == path.end() || *p != *f) return false;
  }
  return true;
}

}  // namespace

bool find_companion(const Input& in, const std::string& uri, uint64_t max_bytes, std::vector<uint8_t>& out) {
  // Only files in the model's folder or below: a URI is relative, has no
  // ".." and no scheme ("file:", "http:"), and no link may lead out. The
  // same rule holds for in-memory companions, so a file gives one outcome
  // natively, in the WASM CLI and in the page.
  namespace fs = std::filesystem;
  const fs::path relative(uri);
  const bool has_scheme = uri.find(':') != std::string::npos;
  if (relative.is_absolute() || relative.has_root_name() || (!uri.empty() && (uri[0] == '/' || uri[0] == '\\')) ||
      has_scheme) {
    fail(ErrorKind::InvalidInput, in,
         "the buffer URI " + quote(uri) + " is not a relative path; only files in the model's folder are read.");
  }
  for (const fs::path& part : relative) {
    if (part == "..") {
      fail(ErrorKind::InvalidInput, in,
           "the buffer URI " + quote(uri) +
               " leads out of the model's folder; only files in the model's folder are read.");
    }
  }
  if (in.companions) {
    for (const auto& pass : {uri, basename_of(uri)}) {
      for (const NamedBuffer& buffer : *in.companions) {
        if (buffer.name == pass || basename_of(buffer.name) == pass) {
          const size_t size = size_t(std::min<uint64_t>(buffer.bytes.size(), max_bytes));
          out.assign(buffer.bytes.begin(), buffer.bytes.begin() + ptrdiff_t(size));
          return true;
        }
      }
    }
  }
  if (in.directory.empty() || uri.empty()) return false;
  std::error_code error;
  const fs::path folder = fs::canonical(in.directory, error);
  if (error) return false;
  const fs::path target = fs::canonical(folder / relative, error);
  if (error) return false;  // absent (or a dangling link)
  if (!is_inside(target, folder)) {
    fail(ErrorKind::InvalidInput, in,
         "the buffer file " + quote(uri) +
             " is a link that leads out of the model's folder; only files in the model's folder are read.");
  }
  if (!fs::is_regular_file(target, error)) {
    fail(ErrorKind::InvalidInput, in, "the buffer file " + quote(uri) + " is not a regular file.");
  }
  out = read_file(target.string(), in.name + ": the buffer file " + quote(uri), max_bytes);
  return true;
}

void finish_soup(TriangleSoup& soup, const Input& in) {
  if (soup.indices.empty()) fail(ErrorKind::InvalidInput, in, "the file contains no triangles.");
  // On every thread: counts summed, and the first index out of range is the
  // smallest any part finds, so the message is the same for any count.
  const size_t vertices = soup.vertex_count(), indices = soup.indices.size();
  UninitialisedVector<char> non_finite(vertices);
  std::atomic<size_t> non_finite_count{0};
  crestline::detail::for_each_part(
      crestline::detail::part_count(vertices), vertices, [&](size_t, size_t begin, size_t end) {
        size_t count = 0;
        for (size_t v = begin; v < end; ++v) {
          const double* p = &soup.positions[3 * v];
          non_finite[v] = !std::isfinite(p[0]) || !std::isfinite(p[1]) || !std::isfinite(p[2]);
          count += size_t(non_finite[v]);
        }
        non_finite_count += count;
      });
  std::atomic<size_t> first_out_of_range{indices};
  std::atomic<bool> any_finite_referenced{false};
  crestline::detail::for_each_part(crestline::detail::part_count(indices), indices,
                                   [&](size_t, size_t begin, size_t end) {
                                     // The largest index first (a loop that vectorises), the
                                     // first one out of range only when there is one.
                                     uint32_t largest = 0;
                                     for (size_t k = begin; k < end; ++k) largest = std::max(largest, soup.indices[k]);
                                     for (size_t k = begin; largest >= vertices && k < end; ++k) {
                                       if (soup.indices[k] >= vertices) {
                                         crestline::detail::atomic_min(first_out_of_range, k);
                                         return;
                                       }
                                     }
                                     for (size_t k = begin; k < end; ++k) {
                                       if (!non_finite[soup.indices[k]]) {
                                         any_finite_referenced = true;
                                         return;
                                       }
                                     }
                                   });
  if (const size_t k = first_out_of_range; k < indices) {
    fail(ErrorKind::InvalidInput, in,
         "triangle " + std::to_string(k / 3) + " refers to vertex " + std::to_string(soup.indices[k]) +
             " but the file has " + std::to_string(vertices) + " vertices.");
  }
  if (!any_finite_referenced) {
    fail(ErrorKind::InvalidInput, in, "every vertex of every triangle has a NaN or infinite coordinate.");
  }
  if (non_finite_count > 0) {
    soup.notes.push_back(std::to_string(non_finite_count.load()) +
                         " vertices have NaN or infinite coordinates; their triangles are dropped.");
  }
}

// --- format detection -------------------------------------------------------

bool looks_like_text(const uint8_t* data, size_t size) {
  const size_t n = std::min<size_t>(size, 4096);
  for (size_t i = 0; i < n; ++i) {
    const uint8_t c = data[i];
    if (c < 9 || (c > 13 && c < 32) || c == 127) return false;
  }
  return true;
}

namespace {

bool starts_with(const uint8_t* data, size_t size, const char* prefix) {
  const size_t n = std::strlen(prefix);
  return size >= n && std::memcmp(data, prefix, n) == 0;
}

std::string lower_extension(const std::string& name) {
  const std::string base = basename_of(name);
  const size_t dot = base.find_last_of('.');
  if (dot == std::string::npos) return "";
  std::string ext = base.substr(dot + 1);
  for (char& c : ext) c = char(std::tolower(static_cast<unsigned char>(c)));
  return ext;
}

// The first whitespace-delimited word, after an optional UTF-8 byte-order mark.
std::string first_word(const uint8_t* data, size_t size) {
  size_t i = starts_with(data, size, "\xEF\xBB\xBF") ? 3 : 0;
  while (i < size && std::isspace(data[i])) ++i;
  std::string word;
  while (i < size && word.size() < 16 && !std::isspace(data[i])) word += char(data[i++]);
  return word;
}

bool looks_like_obj(const uint8_t* data, size_t size) {
  if (!looks_like_text(data, size)) return false;
  const std::string word = first_word(data, size);
  static const char* const keywords[] = {"#", "v", "vn", "vt", "f", "o", "g", "mtllib", "usemtl", "s"};
  return std::any_of(std::begin(keywords), std::end(keywords),
                     [&](const char* k) { return word == k || (word[0] == '#' && k[0] == '#'); });
}

}  // namespace

bool is_binary_stl_size(size_t size, const uint8_t* data) {
  if (size < 84) return false;
  uint32_t count = 0;
  std::memcpy(&count, data + 80, 4);  // little-endian on every target we build for
  return uint64_t(size) == 84 + 50 * uint64_t(count) && !looks_like_text(data, size);
}

}  // namespace detail

MeshFormat detect_format(const std::string& name, const uint8_t* bytes, size_t size) {
  using namespace detail;
  if (starts_with(bytes, size, "glTF")) return MeshFormat::Glb;
  const std::string word = first_word(bytes, size);
  if (word == "ply") return MeshFormat::Ply;
  if (word.size() >= 3 && word.compare(word.size() - 3, 3, "OFF") == 0 &&
      std::all_of(word.begin(), word.end(), [](char c) { return std::isupper(static_cast<unsigned char>(c)); })) {
    return MeshFormat::Off;
  }
  if (is_binary_stl_size(size, bytes)) return MeshFormat::Stl;
  if (word == "solid" && looks_like_text(bytes, size)) return MeshFormat::Stl;
  if (!word.empty() && word[0] == '{') return MeshFormat::Gltf;
  const std::string ext = lower_extension(name);
  if (ext == "obj") return MeshFormat::Obj;
  if (ext == "gltf") return MeshFormat::Gltf;
  if (ext == "glb") return MeshFormat::Glb;
  if (ext == "ply") return MeshFormat::Ply;
  if (ext == "stl") return MeshFormat::Stl;
  if (ext == "off") return MeshFormat::Off;
  if (looks_like_obj(bytes, size)) return MeshFormat::Obj;
  return MeshFormat::Auto;  // not recognised
}

namespace {

TriangleSoup dispatch_format(const detail::Input& in, const ReadOptions& options) {
  using namespace detail;
  const MeshFormat format =
      options.format == MeshFormat::Auto ? detect_format(in.name, in.data, in.size) : options.format;
  switch (format) {
    case MeshFormat::Obj:
      return read_obj(in, options);
    case MeshFormat::Gltf:
    case MeshFormat::Glb:
      return read_gltf(in, options);
    case MeshFormat::Ply:
      return read_ply(in, options);
    case MeshFormat::Stl:
      return read_stl(in, options);
    case MeshFormat::Off:
      return read_off(in, options);
    case MeshFormat::Auto:
      break;
  }
  if (in.size == 0) fail(ErrorKind::InvalidInput, in, "the file is empty.");
  fail(ErrorKind::Unsupported, in, "the format is not recognised (Crestline reads OBJ, glTF/GLB, PLY, STL and OFF).");
}

// Whatever a library throws becomes one sentence about the file too.
TriangleSoup dispatch(const detail::Input& in, const ReadOptions& options) {
  try {
    return dispatch_format(in, options);
  } catch (const Error&) {
    throw;
  } catch (const std::bad_alloc&) {
    detail::fail(ErrorKind::TooLarge, in, "there is not enough memory to read the file.");
  } catch (const std::exception& e) {
    detail::fail(ErrorKind::InvalidInput, in, std::string("the file cannot be read (") + e.what() + ").");
  }
}

}  // namespace

TriangleSoup read_mesh(const std::string& path, const ReadOptions& options) {
  detail::Input in;
  in.name = detail::basename_of(path);
  const detail::FileBytes bytes = detail::read_bytes<detail::FileBytes>(path, in.name, UINT64_MAX);
  in.data = bytes.data();
  in.size = bytes.size();
  in.directory = detail::directory_of(path);
  return dispatch(in, options);
}

TriangleSoup read_mesh_bytes(const std::string& name, const std::vector<uint8_t>& bytes,
                             const std::vector<NamedBuffer>& companions, const ReadOptions& options) {
  detail::Input in;
  in.name = detail::basename_of(name);
  in.data = bytes.data();
  in.size = bytes.size();
  in.companions = &companions;
  return dispatch(in, options);
}

}  // namespace crestline::io
