#include "crestline/lines/creases.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <functional>
#include <limits>

#include "../numerics/select.h"
#include "crestline/mesh/cotan.h"
#include "crestline/mesh/presmooth.h"
#include "crestline/numerics/constants.h"
#include "crestline/numerics/parallel.h"
#include "crestline/numerics/portable_math.h"

namespace crestline {
namespace {

constexpr double kDegree = kPi / 180.0;

// The normal filter: a guided bilateral filter [Zhang et al. 2015, without
// the spatial kernel]. Each face normal becomes the area-weighted mean of the
// normals of the faces around its three corners, each weighted by
// exp(−(1 − g·n) / (1 − cos kRangeAngle)), where the guide g is the mean
// normal of the face's most consistent corner fan (one off the crease, if
// any). Neighbours across a crease hardly count, so creases stay sharp while
// noise averages out. Measured on tests/quality's CAD-like surfaces
// (crestline_crease_report): a single-edge test at 35° on the raw normals
// flags 2–5 % of the flat edges at noise σ = 0.1 mean edges and 27–33 % at
// 0.25; a range of 30° lost the 45° chamfer, 20° kept it; 12 steps left fewer
// false creases than 6 at σ = 0.25 (precision 0.96 against 0.86).
constexpr double kRangeAngle = 20.0;

// Spurs: a chain with a free end (or two) shorter than 12 mean edges is
// dropped and the remaining crease edges are chained again, so that a spur
// does not split a true crease at the junction it hangs on. The filter's rule
// (lines/filter.cpp) also asks for weakness; here length alone decides:
// measured on shared/meshes, the free-ended crease lines of scans (bunny,
// feline, mannequin) are 0.3–12.6 edges long with strength up to 17 (∑
// |angle|·length / h), while the CAD parts' short creases run between
// corners. kSpurStrength stays for tuning.
constexpr double kSpurStrength = 1e9;
constexpr double kSpurEdges = 12.0;
// The spur rule counts in median edges where long slivers make the mean
// edge more than this many times the median: robust/obj/badstl-pcbvicebar,
// an STL bar 150 long, has a mean edge of 10.9 and a median of 3.2, and 12
// mean edges dropped most of its sharp edges as spurs. The mean is 0.98–1.14
// medians on the scans under shared/meshes, 0.70–2.63 on the CAD parts
// (crank, propeller and cessna above 2: only crank's creases changed, its
// spline's teeth now found).
constexpr double kSliverMeanRatio = 2.0;
// Near a corner a triangle whose three corners lie on creases may have all
// its edges selected, or the crease may cut across it: a tiny cycle, or a
// piece between two junctions or sharp turns. Pieces that short are dropped
// (the creases then end within an edge of the corner).
constexpr double kCornerChainEdges = 2.0;
// Bubbles (select_creases, on noisy surfaces only): where two chains join the
// same two junctions, both shorter than kBubbleEdges mean edges and every
// vertex of one within kBubbleWidth mean edges of the other's, the weaker
// goes. On noisy surfaces a crease passes on both sides of a triangle or two,
// or a bridge runs beside it, and the junctions split the line in pieces: at
// σ = 0.25 the filleted box's fragments went from up to 2.33 lines per edge
// to 1.83 (12 edges) and, with the longer bridges, 2.50 to 2.17 (40 edges).
constexpr double kBubbleEdges = 40.0;
constexpr double kBubbleWidth = 3.0;
// Hysteresis: free ends continue along edges of at least this share of the
// angle, for up to this many edges.
constexpr double kHysteresisShare = 0.6;
constexpr int kHysteresisRounds = 3;
// Bridging (bridge_gaps): walks along edges whose support (over
// kBridgeRings rings) reaches kBridgeShare × the angle, or kBridgeWeakShare ×
// the angle for at most kBridgeWeakRun edges in a row, for at most
// kBridgeEdges edges. A walk's direction is that of its last kBridgeBack
// edges (the end's chain's at first; one edge alone may be a noise detour);
// it goes on within 60° of it. With the direction of the walk's last edge
// alone (before 2026-12-02) walks followed their own detours off the crease:
// σ = 0.25, --seeds 3, coverage mean 0.901 → 0.954 and min 0.684 → 0.789,
// targets met 7 → 12, lines per true edge mean 1.21 → 1.08 (max 2.00 →
// 1.33; before redundant chains were dropped this direction alone left them
// at 1.39, the new joins making junctions), precision min 0.987, σ = 0.1
// byte-identical. Measured (crestline_crease_report, 3 seeds): a share of
// 0.8 with no weak edges drew twice the false crease lines of 1.0 on the
// noisy anisotropic smooth meshes; 1.2 lost coverage at σ = 0.1. At σ = 0.25
// the 45° chamfer's support over 2 rings is below 35° for 8–12 % of its
// edges, over 3 rings for 2.4–5.8 % (below 28° for 0–0.8 %), so the walks
// read 3 rings and step over up to two edges of 0.6 × the angle; and gaps of
// any length close: 200 edges instead of 12 raised the coverage at σ = 0.25
// from 0.86 to 0.89 (mean; min 0.48 → 0.66), the false lines on the smooth
// meshes unchanged. Walks that also kept free ends extended (not only gaps
// closed), or that joined only other free ends, did worse.
constexpr double kBridgeShare = 1.0;
constexpr double kBridgeWeakShare = 0.6;
constexpr int kBridgeWeakRun = 2;
constexpr int kBridgeEdges = 200;
constexpr int kBridgeRings = 3;
constexpr int kBridgeBack = 3;
constexpr double kBridgeCos = 0.5;
// Where no edge lies within 60° of the walk's direction (a vertex of valence
// 6 whose edges fall just outside it after a detour: 7 of the 9 walks that
// failed on the chamfered cylinder at σ = 0.25, seed 1, uniform mesh, 7 of
// 17 on the checker mesh), the
// walk goes on along the strongest edge ahead (within 90°) if its support
// reaches the angle; on very noisy surfaces only (above kVeryNoisyCreaseLevel:
// on two meshes of shared/meshes at noise level 0.09–0.10, fandisk-quads and
// OrientationTest.glb, it changed the creases and, through the crease cut,
// the smooth lines). σ = 0.25, --seeds 3 (before → after): coverage mean
// 0.954 → 0.969, min 0.789 → 0.846, targets met 12 → 13 (with redundant
// loops dropped too, which only this makes), lines per true edge mean 1.08
// → 1.06, precision min 0.987 both; σ = 0.1 byte-identical. Within 78° (cos
// 0.2) instead: coverage 0.967; weak steps allowed there too: precision
// 0.963; also joining free ends 2–3 edges apart by a shortest path: false
// creases on the smooth harness at σ = 0.25 (5–6 lines).
constexpr double kBridgeWideCos = 0.0;
// On the noisiest surfaces that bridging runs on (noise level above
// kNoisiestCreaseLevel) a walk's weak run may go on past kBridgeWeakRun
// while the mean support of its last kLongWeakSpan edges (the new one among
// them) reaches kSupportShare × the angle. At σ = 0.25 the 45° chamfer's
// support runs at 28–33° (the angle 35°) for stretches of 3–5 edges: the
// walks stopped there after two weak edges, two edges short of the other
// end's, and a 10 h gap stayed open on the checker meshes (seeds 1 and 2; the
// Pipeline's own creases, in its working frame, also on the irregular mesh
// at seed 2, 24 h of ridges in the gap). Measured (crestline_crease_report
// --seeds 3, before → after): σ = 0.25 targets met 24 → 26 of 27, coverage
// min 0.967 → 0.979, smooth lines within 1 h of a sharp edge with crease
// boundaries 72 → 34 h over the 27 cases (the cylinder's 38 → 0); σ = 0 and
// 0.1 and the smooth harness unchanged.
constexpr size_t kLongWeakSpan = 4;
// The long weak runs above run above this noise level: normal noise σ = 0.25
// mean edges measures 0.198–0.224 (the CAD-like surfaces 0.211–0.222),
// σ = 0.2 0.166–0.184. Above kVeryNoisyCreaseLevel instead, the only file
// under shared/meshes that changed, smooth/cgal-knot2 (noise level 0.153;
// its creases are the corners of a twisted pentagonal tube), had creases
// rerouted where the tube turns towards the view (30 → 26 lines, SVG), not
// clearly better.
constexpr double kNoisiestCreaseLevel = 0.19;
// Bridging again once the spur rounds are done (select_creases), up to this
// many walks from every free end in all: the spurs that hung on a crease made
// junctions, which the first walks did not start from, and their going leaves
// free ends facing a gap (on the notched prism at σ = 0.25 the notch's edges
// lost 2–10 mean edges beside the corners so). Measured
// (crestline_crease_report --seeds 6, σ = 0.25, 54 cases, with the
// half-bridges and the end direction of bridge_gaps): targets met 36 → 46
// with one more pass, 47 with up to three more; σ = 0 and 0.1 and the smooth
// harness unchanged.
constexpr int kBridgePasses = 4;
// The automatic angle: kDefaultCreaseAngle, or this many times the median
// dihedral angle where that is larger. Measured on shared/meshes (median
// |dihedral| of the raw normals): CAD parts 0.0–1.6° (fandisk, mechpart, club,
// casting), where 35° finds their sharp edges; scans 2.5–8.3° (mannequin
// 2.5, bunny 4.1, feline 5.4, armadillo 8.3), whose folds of 35–70° are
// scanning detail, not machined edges: 12× gives them 35°, 49°, 65°, 100°.
constexpr double kMedianFactor = 12.0;
// Not on piecewise-planar meshes (low-poly models, coarse CAD tessellations:
// surface_noise_level at most this, rounding aside), whose edges are flat
// or creases: a box's median edge turns by 90°, and 12× that left every box
// under shared/meshes (glb/Box, robust/obj/*box*, the hundred cubes) without
// creases, as it did the Platonic solids and the OrientationTest's blocks.
constexpr double kPlanarNoiseLevel = 1e-6;
bool piecewise_planar(const CreaseAngles& angles) {
  return angles.noise_measured && angles.noise_level <= kPlanarNoiseLevel;
}
// Edges whose dihedral is below this (degrees) are never creases: their
// support is not computed.
constexpr double kCandidateAngle = 20.0;
// An edge is a crease if both its dihedral angle and its support (the angle
// between the mean raw normals on either side, side_support) reach the
// threshold times this share.
constexpr double kSupportShare = 0.8;
// Support is measured over the faces around the edge's ends, on noisy
// surfaces over those within two rings: at σ = 0.25 mean edges that halved
// the crease lines on the noisy smooth surfaces of tests/quality.
constexpr int kNoisySupportRings = 2;
// On very noisy surfaces (noise level above kVeryNoisyCreaseLevel; normal noise
// σ = 0.25 mean edges is ~0.21) the support reads three rings and counts only
// where it is a local maximum across the edge: at least that with the
// splitting plane moved by kSuppressionShift × the edge's length to either
// side (non-maximum suppression [Canny]). There 2.5–4.5 % of the flat edges
// beside a crease pass the angle and the 2-ring support; they hang on the
// crease as spurs and bubbles, and split it at junctions. Measured
// (crestline_crease_report --seeds 6, σ = 0.25, 54 cases; before → after):
// targets met 5 → 11, precision min 0.944 → 0.983, lines per true edge mean
// 1.49 → 1.38 (max 2.67 → 2.33), coverage mean 0.890 → 0.897 (one filleted
// box loses a short edge: 0.81); crease lines on the noisy smooth surfaces
// 9 → 0 at σ = 0.25, 140 → 11 at 0.5. Measured and not kept (--seeds 3 or
// 6): 2 rings with suppression (the 9 lines stay), 3 rings without it
// (precision 0.958), a shift of half an edge (8 of 54 met), 4 rings (13 of
// 54 but precision 0.965), and suppressed support alone, edges whose
// filtered angle is below kCandidateAngle taking it as their angle: the
// chamfer found (coverage 0.92–0.98) but in 3–5 pieces per edge.
constexpr int kVeryNoisySupportRings = 3;
// Redundant chains (drop_redundant_chains), on very noisy surfaces too, once
// no spur or bubble is left: those within this many rings of other chains
// all along. Measured (crestline_crease_report --seeds 3, σ = 0.25, 27
// cases; before → after): targets met 4 → 7, lines per true edge mean 1.39 →
// 1.21 (max 2.25 → 2.00), coverage the same (mean 0.90, min 0.68), precision
// min 0.983 → 0.987; 1 ring: 7 met, 1.23 lines per edge. The smooth harness
// at σ = 0.5: 11 → 9 false lines. Only where the support is suppressed
// (very noisy): on cleaner meshes two creases two rings apart are real (a
// narrow chamfer).
constexpr int kRedundantRings = 2;
// Splices (drop_redundant_chains, on the very noisy surfaces bridging runs
// on): a redundant chain whose mean |angle| exceeds that of every chain it
// lies beside (not those it meets at its ends) by 1 / kSpliceShare is the
// crease, and the others' stretches beside it (edges with both ends within
// kRedundantRings rings of it) go instead; where such a stretch leaves the
// rest of a chain, the shortest path joins it to the crease. On the notched
// prism's bottom cap, whose rings are 0.42 h apart beside the front wall,
// the 3-ring support the bridge walks read stays high one and two rows
// inside the fold (rim 69–92°, first ring 57–74°, second 26–64°); a walk
// from the corner's piece stepped up to the second ring and ran along it,
// 0.83 h from the rim's crease and never touching it, to the far corner, and
// the rim's two pieces (mean 78° and 89°), each wholly beside that walk's
// chain (54°, itself not redundant as it went on to the corner), were
// dropped: the crease cut two rows off, a ridge on the wall 1.2–2 h above
// the edge (σ = 0.25, uniform walls, seed 2, in the Pipeline's frame). At
// most kSplices rounds, so that joins and cuts cannot cycle. Measured
// (crestline_crease_report --seeds 6, every noise level and the smooth
// harness): that case's smooth lines within 2 h of a sharp edge 24.1 → 0 h
// (within 1 h 1.5 → 0), one other prism case 10.4 → 9.8 h, nothing else
// changed (cases meeting every target 160 of 162 both).
constexpr double kSpliceShare = 0.8;
constexpr int kSplices = 64;
constexpr size_t kSpliceSearch = 400;
constexpr double kSuppressionShift = 1.0;
// The span over which a chain's turn is measured, in mean edges.
// On noisy surfaces that bridging runs on (noise level up to
// kBridgeNoiseLimit) over 4: at σ = 0.25 the zigzags of a crease turn by
// more than 60° over 2 mean edges, which split the box's edges into up to 1.8
// pieces (1.3 over 4 edges; crestline_crease_report). Not above: at σ = 0.5
// the longer pieces of false creases on smooth surfaces outlive the spur rule
// (124 → 166 lines).
constexpr double kTurnSpanEdges = 2.0;
constexpr double kNoisyTurnSpanEdges = 4.0;

// Faces around a vertex, in the filter and the support: fans larger than
// this are left out (their vertex contributes nothing), so that a vertex of
// degree 10,000 (tests/unit/hardening) costs linear time, not quadratic.
constexpr uint32_t kMaxFan = 64;
bool small_fan(const Topology& topology, uint32_t v) {
  return topology.vertex_offsets[v + 1] - topology.vertex_offsets[v] <= kMaxFan;
}

// Appends the vertices of the triangles round each small-fan vertex of
// `from` to `to`, then sorts `to` and drops repeats: one ring's step.
void add_one_ring(const Mesh& mesh, const Topology& topology, const std::vector<uint32_t>& from,
                  std::vector<uint32_t>& to) {
  for (uint32_t u : from)
    if (small_fan(topology, u))
      for (uint32_t j = topology.vertex_offsets[u]; j < topology.vertex_offsets[u + 1]; ++j)
        for (uint32_t w : mesh.triangles[topology.vertex_triangles[j]]) to.push_back(w);
  std::sort(to.begin(), to.end());
  to.erase(std::unique(to.begin(), to.end()), to.end());
}

struct FaceNormals {
  std::vector<Vec3> normal;  // unit (zero for degenerate faces)
  // Empty where only the support reads the areas (no normal filter): made
  // there for the few faces it reads (face_area), the same bits.
  std::vector<double> area;
};

FaceNormals face_normals(const Mesh& mesh) {
  FaceNormals out;
  triangle_areas_normals(mesh.positions, mesh.triangles, out.area, out.normal);
  return out;
}

// The normals alone (triangle_normals: triangle_areas_normals' bits).
FaceNormals face_normals_only(const Mesh& mesh) {
  FaceNormals out;
  triangle_normals(mesh.positions, mesh.triangles, out.normal);
  return out;
}

// Face g's area: ½ triangle_normal, as triangle_areas_normals has it.
double face_area(const Mesh& mesh, const FaceNormals& faces, uint32_t g) {
  if (!faces.area.empty()) return faces.area[g];
  const Triangle& f = mesh.triangles[g];
  Vec3 unit;
  return 0.5 * triangle_normal(mesh.positions[f[0]], mesh.positions[f[1]], mesh.positions[f[2]], unit);
}

// Each vertex's and each face's values from the last step's alone: on any
// number of threads, the same bits. after_step, if set, is called after each step.
std::vector<Vec3> filter_normals(const Mesh& mesh, const Topology& topology, const FaceNormals& faces, int steps,
                                 const std::function<void(int step)>& after_step) {
  std::vector<Vec3> normal = faces.normal, next(normal.size());
  const double scale = 1.0 / (1.0 - portable_cos(kRangeAngle * kDegree));
  const size_t nv = mesh.positions.size();
  std::vector<Vec3> fan_mean(nv);
  std::vector<double> fan_spread(nv);
  std::vector<uint32_t> guide_of(normal.size());
  for (int step = 0; step < steps; ++step) {
    // Guidance: the mean normal of the most consistent corner fan of each
    // face (a fan off the crease, where there is one), so that the range
    // weights compare with the face's side of a crease rather than with the
    // face's own noisy normal.
    parallel_for(nv, [&](size_t first, size_t last) {
      for (size_t v = first; v < last; ++v) {
        Vec3 sum = Vec3::Zero();
        for (uint32_t k = topology.vertex_offsets[v]; k < topology.vertex_offsets[v + 1]; ++k) {
          const uint32_t g = topology.vertex_triangles[k];
          sum += faces.area[g] * normal[g];
        }
        const double len = sum.norm();
        fan_mean[v] = len > 0 ? Vec3(sum / len) : Vec3::Zero();
        double spread = 0, area = 0;
        for (uint32_t k = topology.vertex_offsets[v]; k < topology.vertex_offsets[v + 1]; ++k) {
          const uint32_t g = topology.vertex_triangles[k];
          spread += faces.area[g] * (1.0 - fan_mean[v].dot(normal[g]));
          area += faces.area[g];
        }
        fan_spread[v] = area > 0 ? spread / area : 2.0;
      }
    });
    parallel_for(normal.size(), [&](size_t first, size_t last) {
      for (size_t f = first; f < last; ++f) {
        const Triangle& t = mesh.triangles[f];
        uint32_t best = t[0];
        for (uint32_t v : t)
          if (fan_spread[v] < fan_spread[best]) best = v;
        guide_of[f] = best;
      }
    });
    // Each face's sum, by the vertex whose fan mean guides it: the faces
    // that one guide serves share its corners' fans' weighted sums (a
    // corner fan's sum is formed once per guide, not once per face).
    parallel_for(nv, [&](size_t first, size_t last) {
      struct CornerSum {
        uint32_t corner;
        Vec3 sum;
      };
      std::vector<CornerSum> sums;
      for (size_t b = first; b < last; ++b) {
        // (A large fan's mean costs nothing more: it is computed once per vertex.)
        const Vec3& guide = fan_mean[b];
        sums.clear();
        // Kept for a small fan's guide only (at most 2 kMaxFan + 1 corners
        // to search): a vertex of degree 10,000 stays linear.
        const bool keep = small_fan(topology, b);
        const auto corner_sum = [&](uint32_t v) {
          if (keep)
            for (const CornerSum& c : sums)
              if (c.corner == v) return c.sum;
          Vec3 sum = Vec3::Zero();
          for (uint32_t k = topology.vertex_offsets[v]; k < topology.vertex_offsets[v + 1]; ++k) {
            const uint32_t g = topology.vertex_triangles[k];
            const double w = faces.area[g] * portable_exp(-(1.0 - guide.dot(normal[g])) * scale);
            sum += w * normal[g];
          }
          if (keep) sums.push_back({v, sum});
          return sum;
        };
        for (uint32_t k = topology.vertex_offsets[b]; k < topology.vertex_offsets[b + 1]; ++k) {
          const uint32_t f = topology.vertex_triangles[k];
          if (guide_of[f] != b) continue;
          // Faces around each corner: a face sharing an edge with f is met
          // twice, f itself three times; the weights only need to be local.
          Vec3 sum = Vec3::Zero();
          for (uint32_t v : mesh.triangles[f])
            if (small_fan(topology, v)) sum += corner_sum(v);
          const double len = sum.norm();
          next[f] = len > 0 ? Vec3(sum / len) : normal[f];
        }
      }
    });
    normal.swap(next);
    if (after_step) after_step(step);
  }
  return normal;
}

// The angle between the mean raw normals of the faces around the edge's two
// ends on either side of the plane through the edge along `normal` (sides by
// position, not by normal, so that noise does not sort itself into sides):
// ~10 faces a side average the noise out, while the filtered normals'
// staircase on noisy curved parts has no such support, nor does a single
// folded sliver.
//
// With `shifted`, also the support with the plane moved by ∓offset and
// +offset across the edge (the same faces): a crease edge's support is a
// local maximum across the crease, that of a flat edge beside it is not.
// A set of indices for side_support's ring walks: open addressing in a
// table of a power of two at least twice the entries, cleared per walk.
class IndexSet {
 public:
  void clear() {
    if (count_ > 0) std::fill(slots_.begin(), slots_.end(), kNone);
    count_ = 0;
  }
  /// Adds `key` (not kNone); false if it was there.
  bool insert(uint32_t key) {
    if (2 * (count_ + 1) > slots_.size()) grow();
    for (size_t i = slot(key);; i = (i + 1) & (slots_.size() - 1)) {
      if (slots_[i] == key) return false;
      if (slots_[i] == kNone) {
        slots_[i] = key;
        ++count_;
        return true;
      }
    }
  }

 private:
  size_t slot(uint32_t key) const {
    const uint32_t hash = key * 0x9E3779B1u;  // Fibonacci hashing, wrapping in 32 bits
    return hash & (slots_.size() - 1);
  }
  void grow() {
    std::vector<uint32_t> old(std::max<size_t>(256, 2 * slots_.size()), kNone);
    old.swap(slots_);
    count_ = 0;
    for (uint32_t key : old)
      if (key != kNone) insert(key);
  }
  std::vector<uint32_t> slots_;
  size_t count_ = 0;
};

// What side_support keeps between calls (one per thread).
struct RingScratch {
  std::vector<uint32_t> faces;
  IndexSet face_set, vertex_set;
};

double side_support(const Mesh& mesh, const Topology& topology, const FaceNormals& faces, size_t e, const Vec3& normal,
                    int rings, RingScratch& scratch, double offset = 0, double* shifted = nullptr,
                    Vec3* normal_out = nullptr) {
  const uint32_t a = topology.edges[e][0], b = topology.edges[e][1];
  const Vec3 mid = 0.5 * (mesh.positions[a] + mesh.positions[b]);
  const Vec3 across = (mesh.positions[b] - mesh.positions[a]).cross(normal);
  // The faces within `rings` rings of the edge's ends: its faces, the fans
  // of its ends, then ring by ring the fans of the last ring's faces'
  // corners, each face and corner once (sets, not sorts of repeats: the
  // sorts were 57 % of the crease selection on a noisy scan), in
  // ascending order as the sums below take them.
  std::vector<uint32_t>& found = scratch.faces;
  found.clear();
  scratch.face_set.clear();
  scratch.vertex_set.clear();
  const auto add_fan = [&](uint32_t v) {
    if (!small_fan(topology, v) || !scratch.vertex_set.insert(v)) return;
    for (uint32_t k = topology.vertex_offsets[v]; k < topology.vertex_offsets[v + 1]; ++k)
      if (scratch.face_set.insert(topology.vertex_triangles[k])) found.push_back(topology.vertex_triangles[k]);
  };
  for (uint32_t f : topology.edge_triangles[e])
    if (f != kNone && scratch.face_set.insert(f)) found.push_back(f);
  add_fan(a);
  add_fan(b);
  size_t last_ring = 0;  // where the last ring's faces begin in `found`
  for (int ring = 1; ring < rings; ++ring) {
    const size_t end = found.size();
    for (size_t i = last_ring; i < end; ++i)
      for (uint32_t v : mesh.triangles[found[i]]) add_fan(v);
    last_ring = end;
  }
  std::sort(found.begin(), found.end());
  const double across_norm = across.norm();
  auto support_at = [&](double shift) {
    Vec3 side[2] = {Vec3::Zero(), Vec3::Zero()};
    for (uint32_t g : found) {
      const Triangle& t = mesh.triangles[g];
      const Vec3 centre = (mesh.positions[t[0]] + mesh.positions[t[1]] + mesh.positions[t[2]]) / 3.0;
      side[(centre - mid).dot(across) > shift * across_norm] += face_area(mesh, faces, g) * faces.normal[g];
    }
    if (side[0].squaredNorm() == 0 || side[1].squaredNorm() == 0) return 0.0;
    // Signed like CreaseAngles::angle: side 0 lies on the −across side, so a
    // convex fold turns from side 0 to side 1 about the edge's direction.
    const Vec3 cross = side[0].cross(side[1]);
    if (normal_out && shift == 0) *normal_out = side[0].normalized() + side[1].normalized();
    const double angle = portable_angle(cross.norm(), side[0].dot(side[1]));
    return cross.dot(mesh.positions[b] - mesh.positions[a]) >= 0 ? angle : -angle;
  };
  if (shifted) shifted[0] = support_at(-offset), shifted[1] = support_at(offset);
  return support_at(0.0);
}

struct Chain {
  std::vector<uint32_t> vertices;  // closed chains do not repeat the first
  std::vector<uint32_t> edges;
  bool closed = false;
  bool anchored = false;  // closed, from a junction (its first vertex) back to it
};

// The selected edges and their ends, indexed compactly: on most meshes a
// small share of the mesh, so chaining them, in rounds, allocates and scans
// nothing per vertex of the mesh (at 1.1M triangles with 18 creases the
// per-vertex arrays were most of the selection's cost).
struct SelectedGraph {
  std::vector<uint32_t> edges;     // the selected edges, ascending
  std::vector<uint32_t> vertices;  // their ends, ascending
  // Per vertex i, its selected edges (ascending): incident[offsets[i] .. offsets[i + 1]).
  std::vector<uint32_t> offsets, incident;

  uint32_t vertex(uint32_t v) const {
    return uint32_t(std::lower_bound(vertices.begin(), vertices.end(), v) - vertices.begin());
  }
  uint32_t edge(uint32_t e) const { return uint32_t(std::lower_bound(edges.begin(), edges.end(), e) - edges.begin()); }
  uint32_t degree(uint32_t i) const { return offsets[i + 1] - offsets[i]; }
};

// The edges selected now, ascending: what the rounds below start from.
std::vector<uint32_t> selected_edges(const std::vector<uint8_t>& on) {
  std::vector<uint32_t> edges;
  // Eight flags at a time: nearly all are 0 (creases are few).
  const uint8_t* flags = on.data();
  const size_t n = on.size();
  size_t e = 0;
  for (; e + 8 <= n; e += 8) {
    uint64_t word;
    std::memcpy(&word, flags + e, sizeof word);
    if (word == 0) continue;
    for (size_t k = e; k < e + 8; ++k)
      if (flags[k]) edges.push_back(uint32_t(k));
  }
  for (; e < n; ++e)
    if (flags[e]) edges.push_back(uint32_t(e));
  return edges;
}

// `candidates`: ascending, every selected edge among them (the rounds only
// deselect, or add what they list).
SelectedGraph selected_graph(const Topology& topology, const std::vector<uint8_t>& on,
                             const std::vector<uint32_t>& candidates) {
  SelectedGraph g;
  for (uint32_t e : candidates)
    if (on[e])
      g.edges.push_back(e), g.vertices.push_back(topology.edges[e][0]), g.vertices.push_back(topology.edges[e][1]);
  std::sort(g.vertices.begin(), g.vertices.end());
  g.vertices.erase(std::unique(g.vertices.begin(), g.vertices.end()), g.vertices.end());
  // Each edge's ends looked up once, not once per pass (the searches were
  // most of this function's 24 M instructions for the dragon's 3 calls).
  std::vector<uint32_t> ends(2 * g.edges.size());
  for (size_t i = 0; i < g.edges.size(); ++i)
    for (int k = 0; k < 2; ++k) ends[2 * i + k] = g.vertex(topology.edges[g.edges[i]][k]);
  g.offsets.assign(g.vertices.size() + 1, 0);
  for (uint32_t i : ends) ++g.offsets[i + 1];
  for (size_t i = 0; i < g.vertices.size(); ++i) g.offsets[i + 1] += g.offsets[i];
  g.incident.resize(g.offsets.back());
  std::vector<uint32_t> fill(g.offsets.begin(), g.offsets.end() - 1);
  for (size_t i = 0; i < ends.size(); ++i) g.incident[fill[ends[i]]++] = g.edges[i / 2];
  return g;
}

// Vertices compared by position (lexicographically, then by number where
// two share a position): an order the file's numbering does not change.
bool placed_before(const Mesh& mesh, uint32_t a, uint32_t b) {
  const Vec3 &p = mesh.positions[a], &q = mesh.positions[b];
  if (p.x() != q.x()) return p.x() < q.x();
  if (p.y() != q.y()) return p.y() < q.y();
  if (p.z() != q.z()) return p.z() < q.z();
  return a < b;
}

// Turns a chain to run from the end placed first (placed_before); a closed
// one to start at its vertex placed first (unless anchored: a loop from a
// junction back to it starts there), towards the neighbour placed first.
// The turn splits' ties, the spur rounds and the lines' order then do not
// depend on where the walk that found the chain began (a relabelled file's
// casting.obj had 43 creases instead of 51, fandisk-quads 14 instead of 18).
void orient_chain(const Mesh& mesh, Chain& c) {
  const size_t n = c.vertices.size();
  if (!c.closed) {
    if (placed_before(mesh, c.vertices.back(), c.vertices.front()))
      std::reverse(c.vertices.begin(), c.vertices.end()), std::reverse(c.edges.begin(), c.edges.end());
    return;
  }
  // Edge k runs from vertex k to vertex k + 1 (mod n).
  size_t first = 0;
  for (size_t i = 1; i < n && !c.anchored; ++i)
    if (placed_before(mesh, c.vertices[i], c.vertices[first])) first = i;
  std::rotate(c.vertices.begin(), c.vertices.begin() + std::ptrdiff_t(first), c.vertices.end());
  std::rotate(c.edges.begin(), c.edges.begin() + std::ptrdiff_t(first), c.edges.end());
  if (n > 2 && placed_before(mesh, c.vertices[n - 1], c.vertices[1])) {
    std::reverse(c.vertices.begin() + 1, c.vertices.end());
    std::reverse(c.edges.begin(), c.edges.end());
  }
}

// Chains of the selected edges: through vertices with exactly two crease
// edges of the same sign; each oriented (orient_chain), in order of their
// first two vertices' places.
std::vector<Chain> chain_edges(const Mesh& mesh, const Topology& topology, const std::vector<double>& angle,
                               const std::vector<uint8_t>& on, const std::vector<uint32_t>& candidates) {
  const SelectedGraph g = selected_graph(topology, on, candidates);
  const size_t nv = g.vertices.size();
  auto other = [&](uint32_t e, uint32_t v) {
    return topology.edges[e][0] == v ? topology.edges[e][1] : topology.edges[e][0];
  };
  std::vector<uint8_t> stop(nv, 0);  // chains end here
  for (uint32_t i = 0; i < nv; ++i) {
    const uint32_t d = g.degree(i);
    stop[i] = d != 2 || (angle[g.incident[g.offsets[i]]] > 0) != (angle[g.incident[g.offsets[i] + 1]] > 0);
  }

  std::vector<uint8_t> used(g.edges.size(), 0);
  std::vector<Chain> chains;
  auto walk = [&](uint32_t start, uint32_t edge) {
    Chain c;
    c.vertices.push_back(start);
    uint32_t v = start;
    while (true) {
      used[g.edge(edge)] = 1;
      c.edges.push_back(edge);
      v = other(edge, v);
      if (v == start) {  // around a loop
        c.closed = true;
        break;
      }
      c.vertices.push_back(v);
      const uint32_t i = g.vertex(v);
      if (stop[i]) break;
      const uint32_t a = g.incident[g.offsets[i]], b = g.incident[g.offsets[i] + 1];
      edge = a == edge ? b : a;
      if (used[g.edge(edge)]) break;
    }
    chains.push_back(std::move(c));
  };
  for (uint32_t i = 0; i < nv; ++i)
    if (stop[i])
      for (uint32_t k = g.offsets[i]; k < g.offsets[i + 1]; ++k)
        if (!used[g.edge(g.incident[k])]) walk(g.vertices[i], g.incident[k]);
  for (size_t k = 0; k < g.edges.size(); ++k)
    if (!used[k]) walk(topology.edges[g.edges[k]][0], g.edges[k]);
  for (Chain& c : chains) {
    c.anchored = c.closed && stop[g.vertex(c.vertices[0])];
    orient_chain(mesh, c);
  }
  std::sort(chains.begin(), chains.end(), [&](const Chain& a, const Chain& b) {
    if (a.vertices[0] != b.vertices[0]) return placed_before(mesh, a.vertices[0], b.vertices[0]);
    return placed_before(mesh, a.vertices[1 % a.vertices.size()], b.vertices[1 % b.vertices.size()]);
  });
  return chains;
}

// Splits a chain where it turns by more than max_turn (radians), the turn
// measured between the chain's directions over `span` of arc length before
// and after the vertex: on a noisy mesh the crease detours around single
// triangles, which turns single edges by 60–120° while the line runs on.
// Where consecutive vertices all turn too much, the chain splits once, at
// the sharpest.
std::vector<Chain> split_at_turns(const Mesh& mesh, Chain c, double max_turn, double span) {
  const size_t n = c.vertices.size();
  if (n < 3) return {std::move(c)};
  if (c.anchored) {
    // A loop from a junction back to it is split as a chain with the
    // junction at both ends, never sharp itself: kept whole for being sharp
    // all round, a noisy crease's doubled trace round a triangle or two (a
    // bubble on a junction) went whole as a corner loop, and the crease it
    // hung on then as a spur (cgal-fandisk-large: an 81° crease of 5.6 mean
    // edges; the notched prism at σ = 0.25 in pieces).
    Chain open = c;
    open.vertices.push_back(c.vertices[0]);
    open.closed = open.anchored = false;
    std::vector<Chain> pieces = split_at_turns(mesh, std::move(open), max_turn, span);
    if (pieces.size() == 1) return {std::move(c)};  // no cut: still the loop the corner rule reads
    return pieces;
  }
  auto x = [&](size_t i) -> const Vec3& { return mesh.positions[c.vertices[c.closed ? i % n : i]]; };
  // The point `span` away from vertex i, walking backwards (dir −1) or forwards.
  auto reach = [&](size_t i, int dir) {
    double walked = 0;
    size_t j = i;
    for (size_t steps = 0; steps + 1 < n; ++steps) {
      if (!c.closed && ((dir < 0 && j == 0) || (dir > 0 && j + 1 == n))) break;
      const size_t k = dir < 0 ? (j + n - 1) % n : (j + 1) % n;
      walked += (x(k) - x(j)).norm();
      j = k;
      if (walked >= span) break;
    }
    return x(j);
  };
  std::vector<double> turn(n, 0.0);
  const double cos_max = portable_cos(max_turn);
  std::vector<uint8_t> sharp(n, 0);
  for (size_t i = c.closed ? 0 : 1; i < (c.closed ? n : n - 1); ++i) {
    const Vec3 in = x(i) - reach(i, -1), out = reach(i, +1) - x(i);
    const double norms = in.norm() * out.norm();
    if (!(norms > 0)) continue;
    const double cosine = in.dot(out) / norms;
    turn[i] = -cosine;
    sharp[i] = cosine < cos_max;
  }
  // One cut per run of sharp vertices, at its sharpest (the first of
  // equals, the chain oriented by orient_chain). Not at every local maximum
  // of the turn: on a small round hole, whose rim turns by about the same
  // at every vertex (casting.obj: 112° ± 0.2° over the span at each of 16),
  // the maxima fall where round-off puts them, and the pieces shorter than
  // kCornerChainEdges went as shortcuts, the rest then as spurs: a
  // relabelled file lost or kept its holes' rims by chance. A loop sharp all
  // round has no corner: it stays whole.
  std::vector<size_t> cuts;
  size_t first_run = 0;  // a closed chain's runs are read from a vertex that is not sharp
  if (c.closed) {
    while (first_run < n && sharp[first_run]) ++first_run;
    if (first_run == n) return {std::move(c)};
  }
  for (size_t k = 0; k < n;) {
    const size_t i = (first_run + k) % n;
    if (!sharp[i]) {
      ++k;
      continue;
    }
    size_t best = i;
    for (; k < n && sharp[(first_run + k) % n]; ++k)
      if (turn[(first_run + k) % n] > turn[best]) best = (first_run + k) % n;
    cuts.push_back(best);
  }
  std::sort(cuts.begin(), cuts.end());
  if (cuts.empty()) return {std::move(c)};
  std::vector<Chain> out;
  if (c.closed) {
    // Open the loop at the first cut: vertices cuts[0] … cuts[0] again.
    Chain open;
    for (size_t k = 0; k <= n; ++k) open.vertices.push_back(c.vertices[(cuts[0] + k) % n]);
    for (size_t k = 0; k < n; ++k) open.edges.push_back(c.edges[(cuts[0] + k) % n]);
    for (size_t& cut : cuts) cut = (cut + n - cuts[0]) % n;
    cuts.push_back(n);
    cuts.erase(cuts.begin());
    c = std::move(open);
  }
  size_t begin = 0;
  cuts.push_back(c.vertices.size() - 1);
  for (size_t cut : cuts) {
    if (cut <= begin) continue;
    Chain piece;
    piece.vertices.assign(c.vertices.begin() + begin, c.vertices.begin() + cut + 1);
    piece.edges.assign(c.edges.begin() + begin, c.edges.begin() + cut);
    out.push_back(std::move(piece));
    begin = cut;
  }
  return out;
}

// Hysteresis [Canny]: from every free end of the selection, the crease
// continues along the best edge at or above `low` with the same sign that
// runs on within 60° of the end's direction; a few rounds close the gaps a
// noisy crease leaves where single edges fall just short of the angle.
template <class Passes>
void continue_free_ends(const Mesh& mesh, const Topology& topology, const std::vector<double>& angle,
                        const Passes& passes, std::vector<uint8_t>& on) {
  auto other = [&](uint32_t e, uint32_t v) {
    return topology.edges[e][0] == v ? topology.edges[e][1] : topology.edges[e][0];
  };
  std::vector<uint32_t> selected = selected_edges(on);
  for (int round = 0; round < kHysteresisRounds; ++round) {
    const SelectedGraph g = selected_graph(topology, on, selected);
    std::vector<uint32_t> add;
    for (uint32_t i = 0; i < g.vertices.size(); ++i) {
      if (g.degree(i) != 1) continue;
      const uint32_t v = g.vertices[i], in = g.incident[g.offsets[i]];
      const Vec3 dir = (mesh.positions[v] - mesh.positions[other(in, v)]).normalized();
      uint32_t best = kNone;
      for (uint32_t k = topology.vertex_offsets[v]; k < topology.vertex_offsets[v + 1]; ++k)
        for (uint32_t e : topology.triangle_edges[topology.vertex_triangles[k]]) {
          if (on[e] || (topology.edges[e][0] != v && topology.edges[e][1] != v)) continue;
          if (!passes(e) || (angle[e] > 0) != (angle[in] > 0)) continue;
          const Vec3 next = (mesh.positions[other(e, v)] - mesh.positions[v]).normalized();
          if (dir.dot(next) < 0.5) continue;
          if (best == kNone || std::abs(angle[e]) > std::abs(angle[best])) best = e;
        }
      if (best != kNone) add.push_back(best);
    }
    if (add.empty()) break;
    for (uint32_t e : add) on[e] = 1;
    selected.insert(selected.end(), add.begin(), add.end());
    std::sort(selected.begin(), selected.end());
    selected.erase(std::unique(selected.begin(), selected.end()), selected.end());
  }
}

// Bridging, on noisy surfaces only. At normal noise σ = 0.25 mean edges the
// filter flattens 32–39 % of a 45° crease's edges below kCandidateAngle
// (crestline_crease_report; the support of those edges stays at 33–62°), so
// what passes is pieces a few edges long, with gaps longer than hysteresis
// closes. From each free end the crease is walked on along the edge, within
// 60° of the end's direction, whose signed support (side_support, the same
// sign as the end's) is largest, while that reaches kBridgeShare × the angle
// (or kBridgeWeakShare for up to kBridgeWeakRun edges in a row); a walk is
// kept only if it meets another crease edge within kBridgeEdges edges: a gap
// closed, never a free end extended (a spur stays a spur). With `widen`
// (very noisy surfaces) a walk with no edge in its cone may take a strong
// one ahead (kBridgeWideCos). Bridged edges take their signed support as
// their angle; with `long_weak` a longer weak run goes on while the mean of
// its last kLongWeakSpan edges holds. Returns whether any edge was
// added.
//
// Half-bridges: a walk that fails is kept (stopped for weakness, with up to
// kBridgeWeakRun more weak edges ahead); a later walk of the same sign that
// reaches one of its vertices, heading against it (within 60°), closes the
// gap with it if the two together average kBridgeShare × the angle. On the
// chamfered cylinder's 45° edges at σ = 0.25 a gap's two walks stopped two
// edges apart, each after three edges of 30–34° support against 35°; on
// the noisy torus (aniso-across) failed walks of 22–32° met too, so the mean
// decides. Measured (--seeds 6, σ = 0.25, with the later passes): targets
// met 37 → 47, coverage min 0.846 → 0.939; the smooth harness unchanged.
bool bridge_gaps(const Mesh& mesh, const Topology& topology, double threshold, bool widen, bool long_weak,
                 std::vector<double>& angle, std::vector<uint8_t>& on, const std::function<void()>& checkpoint) {
  const size_t nv = mesh.positions.size(), ne = on.size();
  auto other = [&](uint32_t e, uint32_t v) {
    return topology.edges[e][0] == v ? topology.edges[e][1] : topology.edges[e][0];
  };
  std::vector<uint32_t> degree(nv, 0);
  for (uint32_t e = 0; e < ne; ++e)
    if (on[e]) ++degree[topology.edges[e][0]], ++degree[topology.edges[e][1]];
  // The edges at v (each twice: once per face).
  auto for_edges_at = [&](uint32_t v, auto&& visit) {
    for (uint32_t k = topology.vertex_offsets[v]; k < topology.vertex_offsets[v + 1]; ++k)
      for (uint32_t e : topology.triangle_edges[topology.vertex_triangles[k]])
        if (topology.edges[e][0] == v || topology.edges[e][1] == v) visit(e);
  };
  const FaceNormals faces = face_normals(mesh);
  std::vector<double> support(ne, std::numeric_limits<double>::quiet_NaN());
  RingScratch scratch;
  std::vector<uint32_t> path, path_vertices, trail;
  // Walks that failed, for a walk from a gap's other end to meet (per vertex
  // the last one through it).
  struct Half {
    std::vector<uint32_t> edges, vertices;  // vertices[k] starts edges[k]
    double sign;
  };
  std::vector<Half> halves;
  std::vector<uint32_t> half_at(nv, kNone);
  bool added = false;
  auto signed_support = [&](uint32_t e) {
    if (std::isnan(support[e])) {
      const auto& f = topology.edge_triangles[e];
      support[e] =
          topology.is_boundary_edge(e) || !small_fan(topology, topology.edges[e][0]) ||
                  !small_fan(topology, topology.edges[e][1])
              ? 0.0
              : side_support(mesh, topology, faces, e, faces.normal[f[0]] + faces.normal[f[1]], kBridgeRings, scratch);
    }
    return support[e];
  };
  std::vector<uint32_t> ends;
  for (uint32_t v = 0; v < nv; ++v)
    if (degree[v] == 1) ends.push_back(v);
  for (size_t i = 0; i < ends.size(); ++i) {
    if (checkpoint && i % 256 == 255) checkpoint();
    const uint32_t start = ends[i];
    if (degree[start] != 1) continue;  // joined by an earlier walk
    uint32_t in = kNone;
    for_edges_at(start, [&](uint32_t e) {
      if (on[e]) in = e;
    });
    if (in == kNone) continue;
    const double sign = angle[in] > 0 ? 1.0 : -1.0;
    // The end's direction over up to kBridgeBack edges of its chain: its last
    // edge alone may be a noise detour.
    uint32_t back = other(in, start), via = in;
    for (int k = 1; k < kBridgeBack && degree[back] == 2; ++k) {
      uint32_t next = kNone;
      for_edges_at(back, [&](uint32_t e) {
        if (on[e] && e != via) next = e;
      });
      if (next == kNone || other(next, back) == start) break;
      via = next, back = other(next, back);
    }
    Vec3 dir = (mesh.positions[start] - mesh.positions[back]).normalized();
    {
      // In the surface: a noisy vertex tilts a short end's edges out of it
      // (on the chamfered cylinder's top rim at σ = 0.25 one end's direction
      // rose 42° and found no edge ahead). The sum of the mean normals on
      // either side of the end's edge stands for the surface's. Measured
      // (--seeds 6, σ = 0.25): targets met 45 → 47, coverage min 0.937 →
      // 0.939, precision min 0.987 → 0.963 (a filleted box's fillet, where
      // the walks now also go on along false pieces). Along the fold of
      // those normals (their cross product) instead: at --seeds 3
      // (before the later passes) a filleted box failed (1.33 lines per
      // edge), which the projection keeps at 1.00.
      Vec3 mean_normal = Vec3::Zero();
      const auto& f = topology.edge_triangles[in];
      if (!topology.is_boundary_edge(in))
        side_support(mesh, topology, faces, in, faces.normal[f[0]] + faces.normal[f[1]], kBridgeRings, scratch, 0,
                     nullptr, &mean_normal);
      const Vec3 in_plane = dir - dir.dot(mean_normal.normalized()) * mean_normal.normalized();
      if (mean_normal.squaredNorm() > 0 && in_plane.squaredNorm() > 0) dir = in_plane.normalized();
    }
    uint32_t v = start;
    bool joined = false;
    path.clear();
    path_vertices.assign(1, start);
    trail.assign({back, start});  // the walk's last kBridgeBack + 1 vertices (first the chain's)
    int weak_run = 0;
    uint32_t met = kNone;  // the half-bridge this walk met
    bool weak_stop = false;
    uint32_t best = kNone;
    // One step from v: the best edge within the cone (or, widening, ahead).
    auto step_from = [&](uint32_t from, double& best_support, bool& wide) {
      uint32_t chosen = kNone;
      best_support = 0;
      wide = false;  // no edge within the cone: the best ahead, if strong
      for (double cone : {kBridgeCos, kBridgeWideCos}) {
        if (chosen != kNone || (cone == kBridgeWideCos && !widen)) break;
        wide = cone == kBridgeWideCos;
        for_edges_at(from, [&](uint32_t e) {
          if (on[e] || std::find(path.begin(), path.end(), e) != path.end()) return;
          const Vec3 next = (mesh.positions[other(e, from)] - mesh.positions[from]).normalized();
          if (dir.dot(next) < cone) return;
          const double s = sign * signed_support(e);
          if (chosen == kNone || s > best_support) chosen = e, best_support = s;
        });
      }
      return chosen;
    };
    auto advance = [&](uint32_t e) {
      path.push_back(e);
      const uint32_t w = other(e, v);
      path_vertices.push_back(w);
      trail.push_back(w);
      if (trail.size() > kBridgeBack + 1) trail.erase(trail.begin());
      dir = (mesh.positions[w] - mesh.positions[trail.front()]).normalized();
      v = w;
    };
    for (int step = 0; step < kBridgeEdges && !joined; ++step) {
      double best_support = 0;
      bool wide = false;
      best = step_from(v, best_support, wide);
      if (best == kNone || best_support < (wide ? kBridgeShare : kBridgeWeakShare) * threshold) break;
      weak_run = best_support < kBridgeShare * threshold ? weak_run + 1 : 0;
      // The noisiest surfaces: a longer weak run goes on while the last edges' mean holds.
      bool mean_holds = false;
      if (long_weak && weak_run > kBridgeWeakRun && path.size() + 1 >= kLongWeakSpan) {
        double sum = best_support;
        for (size_t k = path.size() + 1 - kLongWeakSpan; k < path.size(); ++k) sum += sign * support[path[k]];
        mean_holds = sum >= kSupportShare * threshold * static_cast<double>(kLongWeakSpan);
      }
      if (weak_run > kBridgeWeakRun && !mean_holds) {
        weak_stop = true;
        break;
      }
      advance(best);
      joined = degree[v] > 0;
      if (!joined && half_at[v] != kNone) {
        // A half-bridge of the same sign coming the other way.
        const Half& half = halves[half_at[v]];
        const Vec3 along = mesh.positions[half.vertices.back()] - mesh.positions[half.vertices.front()];
        const Vec3 walked = mesh.positions[v] - mesh.positions[start];
        if (half.sign == sign && along.dot(walked) < -kBridgeCos * along.norm() * walked.norm()) {
          // Together as strong as a crease, on average.
          double sum = 0;
          size_t n = path.size();
          for (uint32_t e : path) sum += sign * support[e];
          for (size_t k = 0; k < half.edges.size() && half.vertices[k] != v; ++k, ++n)
            sum += sign * support[half.edges[k]];
          if (sum >= kBridgeShare * threshold * static_cast<double>(n)) met = half_at[v], joined = true;
        }
      }
    }
    auto commit = [&](uint32_t e) {
      if (on[e]) return;
      on[e] = 1;
      added = true;
      angle[e] = support[e];
      ++degree[topology.edges[e][0]], ++degree[topology.edges[e][1]];
    };
    if (joined) {
      for (uint32_t e : path) commit(e);
      if (met != kNone) {
        // The half-bridge from its own end up to where this walk met it.
        const Half& half = halves[met];
        for (size_t k = 0; k < half.edges.size() && half.vertices[k] != v; ++k) commit(half.edges[k]);
      }
      continue;
    }
    // Stopped for weakness: the half-bridge goes on over up to
    // kBridgeWeakRun more weak edges, which a walk from the gap's other end
    // may meet.
    if (weak_stop)
      for (int k = 0; k < kBridgeWeakRun && best != kNone && degree[other(best, v)] == 0; ++k) {
        advance(best);
        double best_support = 0;
        bool wide = false;
        best = step_from(v, best_support, wide);
        if (best != kNone && (wide || best_support < kBridgeWeakShare * threshold)) best = kNone;
      }
    if (path.empty()) continue;
    const uint32_t id = static_cast<uint32_t>(halves.size());
    halves.push_back({path, path_vertices, sign});
    for (uint32_t w : path_vertices) half_at[w] = id;
  }
  return added;
}

double chain_strength(const Mesh& mesh, const Topology& topology, const std::vector<double>& angle, const Chain& c,
                      double& length) {
  double strength = 0;
  length = 0;
  for (uint32_t e : c.edges) {
    const double l = (mesh.positions[topology.edges[e][0]] - mesh.positions[topology.edges[e][1]]).norm();
    length += l;
    strength += std::abs(angle[e]) * l;
  }
  return strength;
}

// Redundant chains, on very noisy surfaces only: a chain every vertex of
// which lies within `rings` rings of another chain's vertices runs beside
// that one (a noisy crease traced twice, a bridge beside a piece, the parallel
// branches of a Y, a second loop beside a closed crease) and splits it at the
// junctions it makes or doubles it; such chains are dropped, the weakest
// (mean |angle|) first, each checked against the chains still kept. Returns
// whether any was dropped.
bool drop_redundant_chains(const Mesh& mesh, const Topology& topology, const std::vector<Chain>& chains,
                           std::vector<double>& angle, int rings, bool splice, std::vector<uint8_t>& on) {
  const size_t nv = mesh.positions.size();
  std::vector<uint32_t> count(nv, 0);  // kept chains through each vertex
  std::vector<std::pair<double, size_t>> order;
  std::vector<double> mean_of(chains.size(), 0.0);
  std::vector<std::pair<uint32_t, uint32_t>> through;  // (vertex, chain), sorted
  for (size_t i = 0; i < chains.size(); ++i) {
    const Chain& c = chains[i];
    for (uint32_t v : c.vertices) ++count[v], through.emplace_back(v, static_cast<uint32_t>(i));
    double length = 0;
    const double strength = chain_strength(mesh, topology, angle, c, length);
    mean_of[i] = length > 0 ? strength / length : 0.0;
    order.emplace_back(mean_of[i], i);
  }
  std::sort(order.begin(), order.end());
  std::sort(through.begin(), through.end());
  std::vector<uint8_t> own(nv, 0), dropped_chain(chains.size(), 0);
  std::vector<uint32_t> ring, next, near_vertices;
  // The vertices within `reach` rings of `from` (from among them).
  auto rings_of = [&](std::vector<uint32_t> from, int reach) {
    std::sort(from.begin(), from.end());
    from.erase(std::unique(from.begin(), from.end()), from.end());
    for (int k = 0; k < reach; ++k) {
      next = from;
      add_one_ring(mesh, topology, from, next);
      from.swap(next);
    }
    return from;
  };
  auto edge_between = [&](uint32_t a, uint32_t b) {
    for (uint32_t j = topology.vertex_offsets[a]; j < topology.vertex_offsets[a + 1]; ++j)
      for (uint32_t e : topology.triangle_edges[topology.vertex_triangles[j]])
        if ((topology.edges[e][0] == a && topology.edges[e][1] == b) ||
            (topology.edges[e][0] == b && topology.edges[e][1] == a))
          return e;
    return kNone;
  };
  bool dropped = false;
  for (const auto& [mean, i] : order) {
    const Chain& c = chains[i];
    for (uint32_t v : c.vertices) own[v] = 1;
    // Another chain near every vertex of c: a vertex of c counts itself once.
    auto other_near = [&](uint32_t v) {
      ring.assign(1, v);
      for (int k = 0;; ++k) {
        for (uint32_t u : ring)
          if (count[u] > own[u]) return true;
        if (k == rings) return false;
        next.clear();
        add_one_ring(mesh, topology, ring, next);
        ring.swap(next);
      }
    };
    const bool redundant = std::all_of(c.vertices.begin(), c.vertices.end(), other_near);
    for (uint32_t v : c.vertices) own[v] = 0;
    if (!redundant) continue;
    if (splice) {
      // Splicing (see kSpliceShare): the chains beside c all weaker.
      near_vertices = rings_of(c.vertices, rings);
      std::vector<uint32_t> beside;
      for (uint32_t u : near_vertices)
        for (auto it = std::lower_bound(through.begin(), through.end(), std::make_pair(u, 0u));
             it != through.end() && it->first == u; ++it)
          if (it->second != i && !dropped_chain[it->second]) beside.push_back(it->second);
      std::sort(beside.begin(), beside.end());
      beside.erase(std::unique(beside.begin(), beside.end()), beside.end());
      // Chains that c meets at its ends continue it: not beside it.
      for (uint32_t end : {c.vertices.front(), c.vertices.back()})
        for (auto it = std::lower_bound(through.begin(), through.end(), std::make_pair(end, 0u));
             it != through.end() && it->first == end; ++it)
          beside.erase(std::remove(beside.begin(), beside.end(), it->second), beside.end());
      const double strong = kSpliceShare * mean;
      const bool weaker =
          !beside.empty() && std::all_of(beside.begin(), beside.end(), [&](uint32_t j) { return mean_of[j] < strong; });
      if (weaker) {
        auto is_near = [&](uint32_t u) { return std::binary_search(near_vertices.begin(), near_vertices.end(), u); };
        const double sign = angle[c.edges.front()] > 0 ? 1.0 : -1.0;
        for (uint32_t j : beside) {
          const Chain& y = chains[j];
          const size_t m = y.edges.size();
          std::vector<uint8_t> cut(m, 0);
          for (size_t k = 0; k < m; ++k)
            cut[k] = is_near(y.vertices[k]) && is_near(y.vertices[(k + 1) % y.vertices.size()]);
          for (size_t k = 0; k < m; ++k)
            if (cut[k]) on[y.edges[k]] = 0;
          // Ends left by the cut: link each to c's nearest vertex.
          for (size_t k = 0; k < m; ++k) {
            const bool left_end = cut[k] && (k > 0 || y.closed) && !cut[(k + m - 1) % m];
            const bool right_end = cut[k] && (k + 1 < m || y.closed) && !cut[(k + 1) % m];
            for (int side = 0; side < 2; ++side) {
              if (!(side ? right_end : left_end)) continue;
              const uint32_t b = y.vertices[side ? (k + 1) % y.vertices.size() : k];
              // Breadth first from b to a vertex of c (at most kSpliceSearch vertices).
              std::vector<uint32_t> seen{b}, parent{kNone};
              uint32_t found = kNone;
              for (size_t q = 0; q < seen.size() && found == kNone && q < kSpliceSearch; ++q) {
                const uint32_t u = seen[q];
                if (std::find(c.vertices.begin(), c.vertices.end(), u) != c.vertices.end()) {
                  found = static_cast<uint32_t>(q);
                  break;
                }
                for (uint32_t t = topology.vertex_offsets[u]; t < topology.vertex_offsets[u + 1]; ++t)
                  for (uint32_t w : mesh.triangles[topology.vertex_triangles[t]])
                    if (std::find(seen.begin(), seen.end(), w) == seen.end())
                      seen.push_back(w), parent.push_back(static_cast<uint32_t>(q));
              }
              if (found == kNone) continue;
              for (uint32_t q = found; parent[q] != kNone; q = parent[q]) {
                const uint32_t e = edge_between(seen[q], seen[parent[q]]);
                if (e == kNone || on[e]) continue;
                on[e] = 1;
                angle[e] = sign * mean;
              }
            }
          }
          dropped_chain[j] = 1;
        }
        return true;
      }
    }
    dropped_chain[i] = 1;
    for (uint32_t v : c.vertices) --count[v];
    for (uint32_t e : c.edges) on[e] = 0;
    dropped = true;
  }
  return dropped;
}

}  // namespace

int automatic_normal_filter_steps(double noise_level) {
  return noise_level > kNoisySurface ? kNoisyCreaseFilterSteps : 0;
}

CreaseAngles measure_crease_angles(const Mesh& mesh, const Topology& topology, const CreaseMeasureOptions& options,
                                   const std::function<void(double)>& progress) {
  CreaseAngles out;
  out.noise_measured = options.normal_filter_steps != 0;
  // The parts' shares of the time, in filter steps (the dragon, 1 thread:
  // a filter step ≈ the noise level ≈ the edges' loop without the filter;
  // with it, the support over more rings ≈ 3 steps). Until the noise level
  // decides the automatic choice, the total assumes the filter runs: it
  // only shrinks then, so the fractions keep rising.
  const auto total = [&](int steps) { return (out.noise_measured ? 1.0 : 0.0) + steps + (steps > 0 ? 3.0 : 1.0); };
  double done = 0,
         parts = total(options.normal_filter_steps >= 0 ? options.normal_filter_steps : kNoisyCreaseFilterSteps);
  const auto report = [&](double share) {
    done += share;
    if (progress) progress(done / parts);
  };
  if (out.noise_measured) {
    out.noise_level = options.noise_level >= 0 ? options.noise_level : surface_noise_level(mesh, topology);
    report(1);
  }
  out.normal_filter_steps =
      options.normal_filter_steps >= 0 ? options.normal_filter_steps : automatic_normal_filter_steps(out.noise_level);
  parts = total(out.normal_filter_steps);
  const double edge_share = out.normal_filter_steps > 0 ? 3.0 : 1.0;
  const size_t ne = topology.edges.size();
  // The median length only where not given (the Pipeline's frames measured
  // every edge's).
  const bool measure_lengths = !(options.median_edge_length >= 0);
  // The per-edge results, and 1 − cos of each edge's angle and its length
  // for the medians (1 − cos: monotonic in the angle; single precision: the
  // rounding moves the automatic angle by parts in 10^7). Where no filter
  // runs, made before the face normals, so that those, freed first, are the
  // heap's top, which glibc returns, not a hole beneath the results (the
  // CLI at 1.1M triangles: max RSS −2 MB on 1 thread, −6 on 2); with the
  // filter, after it (not held through its steps).
  std::vector<float> complement, length;
  // Their fills write fresh pages (33 MB at 1.1M triangles: 16 bytes an
  // edge of doubles, 4 of floats, 4 more where the lengths are measured
  // here), whose faults cost more than the writes:
  // half on one thread, half on another, allocated on this one (see
  // detail::number_edges).
  const auto make_results = [&] {
    out.angle.reserve(ne), out.support.reserve(ne), complement.reserve(ne);
    if (measure_lengths) length.reserve(ne);
    run_side_by_side(
        [&] {
          out.angle.assign(ne, 0.0);
          if (measure_lengths) length.assign(ne, std::numeric_limits<float>::infinity());
        },
        [&] {
          out.support.assign(ne, 0.0);
          complement.assign(ne, std::numeric_limits<float>::infinity());
        });
  };
  if (out.normal_filter_steps == 0) make_results();
  // Without the filter the areas are read only by the support, of the few
  // edges turning by kCandidateAngle or more: not kept for every face (at
  // 1.1M triangles 8 bytes per triangle at the measure's peak).
  FaceNormals faces = out.normal_filter_steps > 0 ? face_normals(mesh) : face_normals_only(mesh);
  // The raw normals themselves where no filter runs (clean meshes): no copy,
  // 24 bytes per triangle less fresh memory.
  std::vector<Vec3> filtered;
  if (out.normal_filter_steps > 0) {
    filtered = filter_normals(mesh, topology, faces, out.normal_filter_steps, [&](int) { report(1); });
    make_results();
  }
  const std::vector<Vec3>& normal = out.normal_filter_steps > 0 ? filtered : faces.normal;
  const bool very_noisy = out.normal_filter_steps > 0 && out.noise_level > kVeryNoisyCreaseLevel;
  const int rings = very_noisy ? kVeryNoisySupportRings : out.normal_filter_steps > 0 ? kNoisySupportRings : 1;
  const double candidate = portable_cos(kCandidateAngle * kDegree);
  // Each edge alone, on every thread, in blocks with progress between them.
  std::atomic<size_t> boundary_edges{0};
  constexpr size_t kBlock = size_t{1} << 16;
  const double block_share =
      edge_share * static_cast<double>(kBlock) / static_cast<double>(std::max<size_t>(ne, kBlock));
  for (size_t block = 0; block < ne; block += kBlock) {
    parallel_for(std::min(ne, block + kBlock) - block, [&](size_t first, size_t last) {
      RingScratch scratch;
      size_t boundary = 0;
      for (size_t e = block + first; e < block + last; ++e) {
        // The faces' normals lie anywhere in their array: those of the edge
        // kAhead on are asked for now (natively; WASM has no prefetch). In
        // the loop: GCC drops a lambda made of prefetches.
        constexpr size_t kAhead = 16;
        if (e + kAhead < block + last) {
          const auto& ahead = topology.edge_triangles[e + kAhead];
          __builtin_prefetch(&normal[ahead[0]]);
          if (ahead[1] != kNone) __builtin_prefetch(&normal[ahead[1]]);
          if (measure_lengths)
            for (uint32_t v : topology.edges[e + kAhead]) __builtin_prefetch(&mesh.positions[v]);
        }
        if (topology.is_boundary_edge(static_cast<uint32_t>(e))) {
          ++boundary;
          continue;
        }
        const uint32_t f0 = topology.edge_triangles[e][0], f1 = topology.edge_triangles[e][1];
        const Vec3 &n0 = normal[f0], &n1 = normal[f1];
        const double cosine = n0.dot(n1);
        complement[e] = static_cast<float>(1.0 - cosine);
        if (measure_lengths)
          length[e] =
              static_cast<float>((mesh.positions[topology.edges[e][1]] - mesh.positions[topology.edges[e][0]]).norm());
        if (cosine > candidate) continue;  // below kCandidateAngle: never a crease, left 0
        // The edge as f0 runs along it (counter-clockwise seen from outside):
        // (n0 × n1)·d > 0 where the surface folds away below f0's plane.
        const Triangle& t = mesh.triangles[f0];
        int k = 0;
        while (k < 2 && topology.triangle_edges[f0][k] != e) ++k;
        const Vec3 d = mesh.positions[t[(k + 1) % 3]] - mesh.positions[t[k]];
        const Vec3 cross = n0.cross(n1);
        const double a = portable_angle(cross.norm(), cosine);
        out.angle[e] = cross.dot(d) >= 0 ? a : -a;
        if (a < kCandidateAngle * kDegree) continue;
        if (!very_noisy) {
          out.support[e] = std::abs(side_support(mesh, topology, faces, e, n0 + n1, rings, scratch));
          continue;
        }
        // Very noisy: only where the support is a local maximum across the edge.
        double shifted[2];
        const double s = std::abs(
            side_support(mesh, topology, faces, e, n0 + n1, rings, scratch, kSuppressionShift * d.norm(), shifted));
        if (s >= std::max(std::abs(shifted[0]), std::abs(shifted[1]))) out.support[e] = s;
      }
      boundary_edges.fetch_add(boundary, std::memory_order_relaxed);
    });
    if (block + kBlock < ne) report(block_share);
  }
  // The normals and areas are done with: freed before the medians' samples
  // are made (at 1.1M triangles 32 bytes per triangle beside them).
  faces = FaceNormals(), filtered = std::vector<Vec3>();
  // The median angle and the same edges' median length (the spur rule's
  // scale, where not given), each on a thread of its own if there are two
  // (detail::value_at_rank: nth_element's value in about one pass). Over every
  // interior edge: a sample of every fourth edge in edge order (before
  // 2026-12-07) depended on how the file numbers its vertices and
  // triangles (bench/relabel.mjs: a shuffled spot.obj's automatic angle
  // 62.8° against 60.8°; a 96-edge cylinder's sample mostly its rims',
  // median 90°, no creases at all). Boundary edges' entries are +∞, above
  // every interior edge's, so the upper median of the interior edges is the
  // element at half their count.
  const size_t interior = ne - boundary_edges.load();
  const auto median_of = [&](std::vector<float>& values) {
    if (interior == 0) return -1.0;
    return double(detail::value_at_rank(values.data(), values.size(), interior / 2));
  };
  const auto median_angle = [&] {
    const double m = median_of(complement);
    if (m >= 0) out.median = portable_acos_of_complement(m) / kDegree;
  };
  out.median_edge_length = options.median_edge_length;
  if (measure_lengths)
    run_side_by_side(median_angle, [&] { out.median_edge_length = std::max(0.0, median_of(length)); });
  else
    median_angle();
  return out;
}

double automatic_crease_angle(const CreaseAngles& angles) {
  if (piecewise_planar(angles)) return kDefaultCreaseAngle;
  return std::min(180.0, std::max(kDefaultCreaseAngle, kMedianFactor * angles.median));
}

CreaseResult select_creases(const Mesh& mesh, const Topology& topology, const CreaseAngles& angles,
                            const CreaseOptions& options, double mean_edge_length,
                            const std::function<void()>& checkpoint) {
  CreaseResult out;
  out.angle = options.angle >= 0 ? options.angle : automatic_crease_angle(angles);
  const double threshold = out.angle * kDegree, max_turn = options.max_turn * kDegree;
  const size_t ne = std::min(topology.edges.size(), angles.angle.size());
  std::vector<uint8_t> on(topology.edges.size(), 0);
  const double floor = kCandidateAngle * kDegree;
  auto passes = [&](size_t e, double limit) {
    const double a = std::abs(angles.angle[e]);
    return a >= std::max(limit, floor) && angles.support[e] >= kSupportShare * std::max(limit, floor);
  };
  parallel_for(ne, [&](size_t begin, size_t end) {
    for (size_t e = begin; e < end; ++e) on[e] = passes(e, threshold);
  });
  const double h = mean_edge_length > 0 ? mean_edge_length : 1.0;
  const double spur_h =
      angles.median_edge_length > 0 && angles.median_edge_length * kSliverMeanRatio < h ? angles.median_edge_length : h;
  continue_free_ends(
      mesh, topology, angles.angle, [&](uint32_t e) { return passes(e, kHysteresisShare * threshold); }, on);
  // The angles the chains read: bridged edges take their support's.
  std::vector<double> bridged;
  const bool very_noisy = angles.normal_filter_steps > 0 && angles.noise_level > kVeryNoisyCreaseLevel;
  const bool noisy = angles.normal_filter_steps > 0 && angles.noise_level <= kBridgeNoiseLimit;
  const bool noisiest = noisy && angles.noise_level > kNoisiestCreaseLevel;
  // On piecewise-planar meshes a short piece between junctions is a real
  // edge: a box's edge is one mesh edge from corner to corner.
  const bool planar = piecewise_planar(angles);
  if (noisy) {
    bridged = angles.angle;
    bridged.resize(topology.edges.size(), 0.0);
    bridge_gaps(mesh, topology, std::max(threshold, floor), very_noisy, noisiest, bridged, on, checkpoint);
  }
  const std::vector<double>& angle = bridged.empty() ? angles.angle : bridged;

  // Drop spurs until none is left (usually one round), then chain again.
  // The rounds only deselect: they chain among the edges selected here.
  std::vector<uint32_t> candidates = selected_edges(on);
  std::vector<Chain> chains;
  int bridge_passes = 1, splices = 0;
  for (bool dropped = true; dropped;) {
    if (checkpoint) checkpoint();
    chains.clear();
    for (Chain& c : chain_edges(mesh, topology, angle, on, candidates))
      for (Chain& piece :
           split_at_turns(mesh, std::move(c), max_turn, (noisy ? kNoisyTurnSpanEdges : kTurnSpanEdges) * h))
        chains.push_back(std::move(piece));
    // Selected edges at a vertex (the chains' ends are among the graph's vertices).
    const SelectedGraph graph = selected_graph(topology, on, candidates);
    auto degree = [&](uint32_t v) { return graph.degree(graph.vertex(v)); };
    dropped = false;
    // Sign blips, on the noisy surfaces bridging runs on: a piece shorter
    // than kCornerChainEdges whose ends both continue, through vertices of
    // two crease edges, along a crease of the other sign is noise (a concave
    // edge from the rim down to a wall vertex on a convex crease) and takes
    // its neighbours' sign. Left alone it split the crease, went as a
    // shortcut, and the shorter side then went as a spur (the notched prism
    // at σ = 0.25: 10 h of a notch edge lost beside the re-entrant corner).
    if (noisy) {
      auto opposite_at = [&](uint32_t v, uint32_t own) {
        const uint32_t i = graph.vertex(v);
        if (graph.degree(i) != 2) return false;
        const uint32_t e0 = graph.incident[graph.offsets[i]], e1 = graph.incident[graph.offsets[i] + 1];
        return (angle[e0 == own ? e1 : e0] > 0) != (angle[own] > 0);
      };
      for (const Chain& c : chains) {
        double length = 0;
        if (c.closed || (chain_strength(mesh, topology, angle, c, length), length >= kCornerChainEdges * h)) continue;
        if (!opposite_at(c.vertices.front(), c.edges.front()) || !opposite_at(c.vertices.back(), c.edges.back()))
          continue;
        for (uint32_t e : c.edges) bridged[e] = -bridged[e];
        dropped = true;  // each flip removes two sign changes, so this ends
      }
      if (dropped) continue;
    }
    // Bubbles, on the noisy surfaces bridging runs on: two chains between the
    // same two junctions, close to each other (a noisy crease passing on both
    // sides of a triangle or two, a bridge beside it), split the line into
    // pieces at both ends; the one with the smaller mean |angle| goes. Not on
    // clean meshes: there two such chains are two real creases (the halves of
    // a small hole's rim; casting.obj lost 26 of its 51 lines).
    if (noisy) {
      std::vector<std::pair<uint64_t, size_t>> ends;
      for (size_t i = 0; i < chains.size(); ++i) {
        const Chain& c = chains[i];
        if (c.closed || c.vertices.front() == c.vertices.back()) continue;
        const uint64_t lo = std::min(c.vertices.front(), c.vertices.back()),
                       hi = std::max(c.vertices.front(), c.vertices.back());
        ends.emplace_back(lo << 32 | hi, i);
      }
      std::sort(ends.begin(), ends.end());
      for (size_t i = 0; i + 1 < ends.size(); ++i) {
        if (ends[i].first != ends[i + 1].first) continue;
        double la = 0, lb = 0;
        const Chain &a = chains[ends[i].second], &b = chains[ends[i + 1].second];
        const double sa = chain_strength(mesh, topology, angle, a, la),
                     sb = chain_strength(mesh, topology, angle, b, lb);
        if (std::max(la, lb) > kBubbleEdges * h) continue;
        const bool a_weaker = sa * lb < sb * la;
        const Chain &weaker = a_weaker ? a : b, &stronger = a_weaker ? b : a;
        // Close: every vertex of the weaker within kBubbleWidth h of the stronger's.
        bool close = true;
        for (uint32_t v : weaker.vertices) {
          double nearest = std::numeric_limits<double>::infinity();
          for (uint32_t w : stronger.vertices)
            nearest = std::min(nearest, (mesh.positions[v] - mesh.positions[w]).squaredNorm());
          close = close && nearest <= kBubbleWidth * kBubbleWidth * h * h;
        }
        if (!close) continue;
        for (uint32_t e : weaker.edges) on[e] = 0;
        dropped = true;
        ++i;
      }
      if (dropped) continue;
    }
    // On noisy surfaces (those bridging runs on) spurs first, shortcuts
    // (below) only in a round that drops none: a spur makes a junction on the
    // crease it hangs on, and two of them make the piece of the crease
    // between them look like a shortcut across a corner; dropping both spurs
    // and that piece at once opened gaps in noisy creases. Not on clean
    // meshes: there the shortcuts at corners then outlived the spurs beside
    // them (cgal-fandisk-large: 49 → 67 creases).
    std::vector<const Chain*> shortcuts;
    for (const Chain& c : chains) {
      double loop_length = 0;
      if (!planar && c.closed && degree(c.vertices.front()) >= 3 &&
          (chain_strength(mesh, topology, angle, c, loop_length), loop_length < 3 * kCornerChainEdges * h)) {
        for (uint32_t e : c.edges) on[e] = 0;  // a corner triangle, round and back to its junction
        dropped = true;
      }
      if (c.closed) continue;
      const bool free_end = degree(c.vertices.front()) == 1 || degree(c.vertices.back()) == 1;
      double length = 0;
      const double strength = chain_strength(mesh, topology, angle, c, length) / h;
      // Between junctions or turns: a shortcut across a corner.
      const bool between_junctions = degree(c.vertices.front()) >= 2 && degree(c.vertices.back()) >= 2;
      if (!planar && between_junctions && length < kCornerChainEdges * h) shortcuts.push_back(&c);
      if (free_end && strength < kSpurStrength && length < kSpurEdges * spur_h) {
        for (uint32_t e : c.edges) on[e] = 0;
        dropped = true;  // each round drops edges, so this ends
      }
    }
    if ((!dropped || !noisy) && noisy && very_noisy) {
      // Very noisy surfaces: shortest first, and only while both ends keep
      // two crease edges, so that no shortcut leaves a free end. There a
      // notch edge was traced twice side by side, the traces joined by rungs
      // of 1 h; the rule took the rungs and the traces' pieces between them
      // at once, and the spur rule then every piece (the notched prism,
      // uniform walls, seed 2, in the Pipeline's frame: coverage 0.950, 19 h
      // of ridge in the gap). Kept, the rungs' going leaves the two traces
      // whole, and the later rounds keep one of them (bubbles, redundant
      // chains).
      std::vector<std::pair<double, const Chain*>> order;
      for (const Chain* c : shortcuts) {
        double length = 0;
        chain_strength(mesh, topology, angle, *c, length);
        order.emplace_back(length, c);
      }
      std::stable_sort(order.begin(), order.end(), [](const auto& x, const auto& y) { return x.first < y.first; });
      std::vector<uint32_t> removed(graph.vertices.size(), 0);
      auto left = [&](uint32_t v) { return degree(v) - removed[graph.vertex(v)]; };
      for (const auto& [length, c] : order) {
        const uint32_t a = c->vertices.front(), b = c->vertices.back();
        if (a == b ? left(a) < 4 : left(a) < 3 || left(b) < 3) continue;
        ++removed[graph.vertex(a)], ++removed[graph.vertex(b)];
        for (uint32_t e : c->edges) on[e] = 0;
        dropped = true;
      }
    } else if (!dropped || !noisy)
      for (const Chain* c : shortcuts) {
        for (uint32_t e : c->edges) on[e] = 0;
        dropped = true;
      }
    if (!dropped && very_noisy) {
      // Splices add edges (their joins): the rounds then chain among those too.
      std::vector<double> unbridged;
      std::vector<double>& working = bridged.empty() ? (unbridged = angles.angle, unbridged) : bridged;
      const bool splice = !bridged.empty() && splices < kSplices;
      dropped = drop_redundant_chains(mesh, topology, chains, working, kRedundantRings, splice, on);
      if (dropped && splice) candidates = selected_edges(on), ++splices;
    }
    // Once no spur is left, the ends they hung on are free: bridge from
    // those once more (a gap beside a spur's junction was no gap before).
    if (!dropped && noisy && bridge_passes < kBridgePasses) {
      ++bridge_passes;
      dropped = bridge_gaps(mesh, topology, std::max(threshold, floor), very_noisy, noisiest, bridged, on, checkpoint);
      if (dropped) candidates = selected_edges(on);
    }
  }

  for (const Chain& c : chains) {
    Polyline line;
    line.type = LineType::Crease;
    line.closed = c.closed;
    line.convex = angle[c.edges.front()] > 0;
    const size_t n = c.vertices.size();
    line.points.reserve(n);
    line.curvature.reserve(n);
    for (size_t i = 0; i < n; ++i) {
      line.points.push_back(mesh.positions[c.vertices[i]]);
      // The mean |angle| of the chain's edges at this point, per mean edge.
      const bool has_before = i > 0 || c.closed, has_after = i < c.edges.size();
      const double before = has_before ? std::abs(angle[c.edges[i > 0 ? i - 1 : c.edges.size() - 1]]) : 0;
      const double after = has_after ? std::abs(angle[c.edges[i]]) : 0;
      line.curvature.push_back((before + after) / (has_before && has_after ? 2.0 : 1.0) / h);
    }
    measure_polyline(line);
    out.edges.insert(out.edges.end(), c.edges.begin(), c.edges.end());
    out.line_vertex.push_back(c.vertices.front());
    out.lines.push_back(std::move(line));
  }
  return out;
}

}  // namespace crestline
