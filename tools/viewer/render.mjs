#!/usr/bin/env node
// Renders one tree to a PNG with the viewer page in headless Chromium.
//   node tools/viewer/render.mjs FILE.glb OUT.png [--view iso|front|side|top|ELEV,AZIM] [--size 768]
//   node tools/viewer/render.mjs --ez "Oak Medium" OUT.png
// --measure prints the coverage numbers as JSON too; --overlay FILE.png writes the measurement
// picture (hull, leaves, bark). --animation NAME --time SECONDS poses the file's animation clip at
// that moment (the camera is fitted to the rest pose), e.g. --animation wind --time 1.5.
import path from 'node:path';
import { openViewer, writeDataURL } from './lib/harness.mjs';

function usage(code) {
  process.stderr.write(
    'usage: node tools/viewer/render.mjs (FILE.glb | --ez PRESET) OUT.png [--view iso|front|side|top|ELEV,AZIM] [--size N] [--measure] [--overlay FILE.png] [--animation NAME --time S] [--verbose]\n',
  );
  process.exit(code);
}

const args = process.argv.slice(2);
const opts = { view: 'iso', size: 768, measure: false, overlay: null, verbose: false, ez: null };
const pos = [];
for (let i = 0; i < args.length; i++) {
  const a = args[i];
  if (a === '--view') opts.view = args[++i];
  else if (a === '--size') opts.size = Number(args[++i]);
  else if (a === '--ez') opts.ez = args[++i];
  else if (a === '--measure') opts.measure = true;
  else if (a === '--overlay') opts.overlay = args[++i];
  else if (a === '--verbose') opts.verbose = true;
  else if (a === '--animation') opts.animation = args[++i];
  else if (a === '--time') opts.time = Number(args[++i]);
  else if (a === '-h' || a === '--help') usage(0);
  else if (a.startsWith('--')) usage(2);
  else pos.push(a);
}
if (opts.ez ? pos.length !== 1 : pos.length !== 2) usage(2);
if (!Number.isInteger(opts.size) || opts.size < 16 || opts.size > 4096) usage(2);
const out = pos[pos.length - 1];
const files = opts.ez ? [] : [pos[0]];

const viewer = await openViewer(files, { size: opts.size, verbose: opts.verbose });
let code = 0;
try {
  const spec = opts.ez ? { kind: 'ez', preset: opts.ez } : { kind: 'glb', file: 0 };
  const r = await viewer.show(spec, {
    view: opts.view,
    size: opts.size,
    measure: opts.measure || !!opts.overlay,
    overlay: !!opts.overlay,
    animation: opts.animation,
    time: opts.time,
  });
  writeDataURL(r.image, out);
  if (opts.overlay) writeDataURL(r.overlay, opts.overlay);
  delete r.image;
  delete r.overlay;
  r.name = opts.ez || path.basename(pos[0]);
  if (opts.measure) process.stdout.write(JSON.stringify(r) + '\n');
  process.stderr.write(`${out}: ${r.name}, ${r.triangles} triangles, ${r.draw_calls} draw calls${r.detail_target ? `, close-up on ${r.detail_target.map((v) => v.toFixed(2)).join(" ")}` : ""} (${viewer.webgl})\n`);
  if (viewer.errors.length) {
    process.stderr.write(viewer.errors.join('\n') + '\n');
    code = 1;
  }
} catch (e) {
  process.stderr.write(`render failed: ${e.message}\n${viewer.errors.join('\n')}\n`);
  code = 1;
} finally {
  await viewer.close();
}
process.exit(code);
