// Validates a .glb with the Khronos glTF validator (npm gltf-validator):
//   node check_glb.mjs model.glb [expected-lamella-node-count]
// Prints the report's counts and its errors; exits 1 when it has an error (or when the number of
// nodes whose extras carry a lamella id differs from the expected count), 2 on bad usage.
import fs from 'node:fs';
import { createRequire } from 'node:module';
const require = createRequire(import.meta.url);
const validator = require('./node_modules/gltf-validator');

const [file, expected] = process.argv.slice(2);
if (!file) {
  console.error('usage: node check_glb.mjs model.glb [lamellas]');
  process.exit(2);
}
const bytes = new Uint8Array(fs.readFileSync(file));
const report = await validator.validateBytes(bytes, { maxIssues: 0 });
const issues = report.issues;
console.log(`${file}: ${issues.numErrors} errors, ${issues.numWarnings} warnings, ${issues.numInfos} infos, ${issues.numHints} hints`);
for (const m of issues.messages.filter((m) => m.severity === 0).slice(0, 20))
  console.log(`error ${m.code} ${m.pointer ?? ''}: ${m.message}`);
let failed = issues.numErrors > 0;
if (expected !== undefined) {
  // Node names and extras from the JSON chunk (validated above).
  const jsonLength = new DataView(bytes.buffer).getUint32(12, true);
  const gltf = JSON.parse(new TextDecoder().decode(bytes.subarray(20, 20 + jsonLength)));
  const lamellas = (gltf.nodes ?? []).filter((n) => n.extras && typeof n.extras.id === 'string' &&
    /^P\d+-[UV]\d+$/.test(n.extras.id) && n.name === n.extras.id && typeof n.extras.length_m === 'number' && n.mesh !== undefined);
  console.log(`lamella nodes: ${lamellas.length} (expected ${expected})`);
  if (lamellas.length !== Number(expected)) failed = true;
}
process.exit(failed ? 1 : 0);
