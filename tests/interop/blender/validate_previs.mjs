// The Khronos glTF-Validator on a previs.glb from `cinepath export --format gltf-camera`: no error and no
// warning, one camera per drone, one animation.
//   node validate_previs.mjs NODE_MODULES_DIR PREVIS_GLB CAMERAS
import { createRequire } from 'node:module';
import fs from 'node:fs';
import path from 'node:path';

const [modules, file, cameras] = process.argv.slice(2);
const require = createRequire(path.join(path.resolve(modules), 'noop.js'));
const validator = require('gltf-validator');

const report = await validator.validateBytes(new Uint8Array(fs.readFileSync(file)), { maxIssues: 100 });
const { numErrors, numWarnings, numInfos } = report.issues;
console.log(`${file}: ${numErrors} errors, ${numWarnings} warnings, ${numInfos} infos (validator ${report.validatorVersion})`);
for (const m of report.issues.messages) console.log(`  ${m.severity} ${m.code} ${m.pointer ?? ''}: ${m.message}`);
let failed = numErrors + numWarnings;
const info = report.info;
console.log(`  ${info.animationCount} animation(s)`);
const doc = (() => {
  const bytes = fs.readFileSync(file);
  const length = bytes.readUInt32LE(12);
  return JSON.parse(bytes.subarray(20, 20 + length).toString('utf8'));
})();
if ((doc.cameras ?? []).length !== Number(cameras)) {
  console.log(`  expected ${cameras} camera(s), found ${(doc.cameras ?? []).length}`);
  failed++;
}
if (info.animationCount !== 1) { console.log('  expected one animation'); failed++; }
process.exit(failed ? 1 : 0);
