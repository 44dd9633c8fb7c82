// Reads a .3dm back through rhino3dm and checks it against what the run should hold:
//   node check_3dm.mjs model.3dm LAYERS LAMELLAS
// LAYERS: the patch-family layers expected ("P0-U,P0-V,P1-U"); LAMELLAS: the number of lamella
// objects. Passes when there is exactly one layer per patch and family named so, and one object
// named P<k>-<F><i> on its family's layer with its id and length_m user strings per lamella.
import fs from 'node:fs';
import { createRequire } from 'node:module';
// The CommonJS build: Debian 12's Node.js 18 reads rhino3dm.module.js (ES syntax in a package
// without "type": "module") as CommonJS and fails; rhino3dm.js loads on Node 18 and later.
const rhino3dm = createRequire(import.meta.url)('./node_modules/rhino3dm/rhino3dm.js');

const [file, layersArg, lamellasArg] = process.argv.slice(2);
if (!file || layersArg === undefined || lamellasArg === undefined) {
  console.error('usage: node check_3dm.mjs model.3dm P0-U,P0-V,... LAMELLAS');
  process.exit(2);
}
const rhino = await rhino3dm();
const doc = rhino.File3dm.fromByteArray(new Uint8Array(fs.readFileSync(file)));
if (!doc) {
  console.log(`${file}: rhino3dm cannot read it`);
  process.exit(1);
}
const problems = [];
const layers = doc.layers();
const familyLayers = new Map();
for (let i = 0; i < layers.count; ++i) {
  const name = layers.get(i).name;
  if (/^P\d+-[UV]$/.test(name)) {
    if (familyLayers.has(name)) problems.push(`layer ${name} twice`);
    familyLayers.set(name, i);
  }
}
const expectedLayers = layersArg.split(',').filter((s) => s.length > 0);
for (const name of expectedLayers) if (!familyLayers.has(name)) problems.push(`no layer ${name}`);
for (const name of familyLayers.keys()) if (!expectedLayers.includes(name)) problems.push(`unexpected layer ${name}`);
const objects = doc.objects();
const ids = new Set();
for (let i = 0; i < objects.count; ++i) {
  const a = objects.get(i).attributes();
  const m = /^(P\d+-[UV])\d+$/.exec(a.name);
  if (!m) continue;
  if (ids.has(a.name)) problems.push(`object ${a.name} twice`);
  ids.add(a.name);
  if (a.layerIndex !== familyLayers.get(m[1])) problems.push(`${a.name} is not on layer ${m[1]}`);
  if (a.getUserString('id') !== a.name) problems.push(`${a.name}: user string id is ${a.getUserString('id')}`);
  if (!(Number(a.getUserString('length_m')) > 0)) problems.push(`${a.name}: no positive length_m`);
}
if (ids.size !== Number(lamellasArg)) problems.push(`${ids.size} lamella objects, expected ${lamellasArg}`);
console.log(`${file}: ${layers.count} layers (${familyLayers.size} patch-family), ${objects.count} objects, ${ids.size} lamellas`);
for (const p of problems.slice(0, 20)) console.log(`problem: ${p}`);
process.exit(problems.length ? 1 : 0);
