// Writes a Rhino .3dm from the JSON description of export/rhino_writer.cpp (rhinoDescription):
//   node write3dm.mjs description.json out.3dm
// Layers with their parents, one mesh object per entry with its name, layer, vertex colours and
// user strings. Exits non-zero with a message on any problem (the caller reports it).
import fs from 'node:fs';
import { createRequire } from 'node:module';
// The CommonJS build: Debian 12's Node.js 18 reads rhino3dm.module.js (ES syntax in a package
// without "type": "module") as CommonJS and fails; rhino3dm.js loads on Node 18 and later.
const rhino3dm = createRequire(import.meta.url)('./node_modules/rhino3dm/rhino3dm.js');

const [input, output] = process.argv.slice(2);
if (!input || !output) {
  console.error('usage: node write3dm.mjs description.json out.3dm');
  process.exit(2);
}
const description = JSON.parse(fs.readFileSync(input, 'utf8'));
const rhino = await rhino3dm();
const doc = new rhino.File3dm();
doc.settings().modelUnitSystem = rhino.UnitSystem.Meters;

const layerIndex = new Map();
for (const spec of description.layers) {
  const layer = new rhino.Layer();
  layer.name = spec.name;
  if (spec.parent !== null) {
    if (!layerIndex.has(spec.parent)) throw new Error(`layer ${spec.name}: unknown parent ${spec.parent}`);
    layer.parentLayerId = doc.layers().get(layerIndex.get(spec.parent)).id;
  }
  layerIndex.set(spec.name, doc.layers().add(layer));
}

for (const o of description.objects) {
  if (o.kind !== 'mesh') throw new Error(`object ${o.name}: unknown kind ${o.kind}`);
  if (!layerIndex.has(o.layer)) throw new Error(`object ${o.name}: unknown layer ${o.layer}`);
  const mesh = new rhino.Mesh();
  const v = mesh.vertices();
  for (let i = 0; i < o.vertices.length; i += 3) v.add(o.vertices[i], o.vertices[i + 1], o.vertices[i + 2]);
  const f = mesh.faces();
  for (let i = 0; i < o.faces.length; i += 3) f.addTriFace(o.faces[i], o.faces[i + 1], o.faces[i + 2]);
  if (o.colours) {
    const c = mesh.vertexColors();
    for (let i = 0; i < o.colours.length; i += 3) c.add(o.colours[i], o.colours[i + 1], o.colours[i + 2]);
  }
  mesh.normals().computeNormals();
  mesh.compact();
  const attributes = new rhino.ObjectAttributes();
  attributes.name = o.name;
  attributes.layerIndex = layerIndex.get(o.layer);
  for (const [key, value] of Object.entries(o.user ?? {})) attributes.setUserString(key, String(value));
  doc.objects().add(mesh, attributes);
}

const bytes = doc.toByteArray();
if (!bytes || bytes.length === 0) throw new Error('rhino3dm wrote no bytes');
fs.writeFileSync(output, bytes);
console.log(`wrote ${output}: ${description.layers.length} layers, ${description.objects.length} objects, ${bytes.length} bytes`);
