// Loads a .glb with three.js's GLTFLoader (as a three.js app would, from the file's bytes) and
// prints what the app gets: meshes with their morph target names and position deltas,
// materials, bounding box, animation clips. A file compressed with EXT_meshopt_compression is
// decoded by three.js's own MeshoptDecoder, set as its documentation says. Usage: node three_load.mjs <dir holding node_modules/three> <file.glb>
// [snippet.js]: a snippet (the README's) is run on the loaded `gltf` first, without its
// `import` lines and the line that loads the file (this script loads it from the bytes).
import fs from 'node:fs';
import path from 'node:path';
import { pathToFileURL } from 'node:url';

const dir = path.resolve(process.argv[2], 'node_modules', 'three');
const THREE = await import(pathToFileURL(path.join(dir, 'build', 'three.module.js')));
const { GLTFLoader } = await import(
  pathToFileURL(path.join(dir, 'examples', 'jsm', 'loaders', 'GLTFLoader.js'))
);
const { MeshoptDecoder } = await import(
  pathToFileURL(path.join(dir, 'examples', 'jsm', 'libs', 'meshopt_decoder.module.js'))
);
const bytes = fs.readFileSync(process.argv[3]);
const buffer = bytes.buffer.slice(bytes.byteOffset, bytes.byteOffset + bytes.byteLength);
const loader = new GLTFLoader().setMeshoptDecoder(MeshoptDecoder);
const gltf = await new Promise((resolve, reject) => loader.parse(buffer, '', resolve, reject));
if (process.argv[4]) {
  const body = fs
    .readFileSync(process.argv[4], 'utf8')
    .split('\n')
    .filter((l) => !l.startsWith('import ') && !l.startsWith('const gltf ='))
    .join('\n');
  const AsyncFunction = (async () => {}).constructor;
  await new AsyncFunction('gltf', 'THREE', body)(gltf, THREE);
}
const meshes = [];
// Positions and morph deltas are reported for files of up to 20 M numbers (a whole head's
// targets would not fit in one JSON string); above that, `arraysOmitted` is true.
let numbers = 0;
gltf.scene.traverse((o) => {
  if (o.isMesh) {
    const g = o.geometry;
    numbers += g.attributes.position.array.length * (1 + (g.morphAttributes.position ?? []).length);
  }
});
const arraysOmitted = numbers > 20e6;
gltf.scene.traverse((o) => {
  if (!o.isMesh) return;
  const g = o.geometry;
  meshes.push({
    name: o.name,
    vertices: g.attributes.position.count,
    attributes: Object.keys(g.attributes).sort(),
    morphTargets: Object.keys(o.morphTargetDictionary ?? {}),
    morphTargetInfluences: o.morphTargetInfluences ?? [],
    positions: arraysOmitted ? [] : Array.from(g.attributes.position.array),
    morphPositions: arraysOmitted ? [] : (g.morphAttributes.position ?? []).map((a) => Array.from(a.array)),
    material: {
      type: o.material.type,
      name: o.material.name,
      metalness: o.material.metalness,
      roughness: o.material.roughness,
      side: o.material.side,
    },
  });
});
const box = new THREE.Box3().setFromObject(gltf.scene);
const size = box.getSize(new THREE.Vector3());
console.log(
  JSON.stringify({
    revision: THREE.REVISION,
    arraysOmitted,
    meshes,
    size: [size.x, size.y, size.z],
    animations: gltf.animations.map((a) => a.name),
    copyright: gltf.asset.copyright ?? null,
  }),
);
