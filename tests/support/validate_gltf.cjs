// Runs the Khronos glTF-Validator on one file and prints its JSON report.
// Usage: node validate_gltf.cjs <dir holding node_modules/gltf-validator> <file.glb|file.gltf>
const fs = require('fs');
const path = require('path');
const validator = require(path.resolve(process.argv[2], 'node_modules', 'gltf-validator'));
const file = process.argv[3];
validator
  .validateBytes(new Uint8Array(fs.readFileSync(file)), {
    uri: path.basename(file),
    maxIssues: 100,
    externalResourceFunction: (uri) =>
      new Promise((resolve, reject) => {
        fs.readFile(path.resolve(path.dirname(file), decodeURIComponent(uri)), (err, data) =>
          err ? reject(err.toString()) : resolve(data));
      }),
  })
  .then((report) => console.log(JSON.stringify(report)))
  .catch((error) => {
    console.error('glTF-Validator failed: ' + error);
    process.exit(2);
  });
