// The surface's picture kept between frames. Drawing the surface costs the
// whole mesh every frame (871k triangles: 1.2 s of CPU in headless
// Chromium's SwiftShader), yet most frames change only the lines: their
// first drawing, a threshold change, a toggle. Such a frame draws the
// picture kept from the last one instead, its colours and depths written
// back by one full-screen triangle, and the lines over it, depth-tested
// against those depths as against the surface itself.
//
// The picture is rendered as the canvas would be: multisampled like the
// antialiased canvas, colours sRGB-encoded in the shaders into RGBA8 (three.js
// renders in the output colour space only on the canvas and into a render
// target flagged as XR's), samples averaged as the canvas averages them.
// Without the lines the pixels are the plain render's. With them, a pixel's
// samples all have the depth of one of them: where a line meets the surface
// at a slant (its wide quad lies flat in depth) the surface hides the same
// line pixel on all its samples or on none, instead of on some, so a line's
// edge pixels differ (tests/browser/surface-cache.test.mjs bounds it).
// WebGL 2 can neither copy samples into a multisampled framebuffer nor
// write a depth per sample, which keeping the samples would need.
//
// Where WebGL rasterises on the CPU (SwiftShader, llvmpipe: no GPU, or one
// the browser will not use), the picture is drawn with one sample a pixel:
// multisampling doubles the cost of every surface frame there (the dragon's
// 871k triangles: 1.5-1.8 s of CPU against 0.8, taken from the worker's
// two threads while it computes the lines), and only the surface's
// silhouette and folds lose their smoothing; the lines are still drawn
// multisampled on the canvas.
import {
  AlwaysDepth,
  BufferAttribute,
  BufferGeometry,
  DepthTexture,
  Mesh,
  NoBlending,
  OrthographicCamera,
  SRGBColorSpace,
  ShaderMaterial,
  Vector2,
  WebGLRenderTarget,
} from 'three';

const size = new Vector2();

/** Writes the picture's texel at each pixel, colour and depth. */
const copyMaterial = () =>
  new ShaderMaterial({
    uniforms: { colors: { value: null }, depths: { value: null } },
    vertexShader: 'void main() { gl_Position = vec4( position.xy, 0.0, 1.0 ); }',
    fragmentShader: `
      uniform sampler2D colors;
      uniform sampler2D depths;
      void main() {
        ivec2 texel = ivec2( gl_FragCoord.xy );
        gl_FragColor = texelFetch( colors, texel, 0 );
        gl_FragDepth = texelFetch( depths, texel, 0 ).r;
      }`,
    blending: NoBlending,
    depthTest: true, // without the test WebGL writes no depth
    depthFunc: AlwaysDepth,
    depthWrite: true,
    toneMapped: false,
  });

/**
 * What the picture depends on, as numbers: the drawing buffer, the camera,
 * the background, and every visible object of the scene outside `overlays`
 * (its place, geometry, attributes' and material's versions and colour).
 * Equal keys draw equal pictures.
 */
export function surfaceKey(renderer, scene, camera, overlays) {
  renderer.getDrawingBufferSize(size);
  const key = [size.x, size.y, ...camera.projectionMatrix.elements, ...camera.matrixWorldInverse.elements];
  const background = scene.background;
  key.push(background?.isColor ? background.getHex() : (background?.id ?? -1));
  const visit = (object) => {
    if (!object.visible || overlays.includes(object)) return;
    key.push(object.id, ...object.matrixWorld.elements);
    if (object.isLight) key.push(object.color.getHex(), object.intensity);
    const { geometry, material } = object;
    if (geometry) {
      key.push(geometry.id, geometry.index?.version ?? -1, geometry.drawRange.start, geometry.drawRange.count);
      for (const name in geometry.attributes) key.push(geometry.attributes[name].id ?? -1, geometry.attributes[name].version ?? -1);
    }
    for (const m of [material ?? []].flat()) key.push(m.id, m.version, m.visible ? 1 : 0, m.color?.getHex() ?? -1);
    for (const child of object.children) visit(child);
  };
  visit(scene);
  return key;
}

const sameKey = (a, b) => a?.length === b.length && a.every((x, i) => x === b[i]);

/**
 * Whether `gl` rasterises on the CPU, as its renderer's name says
 * (Chromium names it only through WEBGL_debug_renderer_info; Firefox, which
 * deprecates that extension, in RENDERER itself).
 */
export function softwareRasterizer(gl) {
  let name = String(gl.getParameter(gl.RENDERER));
  if (/^WebKit WebGL$/i.test(name)) {
    const info = gl.getExtension('WEBGL_debug_renderer_info');
    if (info) name = String(gl.getParameter(info.UNMASKED_RENDERER_WEBGL));
  }
  return /SwiftShader|llvmpipe|softpipe|Software|Basic Render/i.test(name);
}

export class SurfaceCache {
  constructor() {
    this.target = null; // made on the first draw
    this.key = null;
    /** Whether the picture is multisampled (on an antialiased canvas): null, the default, unless on a software rasterizer. */
    this.multisample = null;
    this.software = null; // softwareRasterizer's answer, asked once
    this.canvasSamples = null;
    /** Frames that drew the surface into the picture (the others started from the picture kept). */
    this.surfaceDraws = 0;
    this.material = copyMaterial();
    const triangle = new BufferGeometry();
    triangle.setAttribute('position', new BufferAttribute(new Float32Array([-1, -1, 0, 3, -1, 0, -1, 3, 0]), 3));
    this.copy = new Mesh(triangle, this.material);
    this.copy.frustumCulled = false;
    this.copyCamera = new OrthographicCamera();
  }

  /** The next frame draws the surface again (a lost context took the picture). */
  invalidate() {
    this.key = null;
    this.software = this.canvasSamples = null; // a restored context may rasterise elsewhere
  }

  /**
   * Draws `scene` through `camera` on the canvas: the surface and everything
   * else but `overlays` (objects of the scene, e.g. the line layers' groups)
   * from the picture kept if nothing it shows changed, else into a new one;
   * then the overlays.
   */
  draw(renderer, scene, camera, overlays) {
    scene.updateMatrixWorld();
    const key = surfaceKey(renderer, scene, camera, overlays);
    const [width, height] = [key[0], key[1]];
    const samples = this.samples(renderer);
    if (this.target?.samples !== samples) {
      this.release();
      this.target = this.createTarget(renderer, width, height, samples);
    } else if (this.target.width !== width || this.target.height !== height) this.target.setSize(width, height);
    const previous = renderer.getRenderTarget();
    const autoClear = renderer.autoClear;
    const shown = overlays.map((o) => o.visible);
    try {
      if (!sameKey(this.key, key)) {
        overlays.forEach((o) => (o.visible = false));
        renderer.setRenderTarget(this.target);
        renderer.render(scene, camera);
        overlays.forEach((o, i) => (o.visible = shown[i]));
        this.key = key;
        this.surfaceDraws++;
      }
      renderer.setRenderTarget(previous);
      this.material.uniforms.colors.value = this.target.texture;
      this.material.uniforms.depths.value = this.target.depthTexture;
      renderer.render(this.copy, this.copyCamera); // clears (autoClear) and writes every pixel
      renderer.autoClear = false;
      for (const overlay of overlays) if (overlay.visible) renderer.render(overlay, camera);
    } finally {
      overlays.forEach((o, i) => (o.visible = shown[i]));
      renderer.setRenderTarget(previous);
      renderer.autoClear = autoClear;
    }
  }

  /** The picture's samples a pixel: the canvas's, or 0 (one) on a software rasterizer unless `multisample` says. */
  samples(renderer) {
    const gl = renderer.getContext();
    if (!gl.getContextAttributes()?.antialias) return 0;
    this.software ??= softwareRasterizer(gl);
    this.canvasSamples ??= gl.getParameter(gl.SAMPLES) || 4;
    return (this.multisample ?? !this.software) ? this.canvasSamples : 0;
  }

  createTarget(renderer, width, height, samples) {
    const target = new WebGLRenderTarget(width, height, {
      samples,
      depthTexture: new DepthTexture(width, height),
      colorSpace: SRGBColorSpace,
      internalFormat: 'RGBA8', // the encoded values as they are, not an sRGB texture that decodes them
      generateMipmaps: false,
    });
    // three.js renders in the output colour space (sRGB, as on the canvas) only on the canvas and into XR's targets.
    target.isXRRenderTarget = true;
    return target;
  }

  /** Frees the pictures' GPU memory (a small surface drawn directly); the next draw makes them again. */
  release() {
    this.target?.depthTexture.dispose();
    this.target?.dispose();
    this.target = null;
    this.key = null;
  }

  dispose() {
    this.release();
    this.copy.geometry.dispose();
    this.material.dispose();
  }
}
