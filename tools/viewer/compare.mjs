#!/usr/bin/env node
// Renders Sylva's species GLBs and ez-tree presets with the same viewer, measures leaf coverage
// of the crown hull, and writes the pictures and numbers. Run by scripts/compare-trees.sh, which
// exports the GLBs first.
//
//   node tools/viewer/compare.mjs --glb-dir DIR --preset-dir presets --out-dir out/compare
//        --grid out/side_by_side.png [--ez "Oak Medium,Pine Medium,..."] [--size 768] [--azimuths 45,135,225,315]
//
// DIR holds species_NAME.glb for each exported preset; presets/species_NAME.json gives the
// tags (a "conifer" tag picks the conifer goal).
import fs from 'node:fs';
import path from 'node:path';
import { execFileSync } from 'node:child_process';
import { openViewer, writeDataURL, pkgVersion, reportHeader } from './lib/harness.mjs';

const GRID_SPECIES = ['oak', 'pine', 'birch', 'willow', 'maple', 'palm'];
const DEFAULT_EZ = ['Oak Medium', 'Pine Medium', 'Aspen Medium', 'Ash Medium'];
const GOAL = { broadleaf: 0.55, conifer: 0.45 };

const args = process.argv.slice(2);
const opt = { size: 768, ez: DEFAULT_EZ, glbDir: null, presetDir: 'presets', outDir: 'out/compare', grid: 'out/side_by_side.png', binary: '', azimuths: [45, 135, 225, 315] };
for (let i = 0; i < args.length; i++) {
  const a = args[i];
  const next = () => args[++i];
  if (a === '--glb-dir') opt.glbDir = next();
  else if (a === '--preset-dir') opt.presetDir = next();
  else if (a === '--out-dir') opt.outDir = next();
  else if (a === '--grid') opt.grid = next();
  else if (a === '--size') opt.size = Number(next());
  else if (a === '--ez') opt.ez = next().split(',').map((s) => s.trim()).filter(Boolean);
  else if (a === '--binary') opt.binary = next();
  else if (a === '--azimuths') opt.azimuths = next().split(',').filter(Boolean).map(Number);
  else {
    process.stderr.write(`compare: unknown argument ${a}\n`);
    process.exit(2);
  }
}
if (!opt.glbDir) {
  process.stderr.write('compare: --glb-dir is required\n');
  process.exit(2);
}


// Sylva trees: every species_*.json in the preset dir, grid species first.
const presetFiles = fs.existsSync(opt.presetDir) ? fs.readdirSync(opt.presetDir).filter((f) => /^species_.+\.json$/.test(f)) : [];
const speciesFound = presetFiles.map((f) => f.replace(/^species_|\.json$/g, ''));
const ordered = [...GRID_SPECIES.filter((s) => speciesFound.includes(s)), ...speciesFound.filter((s) => !GRID_SPECIES.includes(s)).sort()];
const missing = GRID_SPECIES.filter((s) => !speciesFound.includes(s));

const trees = [];
const files = [];
for (const sp of ordered) {
  let tags = [];
  try {
    tags = JSON.parse(fs.readFileSync(path.join(opt.presetDir, `species_${sp}.json`), 'utf8')).tags || [];
  } catch {
    /* unreadable preset: no tags */
  }
  const glb = path.join(opt.glbDir, `species_${sp}.glb`);
  const entry = {
    name: `sylva ${sp}`,
    source: 'sylva',
    species: sp,
    preset: path.join(opt.presetDir, `species_${sp}.json`),
    kind: tags.includes('conifer') ? 'conifer' : 'broadleaf',
    png: `sylva_${sp}.png`,
  };
  if (!fs.existsSync(glb)) {
    entry.error = 'export failed';
    trees.push(entry);
    continue;
  }
  entry.file = files.length;
  files.push(glb);
  trees.push(entry);
}
for (const preset of opt.ez) {
  const slug = preset.toLowerCase().replace(/[^a-z0-9]+/g, '_');
  trees.push({
    name: `ez-tree ${preset}`,
    source: 'ez-tree',
    preset,
    kind: /pine|spruce|fir|conifer/i.test(preset) ? 'conifer' : 'broadleaf',
    png: `ez_${slug}.png`,
  });
}

fs.mkdirSync(opt.outDir, { recursive: true });
// Pictures of an earlier run (a preset since removed) would linger next to the new ones.
for (const f of fs.readdirSync(opt.outDir)) {
  if (/^(sylva_|ez_).*\.png$|^all_species\.png$/.test(f)) fs.rmSync(path.join(opt.outDir, f));
}
const t0 = Date.now();
const viewer = await openViewer(files, { size: opt.size });
let failures = 0;
try {
  for (const t of trees) {
    if (t.error) continue;
    const spec = t.source === 'sylva' ? { kind: 'glb', file: t.file } : { kind: 'ez', preset: t.preset };
    try {
      const r = await viewer.show(spec, { view: 'iso', size: opt.size, measure: true, overlay: true });
      writeDataURL(r.image, path.join(opt.outDir, t.png));
      const overlay = t.png.replace(/\.png$/, '_coverage.png');
      writeDataURL(r.overlay, path.join(opt.outDir, overlay));
      delete r.image;
      delete r.overlay;
      Object.assign(t, r, { overlay_png: overlay, goal: GOAL[t.kind] });
      // The same measurement from the other three iso corners: how much of a tree's number is
      // the side it happens to show.
      t.coverage_by_azimuth = { 45: r.coverage };
      for (const az of opt.azimuths.filter((a) => a !== 45)) {
        const ra = await viewer.show(spec, { view: `35,${az}`, size: opt.size, measure: true, image: false });
        t.coverage_by_azimuth[az] = ra.coverage;
      }
      const all = Object.values(t.coverage_by_azimuth);
      t.coverage_mean_azimuths = all.reduce((a, b) => a + b, 0) / all.length;
      t.meets_goal = t.coverage >= t.goal;
    } catch (e) {
      t.error = e.message;
      failures++;
    }
    delete t.file;
  }
} finally {
  await viewer.close();
}
const seconds = (Date.now() - t0) / 1000;

process.stdout.write(`coverage: iso view at azimuth 45 deg (the goal's number); 4-az: mean over azimuths ${opt.azimuths.join(', ')}\n`);

// Side-by-side grid: Sylva's grid species on the first row (a grey tile for each missing one),
// ez-tree's presets on the second.
const tileSize = 320;
const label = (t) => (t.error ? `${t.name}\n${t.error}` : `${t.name}\ncoverage ${(100 * t.coverage).toFixed(1)}% (goal ${Math.round(100 * t.goal)}%)`);
const montageArgs = [];
const addTile = (img, text) => montageArgs.push('-label', text, img);
const cols = GRID_SPECIES.length;
for (const sp of GRID_SPECIES) {
  const t = trees.find((x) => x.source === 'sylva' && x.species === sp);
  if (t && !t.error) addTile(path.join(opt.outDir, t.png), label(t));
  else addTile(`xc:#c8ccd0`, t ? label(t) : `sylva ${sp}\nmissing: no species_${sp}.json`);
}
const ezTrees = trees.filter((t) => t.source === 'ez-tree');
for (let i = 0; i < cols; i++) {
  const t = ezTrees[i];
  if (t && !t.error) addTile(path.join(opt.outDir, t.png), label(t));
  else if (t) addTile('xc:#c8ccd0', label(t));
  else montageArgs.push('null:');
}
fs.mkdirSync(path.dirname(path.resolve(opt.grid)), { recursive: true });
let gridOk = true;
try {
  execFileSync(
    'montage',
    [
      ...montageArgs,
      '-tile', `${cols}x`,
      '-geometry', `${tileSize}x${tileSize}+6+6`,
      '-font', 'DejaVu-Sans',
      '-pointsize', '15',
      '-background', 'white',
      '-title', `Sylva species (top) vs ez-tree ${pkgVersion('@dgreenheck/ez-tree')} presets (bottom): three.js ${pkgVersion('three')}, iso view, leaf coverage of the crown hull`,
      opt.grid,
    ],
    { stdio: ['ignore', 'inherit', 'inherit'] },
  );
} catch (e) {
  gridOk = false;
  process.stderr.write(`compare: montage failed: ${e.message}\n`);
}

// Every Sylva species in one more grid (out/compare/all_species.png), six to a row.
const allSylva = trees.filter((t) => t.source === 'sylva');
if (gridOk && allSylva.length) {
  const a = [];
  for (const t of allSylva) a.push('-label', label(t), t.error ? 'xc:#c8ccd0' : path.join(opt.outDir, t.png));
  try {
    execFileSync(
      'montage',
      [...a, '-tile', `${cols}x`, '-geometry', `${tileSize}x${tileSize}+6+6`, '-font', 'DejaVu-Sans', '-pointsize', '15', '-background', 'white',
        '-title', `Sylva species presets (${opt.presetDir}), iso view, leaf coverage of the crown hull`, path.join(opt.outDir, 'all_species.png')],
      { stdio: ['ignore', 'inherit', 'inherit'] },
    );
  } catch (e) {
    gridOk = false;
    process.stderr.write(`compare: montage failed: ${e.message}\n`);
  }
}

const report = {
  ...reportHeader(opt, viewer),
  view: { name: 'iso', elevation_deg: 35, azimuth_deg: 45, fov_deg: 30, size: opt.size, extra_azimuths_deg: opt.azimuths.filter((a) => a !== 45) },
  goal: GOAL,
  missing: missing.map((s) => `species_${s}.json`),
  page_requests: [...new Set(viewer.requests)],
  page_errors: viewer.errors,
  render_seconds: seconds,
  trees,
};
fs.writeFileSync(path.join(opt.outDir, 'coverage.json'), JSON.stringify(report, null, 2) + '\n');

// Table.
const pad = (s, n) => String(s).padEnd(n);
const lpad = (s, n) => String(s).padStart(n);
const lines = [];
lines.push(`${pad('tree', 24)} ${pad('kind', 9)} ${lpad('coverage', 8)} ${lpad('4-az', 6)} ${lpad('goal', 5)} ${pad('ok', 3)} ${lpad('hull_px', 8)} ${lpad('leaf_px', 8)} ${lpad('bark_px', 8)} ${lpad('triangles', 9)} ${lpad('calls', 5)}`);
for (const t of trees) {
  if (t.error) {
    lines.push(`${pad(t.name, 24)} ${pad(t.kind, 9)} ${t.error}`);
    continue;
  }
  lines.push(
    `${pad(t.name, 24)} ${pad(t.kind, 9)} ${lpad((100 * t.coverage).toFixed(1) + '%', 8)} ${lpad((100 * t.coverage_mean_azimuths).toFixed(1) + '%', 6)} ${lpad(Math.round(100 * t.goal) + '%', 5)} ${pad(t.meets_goal ? 'yes' : 'no', 3)} ${lpad(t.hull_px, 8)} ${lpad(t.leaf_px, 8)} ${lpad(t.bark_px, 8)} ${lpad(t.triangles, 9)} ${lpad(t.draw_calls, 5)}`,
  );
}
process.stdout.write(lines.join('\n') + '\n');
if (missing.length) process.stdout.write(`missing presets: ${missing.map((s) => `species_${s}.json`).join(', ')}\n`);
process.stdout.write(`rendered ${trees.filter((t) => !t.error).length} trees in ${seconds.toFixed(1)} s with ${viewer.webgl}\n`);
process.stdout.write(`wrote ${path.join(opt.outDir, 'coverage.json')}, ${opt.outDir}/*.png${gridOk ? `, ${opt.grid}` : ''}\n`);
if (viewer.errors.length) process.stderr.write(`page errors:\n  ${viewer.errors.join('\n  ')}\n`);
process.exit(failures || !gridOk || viewer.errors.length ? 1 : 0);
