// Which of the files dropped together are read: the mesh (pickMainFile) and
// its companions (a .gltf's buffers and images, an .obj's .mtl); the rest are
// named in one sentence.
import { MESH_EXTENSIONS, pickMainFile } from '../worker/protocol.js';

const IMAGES = ['png', 'jpg', 'jpeg', 'webp', 'ktx2'];
/** Companion extensions per mesh extension. */
const COMPANIONS = { gltf: ['bin', ...IMAGES], obj: ['mtl'] };

/** @param {string} name */
const extensionOf = (name) => (/\.([^./\\]+)$/.exec(name)?.[1] ?? '').toLowerCase();

/** The file picker's `accept`: the formats the readers know and their companions. */
export const PICKER_ACCEPT = [...new Set([...MESH_EXTENSIONS, ...Object.values(COMPANIONS).flat()])].map((e) => `.${e}`).join(',');

/**
 * @template {{name: string, bytes: ArrayBuffer | Uint8Array}} F
 * @param {F[]} files
 * @returns {{read: F[], ignored: string[]}} the main file first, then its companions
 */
export function selectFiles(files) {
  const main = pickMainFile(files);
  const companions = COMPANIONS[extensionOf(main.name)] ?? [];
  const read = [main, ...files.filter((f) => f !== main && companions.includes(extensionOf(f.name)))];
  return { read, ignored: files.filter((f) => !read.includes(f)).map((f) => f.name) };
}

/** One sentence naming the ignored files, or null. @param {string} main @param {string[]} ignored */
export function ignoredSentence(main, ignored) {
  if (!ignored.length) return null;
  const list = ignored.length === 1 ? ignored[0] : `${ignored.slice(0, -1).join(', ')} and ${ignored.at(-1)}`;
  return `Read ${main}; ignored ${list} (one mesh at a time, with its .bin, images or .mtl).`;
}
