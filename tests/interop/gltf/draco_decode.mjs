// Reads every GLB of manifest.json with glTF-Transform (Draco GLBs through draco3dgltf's
// decoder) and checks the vertex and face counts, COLOR_0, the ENU bounds and the geo extras.
//   node draco_decode.mjs NODE_MODULES_DIR SAMPLES_DIR
import { createRequire } from 'node:module';
import fs from 'node:fs';
import path from 'node:path';

const [modules, samples] = process.argv.slice(2);
const require = createRequire(path.join(path.resolve(modules), 'noop.js'));
const { NodeIO } = await import(require.resolve('@gltf-transform/core'));
const { ALL_EXTENSIONS } = await import(require.resolve('@gltf-transform/extensions'));
const draco3d = require('draco3dgltf');

const io = new NodeIO()
  .registerExtensions(ALL_EXTENSIONS)
  .registerDependencies({ 'draco3d.decoder': await draco3d.createDecoderModule() });

const manifest = JSON.parse(fs.readFileSync(path.join(samples, 'manifest.json'), 'utf8'));
let failed = 0;
const expect = (ok, what) => { if (!ok) { console.log(`  FAIL ${what}`); failed++; } };
for (const entry of manifest) {
  const doc = await io.read(path.join(samples, entry.file));
  const root = doc.getRoot();
  const prims = root.listMeshes().flatMap((m) => m.listPrimitives());
  expect(prims.length === 1, `${entry.file}: one primitive, got ${prims.length}`);
  const prim = prims[0];
  const position = prim.getAttribute('POSITION');
  const vertices = position.getCount();
  const faces = prim.getIndices().getCount() / 3;
  console.log(`${entry.file}: ${vertices} vertices, ${faces} faces (expected ${entry.vertices}, ` +
              `${entry.faces}), draco=${entry.draco}`);
  expect(vertices === entry.vertices, `${entry.file}: vertex count`);
  expect(faces === entry.faces, `${entry.file}: face count`);
  expect(!!prim.getAttribute('COLOR_0') === entry.colors, `${entry.file}: COLOR_0 presence`);
  // Textured GLBs: TEXCOORD_0 in [0, 1], and a baseColorTexture whose image is a JPEG or PNG.
  const uv = prim.getAttribute('TEXCOORD_0');
  expect(!!uv === !!entry.texture, `${entry.file}: TEXCOORD_0 presence`);
  if (entry.texture && uv) {
    const a = uv.getArray();
    expect(a.every((x) => x >= 0 && x <= 1), `${entry.file}: TEXCOORD_0 within [0, 1]`);
    const tex = prim.getMaterial()?.getBaseColorTexture();
    expect(!!tex && ['image/jpeg', 'image/png'].includes(tex.getMimeType()) && tex.getImage().byteLength > 100,
           `${entry.file}: baseColorTexture with an embedded image`);
  }
  const used = root.listExtensionsUsed().map((e) => e.extensionName);
  expect(used.includes('KHR_draco_mesh_compression') === entry.draco, `${entry.file}: Draco extension`);
  // Every index is in range and positions are finite; glTF +Y is up (ENU u), so the terrain's
  // vertical extent is along y and much smaller than its horizontal one.
  const idx = prim.getIndices().getArray();
  let maxIndex = 0;
  for (const i of idx) maxIndex = Math.max(maxIndex, i);
  expect(maxIndex < vertices, `${entry.file}: index in range`);
  const min = position.getMin([]), max = position.getMax([]);
  expect(min.every(Number.isFinite) && max.every(Number.isFinite), `${entry.file}: finite bounds`);
  expect(max[1] - min[1] < 0.5 * Math.max(max[0] - min[0], max[2] - min[2]),
         `${entry.file}: glTF +Y is up`);
  const extras = root.getDefaultScene()?.getExtras() ?? {};
  expect(extras.origin && Math.abs(extras.origin.lat_deg - 50.8225) < 1e-12,
         `${entry.file}: scene extras hold the geo origin`);
}
process.exit(failed ? 1 : 0);
