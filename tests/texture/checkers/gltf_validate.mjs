// Runs the Khronos glTF-Validator (npm gltf-validator) on each file named on the command line,
// with the files it references read from disk, and prints one JSON line per file: the counts
// of errors, warnings, infos and hints, the messages, and the resources it loaded.
// Usage: node gltf_validate.mjs NPM_DIR FILE.gltf...
import { createRequire } from 'module';
import fs from 'fs';
import path from 'path';

const [npm, ...files] = process.argv.slice(2);
const validator = createRequire(path.join(npm, 'package.json'))('gltf-validator');
for (const file of files) {
  const dir = path.dirname(file);
  const report = await validator.validateBytes(new Uint8Array(fs.readFileSync(file)), {
    uri: file,
    maxIssues: 0,
    externalResourceFunction: (uri) => new Promise((resolve, reject) => {
      try {
        resolve(new Uint8Array(fs.readFileSync(path.resolve(dir, decodeURIComponent(uri)))));
      } catch (e) {
        reject(e.toString());
      }
    }),
  });
  const i = report.issues;
  console.log(JSON.stringify({
    file, validator: report.validatorVersion, errors: i.numErrors, warnings: i.numWarnings, infos: i.numInfos,
    hints: i.numHints, messages: i.messages,
    resources: (report.info.resources || []).map((r) => ({ pointer: r.pointer, uri: r.uri, image: r.image || null })),
    materials: report.info.materialCount, vertices: report.info.totalVertexCount,
  }));
}
