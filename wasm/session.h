#pragma once
// The handle JavaScript holds: one repaired mesh and its Pipeline. It only
// converts (typed arrays in, copied typed arrays out — heap views die when
// memory grows) and turns every exception into {error, kind}; all geometry
// lives in core/.
#include <emscripten/val.h>

#include <memory>
#include <string>

#include "crestline/mesh/repair.h"
#include "crestline/parameters.h"
#include "crestline/pipeline.h"

namespace crestline::wasm {

using emscripten::val;

class Session {
 public:
  /// positions: Float64Array or Float32Array (x,y,z per vertex); indices:
  /// Uint32Array (3 per triangle); options: {weldTolerance, maxTriangles}.
  /// Repairs the soup (repair_mesh) and builds a Pipeline on it.
  /// Returns {ok, vertices, triangles, report:{…}, notes:[…]} or {error, kind}.
  val load(val positions, val indices, val options);
  /// Reads a file with the native CLI's readers (io::read_mesh_bytes), then
  /// as load(). name: the file's name, for messages and the format hint;
  /// bytes: Uint8Array; companions: [{name, bytes}], a .gltf's external
  /// files (may be empty or undefined); options: as load(). Notes include
  /// the reader's. Draco/meshopt glTF returns {error, kind: "unsupported"}:
  /// the browser decodes those.
  val loadFile(std::string name, val bytes, val companions, val options);

  /// Sets parameters of the table (crestline/parameters.h) by their keys;
  /// missing ones keep their value. Values: numbers, booleans, a choice's
  /// name, or "auto" where describe() says `automatic`. Also `vertexWeights`
  /// (Float64Array, one per vertex, or null). All or nothing: an unknown key
  /// or a value outside its range returns {error, kind: "usage"} naming the
  /// key, and changes nothing. Works before a mesh is loaded (the settings
  /// carry over to every mesh loaded later; weights do not). Cheap: only
  /// marks stages dirty.
  val setOptions(val options);
  /// Every parameter's current value by key ("auto" for the automatic mode),
  /// plus `weighted`. Without a mesh: the defaults, unless set.
  val options() const;
  /// The parameter table for JavaScript: an array, in --help's order, of
  /// {key, flag, group, kind: "integer"|"number"|"boolean"|"choice",
  /// automatic (may be "auto"), default, min, max, choices, unit, help,
  /// stage (the first stage a change re-runs, or null)}. See wasm/README.md.
  val describe() const;

  /// Runs the dirty stages. progress(stageName, fraction) may return false
  /// to cancel. Returns {ok, ran:[stage names], stats} or {cancelled} or
  /// {error, kind}.
  val run(val progress);

  /// {positions: Float64Array, indices: Uint32Array, view} of the repaired
  /// input mesh: the lines are placed on it even when pre-smoothing traced
  /// them on a smoothed copy. view: what a viewer draws, {positions:
  /// Float32Array relative to origin, normals: Float32Array (unit,
  /// area-weighted), origin: Float64Array (the bounding box's centre),
  /// radius: the bounding sphere's about it, closed: is_closed_outward
  /// (its back faces are hidden from outside)}.
  val surface() const;
  /// Ridges and valleys as flat arrays: {points: Float64Array (xyz), offsets: Uint32Array
  /// (lineCount+1, in points), types: Uint8Array (0 ridge, 1 valley),
  /// strengths, lengths: Float64Array, closed: Uint8Array}. `all` selects
  /// every faired line instead of those passing the filter.
  val lines(bool all) const;
  /// Uint32Array: the indices into lines(true) of the lines that pass the
  /// filter, in order (a threshold change needs only these).
  val keptLines() const;
  /// The sharp creases (lines/creases.h) as flat arrays: {points, offsets,
  /// closed, strengths, lengths} as in lines(), plus convex: Uint8Array (1 where
  /// the dihedral angle is positive, an outer edge) and angles: Float64Array
  /// (the mean |dihedral angle| along each line, degrees). Their own call, so
  /// that lines() keeps ridges and valleys only; a new creaseAngle re-runs
  /// only the crease selection.
  val creases() const;
  /// Per-vertex kappaMax, kappaMin, eMax, eMin (Float64Array, pointwise) and
  /// per-triangle regularMax, regularMin (Uint8Array).
  val fields() const;
  val stats() const;
  /// The filtered lines in the native CLI's formats (the shared writers):
  /// OBJ, JSON with stats, the stats JSON alone.
  std::string linesObj() const;
  std::string linesJson() const;
  std::string statsJson() const;
  /// SVG (io::write_lines_svg, the CLI's writer) drawn with the session's SVG
  /// parameters (view, svgWidth, strokeWidth, silhouette,
  /// svgSurfaceTolerance), overridden by `options` with the same keys, plus
  /// what a viewer shows: camera {matrix: 16 numbers, column-major, model →
  /// clip (three.js projectionMatrix · matrixWorldInverse · the model's
  /// matrixWorld), width, height (pixels)} instead of `view`; ridges,
  /// valleys, creases (booleans: drawn or not); ridgeColor, valleyColor,
  /// creaseColor, concaveColor, silhouetteColor, background (CSS colours).
  /// Returns the text or {error, kind}.
  val linesSvg(val options) const;
  /// GLB (io::write_glb, the CLI's `--with-mesh` writer): the surface and the
  /// filtered lines, creases included, as a Uint8Array; `options` {ridges,
  /// valleys, creases} (booleans, default true) leave groups out (an empty
  /// node stays). Returns the bytes or {error, kind}.
  val linesGlb(val options) const;

 private:
  /// Repairs `soup` and builds the Pipeline on it: the shared end of load()
  /// and loadFile().
  val adopt(TriangleSoup soup, const RepairOptions& repair);

  Settings settings_;  // pipeline and SVG parameters, kept across loads
  std::unique_ptr<Pipeline> pipeline_;
  bool closed_outward_ = false;  // is_closed_outward of the loaded mesh (surface()'s view.closed)
  size_t triangles_ = 0;
};

}  // namespace crestline::wasm
