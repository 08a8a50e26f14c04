#pragma once
// One entry for every input format. Readers parse only; welding and repair
// happen afterwards in repair_mesh.
#include <cstdint>
#include <string>
#include <vector>

#include "crestline/mesh/mesh.h"

namespace crestline::io {

enum class MeshFormat { Auto, Obj, Gltf, Glb, Ply, Stl, Off };

struct ReadOptions {
  MeshFormat format = MeshFormat::Auto;  // Auto: detect from content, then extension
  /// Refuse files that claim more than this many triangles or vertices
  /// before allocating for them.
  size_t max_triangles = 50'000'000;
  /// glTF instances (nodes sharing a mesh, EXT_mesh_gpu_instancing) may
  /// expand the triangles a scene stores to at most the larger of
  /// `max_expanded_triangles` and `max_expansion` times the triangles stored
  /// (each placed mesh counted once), checked before anything is expanded.
  /// Past that a small file would cost what a huge one does (a 1 MB glTF
  /// placing 48 triangles 10^6 times took 4 GB and 18 s). Any scene may
  /// expand to 4·10^6 triangles, what a stored mesh of that size costs;
  /// beyond, the work stays within 16 times that of the stored triangles,
  /// room for assemblies of repeated parts (the largest ratio among the
  /// test meshes is 1.27, CesiumMilkTruck's wheels).
  size_t max_expanded_triangles = 4'000'000;
  size_t max_expansion = 16;
};

/// Reads a file. Multi-file glTF resolves .bin files relative to `path`.
/// Throws crestline::Error with a one-sentence message naming the file
/// (its basename): InvalidInput for broken data (indices out of range, no
/// triangles, every vertex NaN/infinite, truncated data), Unsupported for a
/// format or variant we do not read (and, in the WASM build, Draco/meshopt
/// compressed glTF, which the browser decodes), TooLarge for claims beyond
/// `max_triangles` or beyond memory, Io when the file or a .bin is missing
/// or not a regular file. External glTF buffers are read only from inside
/// the folder of `path` and never past their byteLength; glTF instances are
/// counted against `max_triangles`, `max_expanded_triangles` and
/// `max_expansion` before they are expanded (README, "Limits").
///
/// The soup is as stored: OBJ/PLY/OFF vertices in file order, one vertex per
/// STL facet corner, glTF vertices per primitive instance (world space).
/// Polygons are ear-clipped in their best-fit plane (n - 2 triangles each).
/// Vertices with NaN/infinite coordinates are kept (noted); repair_mesh
/// drops their triangles. glTF: the default scene (else scene 0, else all
/// root nodes), instances expanded, TRIANGLES/STRIP/FAN primitives; points
/// and lines are skipped with a note.
TriangleSoup read_mesh(const std::string& path, const ReadOptions& options = {});

/// Reads from memory (the browser). `name` is used for messages and for the
/// extension hint. External glTF resources are looked up in `companions`
/// by their URI (may be empty).
struct NamedBuffer {
  std::string name;
  std::vector<uint8_t> bytes;
};
TriangleSoup read_mesh_bytes(const std::string& name, const std::vector<uint8_t>& bytes,
                             const std::vector<NamedBuffer>& companions = {}, const ReadOptions& options = {});

MeshFormat detect_format(const std::string& name, const uint8_t* bytes, size_t size);

}  // namespace crestline::io
