// Loads a .vrm with three.js's GLTFLoader and three-vrm's VRMLoaderPlugin (as a VRM app does)
// and prints, for each expression named on the command line, how far it moves the avatar's
// vertices: the largest length over every mesh vertex of Σ influence × morph delta after
// `vrm.expressionManager.setValue(name, 1); vrm.update(0)`, in metres.
// Usage: node three_vrm.mjs <dir holding node_modules> <file.vrm> <expression>...
import fs from 'node:fs';
import path from 'node:path';
import { pathToFileURL } from 'node:url';

const modules = path.resolve(process.argv[2], 'node_modules');
const THREE = await import(pathToFileURL(path.join(modules, 'three', 'build', 'three.module.js')));
const { GLTFLoader } = await import(
  pathToFileURL(path.join(modules, 'three', 'examples', 'jsm', 'loaders', 'GLTFLoader.js'))
);
const { VRMLoaderPlugin } = await import(
  pathToFileURL(path.join(modules, '@pixiv', 'three-vrm', 'lib', 'three-vrm.module.js'))
);
const bytes = fs.readFileSync(process.argv[3]);
const buffer = bytes.buffer.slice(bytes.byteOffset, bytes.byteOffset + bytes.byteLength);
const loader = new GLTFLoader();
loader.register((parser) => new VRMLoaderPlugin(parser));
const gltf = await new Promise((resolve, reject) => loader.parse(buffer, '', resolve, reject));
const vrm = gltf.userData.vrm;
if (!vrm) {
  console.log(JSON.stringify({ error: 'no VRM in the file' }));
  process.exit(0);
}
const moved = (name) => {
  for (const e of vrm.expressionManager.expressions) vrm.expressionManager.setValue(e.expressionName, 0);
  vrm.expressionManager.setValue(name, 1);
  vrm.update(0);
  let largest = 0;
  vrm.scene.traverse((o) => {
    if (!o.isMesh || !o.morphTargetInfluences) return;
    const morphs = o.geometry.morphAttributes.position ?? [];
    const n = o.geometry.attributes.position.count;
    for (let i = 0; i < n; i++) {
      let x = 0, y = 0, z = 0;
      morphs.forEach((m, t) => {
        const w = o.morphTargetInfluences[t];
        if (w) { x += w * m.getX(i); y += w * m.getY(i); z += w * m.getZ(i); }
      });
      largest = Math.max(largest, Math.hypot(x, y, z));
    }
  });
  return largest;
};
const expressions = {};
for (const name of process.argv.slice(4)) {
  expressions[name] = vrm.expressionManager.getExpression(name) ? moved(name) : null;
}
console.log(JSON.stringify({
  metaVersion: vrm.meta?.metaVersion ?? null,
  humanBones: Object.keys(vrm.humanoid?.humanBones ?? {}).length,
  expressions,
}));
