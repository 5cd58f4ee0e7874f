// Runs the Khronos glTF-Validator on every GLB in manifest.json; fails on any error.
//   node validate.mjs NODE_MODULES_DIR SAMPLES_DIR
import { createRequire } from 'node:module';
import fs from 'node:fs';
import path from 'node:path';

const [modules, samples] = process.argv.slice(2);
const require = createRequire(path.join(path.resolve(modules), 'noop.js'));
const validator = require('gltf-validator');

const manifest = JSON.parse(fs.readFileSync(path.join(samples, 'manifest.json'), 'utf8'));
let failed = 0;
for (const entry of manifest) {
  const bytes = new Uint8Array(fs.readFileSync(path.join(samples, entry.file)));
  const report = await validator.validateBytes(bytes, { maxIssues: 100 });
  const { numErrors, numWarnings, numInfos } = report.issues;
  console.log(`${entry.file}: ${numErrors} errors, ${numWarnings} warnings, ${numInfos} infos` +
              ` (validator ${report.validatorVersion})`);
  for (const m of report.issues.messages) {
    if (m.severity === 0) console.log(`  ERROR ${m.code} ${m.pointer ?? ''}: ${m.message}`);
    else if (m.severity === 1) console.log(`  warning ${m.code} ${m.pointer ?? ''}: ${m.message}`);
  }
  if (numErrors !== 0) failed++;
  if (report.info.drawCallCount !== 1) { console.log('  expected one draw call'); failed++; }
}
if (manifest.length === 0) { console.log('no GLB to validate'); failed++; }
process.exit(failed ? 1 : 0);
