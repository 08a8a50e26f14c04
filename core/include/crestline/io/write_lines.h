#pragma once
// Output formats for feature lines. Each returns the file's text, or hands
// it to a sink in pieces; the caller writes it (the core never touches the
// filesystem in a stage).
#include <Eigen/Core>
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "crestline/lines/polylines.h"
#include "crestline/mesh/topology.h"
#include "crestline/pipeline.h"

namespace crestline::io {

/// The creases' default colour (amber), in every writer: the SVG's
/// SvgOptions::crease_color and the GLB's "crease" material. The page and the
/// widget use the same one (web/src: their crease-colour defaults).
constexpr const char* kCreaseColor = "#e08a00";

/// OBJ contract: `v` lines, then `o ridges` with one `l i j k …` per
/// polyline (closed ones repeat their first index at the end), then
/// `o valleys` likewise, then `o creases` likewise if there are any.
std::string write_lines_obj(const std::vector<Polyline>& lines);

/// Receives a text writer's output in order, in pieces of about 1 MB (the
/// last one shorter): the same bytes as the writer's string, never held whole.
using TextSink = std::function<void(std::string_view piece)>;
void write_lines_obj(const std::vector<Polyline>& lines, const TextSink& sink);

/// The welded surface and the lines in one OBJ: `o surface` with its `v` and
/// `f` lines (1-based, in mesh order), then the lines exactly as in
/// write_lines_obj with their indices numbered after the surface's vertices.
std::string write_mesh_and_lines_obj(const Mesh& mesh, const std::vector<Polyline>& lines);
void write_mesh_and_lines_obj(const Mesh& mesh, const std::vector<Polyline>& lines, const TextSink& sink);

/// A glTF 2.0 binary (GLB): one buffer; float32 POSITION accessors with
/// min/max and uint32 indices. With a mesh, node "surface" holds it as one
/// TRIANGLES primitive (grey material). Nodes "ridges" and "valleys" hold one
/// LINE_STRIP primitive (mode 3) per polyline (red and blue materials);
/// closed lines repeat their first point at the end. Lines with fewer than
/// two points are left out; an empty group is still a node without a mesh.
/// Node "creases" (kCreaseColor) follows only if there are creases; each of its
/// primitives has extras {"convex": b}.
std::vector<uint8_t> write_glb(const Mesh* mesh, const std::vector<Polyline>& lines);

/// {"ridges":[{"points":[[x,y,z],…],"strength":s,"length":l,"closed":b}…],"valleys":[…],
///  "creases":[{…,"convex":b}…],"stats":{…}} — "creases" is always there (maybe empty).
std::string write_lines_json(const std::vector<Polyline>& lines, const PipelineStats& stats);
void write_lines_json(const std::vector<Polyline>& lines, const PipelineStats& stats, const TextSink& sink);

/// The stats object alone (also what `crestline --stats` prints).
std::string stats_json(const PipelineStats& stats);

enum class View { Front, Back, Left, Right, Top, Bottom };

/// A camera for the SVG drawing instead of a fixed View: what a viewer shows.
struct SvgCamera {
  /// Model coordinates → clip space, for column vectors (clip = matrix · [p, 1]),
  /// OpenGL's convention: visible where -w ≤ x, y, z ≤ w, y up. A perspective
  /// matrix (last row not (0,0,0,1)) or an orthographic one, e.g. a three.js
  /// camera's projectionMatrix · matrixWorldInverse · the object's matrixWorld.
  /// The view part must not scale: depths are compared in model units.
  Eigen::Matrix4d matrix = Eigen::Matrix4d::Identity();
  int width = 1000, height = 1000;  // pixels of the drawing, the camera's frame
};

struct SvgOptions {
  View view = View::Front;
  int width = 1000;  // pixels of the longer side; the other follows the aspect ratio
  double stroke_width = 1.5;
  std::string ridge_color = "#c0392b";
  std::string valley_color = "#2471a3";
  std::string crease_color = kCreaseColor;  // group "creases", each path class "convex" or "concave"
  std::string concave_color;                // concave creases get their own stroke; empty: crease_color
  bool silhouette = false;                  // also draw the surface's outline (group "silhouette")
  std::string silhouette_color = "#555555";
  bool ridges = true, valleys = true, creases = true;  // which groups are drawn
  std::string background;                              // a rectangle under the lines; empty: none
  /// With a camera, `view` and `width` are not used: the drawing is the
  /// camera's frame and parts outside it are cut.
  std::optional<SvgCamera> camera;
  /// How far (in mean edge lengths of `surface`) a line may lie off the
  /// surface and still count as on it: faired lines move up to
  /// FairingOptions::hausdorff_bound, and chords between crossings on curved
  /// triangles sag. Larger values let lines show through thin parts.
  double surface_tolerance = 0.5;
};

/// Orthographic drawing of the lines with the parts hidden by `surface` removed.
/// Linear in the mesh size; the silhouette needs adjacency, built here.
std::string write_lines_svg(const std::vector<Polyline>& lines, const Mesh& surface, const SvgOptions& options);
/// The same, reusing the surface's adjacency (e.g. Pipeline::topology()) for
/// the silhouette instead of building it (about a second per 1M triangles).
std::string write_lines_svg(const std::vector<Polyline>& lines, const Mesh& surface, const Topology& topology,
                            const SvgOptions& options);

}  // namespace crestline::io
