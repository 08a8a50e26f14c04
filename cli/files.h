#pragma once
// The CLI's only contact with the filesystem besides io::read_mesh.
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "crestline/io/write_lines.h"
#include "crestline/mesh/mesh.h"

namespace crestline::cli {

/// Writes `text` to `path` atomically: to `path`.tmp first, then renamed over
/// `path`, so a failure never leaves a partial output behind. Throws
/// Error(Io) without a file name (the caller knows it).
void write_file_atomically(const std::string& path, const std::string& text);
/// The same with the text made by `write`, which hands it to its sink in
/// pieces: written as they come, never held whole.
void write_file_atomically(const std::string& path, const std::function<void(const io::TextSink&)>& write);

/// The most bytes read from a weights file for a mesh of `vertices` input
/// vertices: 100 per vertex plus 1 MiB for comments.
uint64_t max_weights_bytes(size_t vertices);

/// Reads one number per line (blank lines and lines starting with # are
/// skipped) and matches them to the repaired mesh's vertices: one per vertex
/// of the input file, in its order, carried over by position (repair welds,
/// drops and renumbers vertices), or else one per repaired vertex (the order
/// of the surface --with-mesh writes). Only a regular file is read, and at
/// most max_weights_bytes of it. Throws Error(InvalidInput), Io, TooLarge.
std::vector<double> read_vertex_weights(const std::string& path, const TriangleSoup& soup, const Mesh& mesh);

}  // namespace crestline::cli
