// Validates one glTF/GLB file with the Khronos glTF validator (npm gltf-validator, installed into
// node_modules by scripts/bootstrap) and prints its report as JSON on stdout.
// Usage: node gltf_validate.js MODULE_DIR FILE   (MODULE_DIR: the repository's node_modules)
// Exit 0 with the report; 3 when the validator cannot be loaded; 1 on any other failure.
"use strict";
const fs = require("fs");
const path = require("path");

const [moduleDir, file] = process.argv.slice(2);
let validator;
try {
  validator = require(path.resolve(moduleDir, "gltf-validator"));
} catch (e) {
  console.error("gltf-validator not installed in " + moduleDir + " (run scripts/bootstrap): " + e.message.split("\n")[0]);
  process.exit(3);
}
const bytes = new Uint8Array(fs.readFileSync(file));
validator
  .validateBytes(bytes, {
    uri: path.basename(file),
    maxIssues: 100,
    externalResourceFunction: (uri) =>
      new Promise((resolve, reject) => {
        fs.readFile(path.resolve(path.dirname(file), decodeURIComponent(uri)), (err, data) =>
          err ? reject(err.toString()) : resolve(new Uint8Array(data)));
      }),
  })
  .then((report) => console.log(JSON.stringify(report)))
  .catch((error) => {
    console.error("validation failed: " + error);
    process.exit(1);
  });
