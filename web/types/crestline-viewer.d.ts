// Types of `import 'crestline/viewer'`: defines <crestline-viewer>.
export class CrestlineViewer extends HTMLElement {
  src: string;
  alt: string;
  smoothing: number;
  threshold: number | 'auto';
  fairing: number;
  cancel(): void;
  toSVG(options?: { silhouette?: boolean | string }): Promise<string>;
  toPNG(options?: { width?: number; height?: number }): Promise<Blob>;
  toGLB(): Promise<Blob>;
  toOBJ(): Promise<string>;
  toJSON(): Promise<string>;
}
