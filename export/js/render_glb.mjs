// Renders a .glb to a PNG with headless Chromium, for looking at the model (no dependency but
// Chromium): writes an HTML page holding the file and a small WebGL2 renderer (flat shading,
// material colour x COLOR_0, translucent materials last) and screenshots it.
//   node render_glb.mjs model.glb out.png [azimuth_deg=35] [elevation_deg=30] [size=1400] [zoom=1]
// zoom > 1 looks at the middle of the model from closer (to see ribbons and bolts).
import fs from 'node:fs';
import os from 'node:os';
import path from 'node:path';
import { execFileSync } from 'node:child_process';

const [file, png, az = '35', el = '30', size = '1400', zoom = '1'] = process.argv.slice(2);
if (!file || !png) {
  console.error('usage: node render_glb.mjs model.glb out.png [azimuth_deg] [elevation_deg] [size] [zoom]');
  process.exit(2);
}
const b64 = fs.readFileSync(file).toString('base64');
const page = `<!doctype html><html><body style="margin:0;background:#fff">
<canvas id="c" width="${size}" height="${size}"></canvas><script>
const bytes = Uint8Array.from(atob("${b64}"), c => c.charCodeAt(0));
const dv = new DataView(bytes.buffer);
const jsonLen = dv.getUint32(12, true);
const gltf = JSON.parse(new TextDecoder().decode(bytes.subarray(20, 20 + jsonLen)));
const binStart = 20 + jsonLen + 8;
function acc(i) {
  const a = gltf.accessors[i], v = gltf.bufferViews[a.bufferView];
  const n = {SCALAR: 1, VEC3: 3}[a.type];
  const off = binStart + (v.byteOffset || 0) + (a.byteOffset || 0);
  return a.componentType === 5126 ? new Float32Array(bytes.buffer.slice(off, off + a.count * n * 4))
                                  : new Uint32Array(bytes.buffer.slice(off, off + a.count * n * 4));
}
function mul(a, b) { const r = new Array(16).fill(0);
  for (let i = 0; i < 4; ++i) for (let j = 0; j < 4; ++j) for (let k = 0; k < 4; ++k) r[j*4+i] += a[k*4+i] * b[j*4+k]; return r; }
function nodeMatrix(n) {
  let m = [1,0,0,0, 0,1,0,0, 0,0,1,0, 0,0,0,1];
  if (n.rotation) { const [x,y,z,w] = n.rotation;
    m = [1-2*(y*y+z*z), 2*(x*y+z*w), 2*(x*z-y*w), 0, 2*(x*y-z*w), 1-2*(x*x+z*z), 2*(y*z+x*w), 0,
         2*(x*z+y*w), 2*(y*z-x*w), 1-2*(x*x+y*y), 0, 0,0,0,1]; }
  return m;
}
const draws = [];
function walk(i, parent) {
  const n = gltf.nodes[i], m = mul(parent, nodeMatrix(n));
  if (n.mesh !== undefined) for (const p of gltf.meshes[n.mesh].primitives) draws.push({p, m});
  for (const c of n.children || []) walk(c, m);
}
for (const r of gltf.scenes[gltf.scene || 0].nodes) walk(r, [1,0,0,0, 0,1,0,0, 0,0,1,0, 0,0,0,1]);
let lo = [1e30,1e30,1e30], hi = [-1e30,-1e30,-1e30];
for (const d of draws) { const P = acc(d.p.attributes.POSITION); d.P = P;
  for (let i = 0; i < P.length; i += 3) { const x = P[i], y = P[i+1], z = P[i+2];
    const q = [0,1,2].map(k => d.m[k]*x + d.m[4+k]*y + d.m[8+k]*z + d.m[12+k]);
    for (let k = 0; k < 3; ++k) { lo[k] = Math.min(lo[k], q[k]); hi[k] = Math.max(hi[k], q[k]); } } }
const centre = lo.map((v, k) => (v + hi[k]) / 2), radius = Math.hypot(hi[0]-lo[0], hi[1]-lo[1], hi[2]-lo[2]) / 2;
const az = ${Number(az)} * Math.PI / 180, el = ${Number(el)} * Math.PI / 180;
const dir = [Math.cos(el) * Math.sin(az), Math.sin(el), Math.cos(el) * Math.cos(az)];
const dist = radius / Math.sin(Math.PI / 10) * 1.05 / ${Number(zoom)};
const eye = centre.map((c, k) => c + dist * dir[k]);
function lookAt(e, c) { const f = c.map((v,k) => v - e[k]); const fl = Math.hypot(...f); f.forEach((v,k) => f[k] = v/fl);
  let s = [f[1]*0 - f[2]*1, f[2]*0 - f[0]*0, f[0]*1 - f[1]*0]; const sl = Math.hypot(...s); s = s.map(v => v/sl);
  const u = [s[1]*f[2]-s[2]*f[1], s[2]*f[0]-s[0]*f[2], s[0]*f[1]-s[1]*f[0]];
  return [s[0],u[0],-f[0],0, s[1],u[1],-f[1],0, s[2],u[2],-f[2],0, -(s[0]*e[0]+s[1]*e[1]+s[2]*e[2]), -(u[0]*e[0]+u[1]*e[1]+u[2]*e[2]), f[0]*e[0]+f[1]*e[1]+f[2]*e[2], 1]; }
const near = Math.max(dist - 1.2 * radius, dist / 1000), far = dist + 1.2 * radius, t = 1 / Math.tan(Math.PI / 10);
const proj = [t,0,0,0, 0,t,0,0, 0,0,(far+near)/(near-far),-1, 0,0,2*far*near/(near-far),0];
const viewProj = mul(proj, lookAt(eye, centre));
const gl = document.getElementById('c').getContext('webgl2', {antialias: true, preserveDrawingBuffer: true});
function shader(type, src) { const s = gl.createShader(type); gl.shaderSource(s, src); gl.compileShader(s);
  if (!gl.getShaderParameter(s, gl.COMPILE_STATUS)) throw new Error(gl.getShaderInfoLog(s)); return s; }
const prog = gl.createProgram();
gl.attachShader(prog, shader(gl.VERTEX_SHADER, \`#version 300 es
in vec3 pos; in vec3 col; uniform mat4 vp, model; out vec3 wpos; out vec3 vcol;
void main() { vec4 w = model * vec4(pos, 1.0); wpos = w.xyz; vcol = col; gl_Position = vp * w; }\`));
gl.attachShader(prog, shader(gl.FRAGMENT_SHADER, \`#version 300 es
precision highp float; in vec3 wpos; in vec3 vcol; uniform vec4 base; uniform vec3 eye; out vec4 o;
void main() { vec3 n = normalize(cross(dFdx(wpos), dFdy(wpos))); if (dot(n, eye - wpos) < 0.0) n = -n;
  vec3 l = normalize(vec3(0.4, 1.0, 0.6)); float d = 0.35 + 0.65 * max(dot(n, l), 0.0);
  vec3 c = pow(base.rgb * vcol * d, vec3(1.0 / 2.2)); o = vec4(c, base.a); }\`));
gl.linkProgram(prog); gl.useProgram(prog);
gl.clearColor(1, 1, 1, 1); gl.clear(gl.COLOR_BUFFER_BIT | gl.DEPTH_BUFFER_BIT); gl.enable(gl.DEPTH_TEST);
gl.uniformMatrix4fv(gl.getUniformLocation(prog, 'vp'), false, viewProj);
gl.uniform3fv(gl.getUniformLocation(prog, 'eye'), eye);
const pass = (blend) => { for (const d of draws) {
  const mat = gltf.materials[d.p.material] || {}; const base = (mat.pbrMetallicRoughness || {}).baseColorFactor || [1,1,1,1];
  if ((mat.alphaMode === 'BLEND') !== blend) continue;
  const vao = gl.createVertexArray(); gl.bindVertexArray(vao);
  const b = gl.createBuffer(); gl.bindBuffer(gl.ARRAY_BUFFER, b); gl.bufferData(gl.ARRAY_BUFFER, d.P, gl.STATIC_DRAW);
  const lp = gl.getAttribLocation(prog, 'pos'); gl.enableVertexAttribArray(lp); gl.vertexAttribPointer(lp, 3, gl.FLOAT, false, 0, 0);
  const lc = gl.getAttribLocation(prog, 'col');
  if (d.p.attributes.COLOR_0 !== undefined) { const cb = gl.createBuffer(); gl.bindBuffer(gl.ARRAY_BUFFER, cb);
    gl.bufferData(gl.ARRAY_BUFFER, acc(d.p.attributes.COLOR_0), gl.STATIC_DRAW); gl.enableVertexAttribArray(lc); gl.vertexAttribPointer(lc, 3, gl.FLOAT, false, 0, 0);
  } else { gl.disableVertexAttribArray(lc); gl.vertexAttrib3f(lc, 1, 1, 1); }
  const ib = gl.createBuffer(); gl.bindBuffer(gl.ELEMENT_ARRAY_BUFFER, ib); const I = acc(d.p.indices);
  gl.bufferData(gl.ELEMENT_ARRAY_BUFFER, I, gl.STATIC_DRAW);
  gl.uniformMatrix4fv(gl.getUniformLocation(prog, 'model'), false, d.m);
  gl.uniform4fv(gl.getUniformLocation(prog, 'base'), base);
  gl.drawElements(gl.TRIANGLES, I.length, gl.UNSIGNED_INT, 0); } };
pass(false); gl.enable(gl.BLEND); gl.blendFunc(gl.SRC_ALPHA, gl.ONE_MINUS_SRC_ALPHA); gl.depthMask(false); pass(true);
document.title = 'rendered ' + draws.length;
</script></body></html>`;
const dir = fs.mkdtempSync(path.join(os.tmpdir(), 'egg-render-'));
const html = path.join(dir, 'view.html');
fs.writeFileSync(html, page);
try {
  execFileSync('chromium', ['--headless', '--no-sandbox', '--no-first-run', '--disable-extensions',
    '--use-angle=swiftshader', '--enable-unsafe-swiftshader', '--hide-scrollbars',
    `--window-size=${size},${size}`, '--virtual-time-budget=20000', `--screenshot=${path.resolve(png)}`,
    'file://' + html], { stdio: ['ignore', 'ignore', 'pipe'], timeout: 180000 });
} finally {
  fs.rmSync(dir, { recursive: true, force: true });
}
console.log(`wrote ${png}`);
