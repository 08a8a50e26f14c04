// Types of the package's entry (`import { computeFeatureLines, FeatureLines } from 'crestline'`).
import type { BufferGeometry, Camera, Group, Mesh, Object3DEventMap } from 'three';

/** A triangle mesh: xyz per vertex, three vertex indices per triangle (absent: every three vertices). */
export interface MeshArrays {
  positions: Float32Array | Float64Array | ArrayLike<number>;
  indices?: Uint32Array | Uint16Array | ArrayLike<number> | null;
}

/**
 * The parameter table's keys (`Session.options()`, the CLI's flags in
 * camelCase); each left out keeps its default. Lengths are in mean edge
 * lengths, strengths in ∫|κ| ds; 'auto' lets the core choose the threshold
 * or the pre-smoothing count. Ranges: `Session.describe()`.
 */
export interface PipelineOptions {
  presmoothSteps?: number | 'auto';
  presmoothTimeStep?: number;
  smoothingSteps?: number;
  smoothingTimeStep?: number;
  hausdorffBound?: number;
  fairingIterations?: number;
  threshold?: number | 'auto';
  /** Weak lines (strength below 1) shorter than this many mean edges are dropped too; 0 keeps them. */
  shortLineLength?: number;
  boundaryRings?: number;
  /** Sharp creases: edges whose dihedral angle is at least this many degrees (20–180; 180: none). */
  creaseAngle?: number | 'auto';
  /** A crease line is split where it turns by more than this many degrees. */
  creaseMaxTurn?: number;
  /** Steps of the normal filter before crease angles are measured (0: raw normals). */
  creaseFilterSteps?: number | 'auto';
  /** Ridges and valleys stop at the creases of the automatic angle. */
  creaseBoundaries?: boolean;
  /** ...this many edge lengths (at the crease) away from them; 0: where the boundary band ends. */
  creaseClearance?: number;
  /** Per-vertex smoothing strength (0 freezes a vertex, 1 is the global time step). */
  vertexWeights?: Float64Array | null;
}

export interface ComputeOptions extends PipelineOptions {
  /** Called as the pipeline advances: a stage name and the fraction done. */
  onProgress?: (stage: string, fraction: number) => void;
  /** Aborting rejects the promise with the signal's reason. */
  signal?: AbortSignal;
}

export interface FeatureLine {
  /** x, y, z of each point; a closed line does not repeat its first point. */
  points: Float32Array;
  /** ∫|κ| ds along the line. */
  strength: number;
  closed: boolean;
  length: number;
}

/** The CLI's --stats object (snake_case keys). */
export interface FeatureLineStats {
  vertices: number;
  triangles: number;
  ridges: number;
  valleys: number;
  threshold: number;
  mean_edge_length: number;
  [key: string]: unknown;
}

export interface FeatureLinesResult {
  ridges: FeatureLine[];
  valleys: FeatureLine[];
  stats: FeatureLineStats;
}

/** Ridges and valleys of a mesh, computed in a worker (a worker thread in node). */
export function computeFeatureLines(mesh: MeshArrays | BufferGeometry, options?: ComputeOptions): Promise<FeatureLinesResult>;

export interface FeatureLinesOptions extends PipelineOptions {
  ridgeColor?: string;
  valleyColor?: string;
  /** In CSS pixels. */
  lineWidth?: number;
}

export interface FeatureLinesEventMap extends Object3DEventMap {
  change: {};
  error: { message: string };
}

/** The ridges and valleys of a mesh as wide lines; add it to the mesh. */
export class FeatureLines extends Group<FeatureLinesEventMap> {
  constructor(source: Mesh | BufferGeometry | MeshArrays, options?: FeatureLinesOptions);
  /** The pipeline options in use. */
  readonly options: PipelineOptions;
  /** Resolves with this object once the first lines are shown. */
  readonly ready: Promise<FeatureLines>;
  /** Session.stats() of the lines shown (camelCase), null before the first result. */
  readonly stats: Record<string, number> | null;
  readonly ridgeCount: number;
  readonly valleyCount: number;
  /** New options, merged with the current ones; resolves when the lines are shown. */
  update(options: FeatureLinesOptions): Promise<FeatureLines>;
  /**
   * Draws the lines through the points that keep them within a fifth of a
   * pixel of all their points in `camera`'s view, `height` pixels high
   * (far fewer segments for a large mesh seen whole). Call it before each
   * render; without it every point is drawn.
   */
  fitDetail(camera: Camera, height: number): void;
  cancel(): void;
  dispose(): void;
}
