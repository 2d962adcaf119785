#!/usr/bin/env node
// The blind-judging kit (issue 23, docs/JUDGING.md): renders every Sylva species GLB and the
// nearest ez-tree preset with the same viewer page (lights, background, camera rule), and writes
//   OUT/judge/pairs/pair_NN_SPECIES[_front].png   the two trees side by side, labelled only A and B
//   OUT/judge/recognition/tree_NN[_front].png     each Sylva species alone, unlabelled
//   OUT/judge/answers-template.json, OUT/judge/INSTRUCTIONS.md   what a reader fills in and reads
//   OUT/key.json                                  which side is Sylva, which image is which species
// Only OUT/judge/ goes to a reader; key.json stays with whoever scores (judge-score.mjs).
// Run by scripts/blind-pairs.sh, which exports the GLBs first.
//
//   node tools/viewer/blind-pairs.mjs --glb-dir DIR --preset-dir presets --out-dir /tmp/sylva-judging
//        [--seed 23] [--views iso,front] [--close-ups detail_leaves,detail_bark] [--size 768] [--binary PATH]
import fs from 'node:fs';
import path from 'node:path';
import { execFileSync } from 'node:child_process';
import { openViewer, writeDataURL, reportHeader } from './lib/harness.mjs';
import { EXCLUDED_PRESETS, EZ_FOR_SPECIES, makeKey } from './lib/blind.js';

const args = process.argv.slice(2);
const opt = { glbDir: null, presetDir: 'presets', outDir: '/tmp/sylva-judging', seed: 23, views: ['iso', 'front'], closeUps: ['detail_leaves', 'detail_bark'], size: 768, binary: '' };
for (let i = 0; i < args.length; i++) {
  const a = args[i];
  const next = () => args[++i];
  if (a === '--glb-dir') opt.glbDir = next();
  else if (a === '--preset-dir') opt.presetDir = next();
  else if (a === '--out-dir') opt.outDir = next();
  else if (a === '--seed') opt.seed = Number(next());
  else if (a === '--views') opt.views = next().split(',').map((s) => s.trim()).filter(Boolean);
  // Close-ups (viewer.js detailCamera) for the recognition plates only; the pairs keep whole trees.
  else if (a === '--close-ups') opt.closeUps = next().split(',').map((s) => s.trim()).filter(Boolean);
  else if (a === '--size') opt.size = Number(next());
  else if (a === '--binary') opt.binary = next();
  else {
    process.stderr.write(`blind-pairs: unknown argument ${a}\n`);
    process.exit(2);
  }
}
if (!opt.glbDir || !Number.isInteger(opt.seed) || !opt.views.length || !Number.isInteger(opt.size)) {
  process.stderr.write('usage: blind-pairs.mjs --glb-dir DIR [--preset-dir DIR] [--out-dir DIR] [--seed N] [--views iso,front] [--close-ups detail_leaves,detail_bark] [--size N]\n');
  process.exit(2);
}

// The first view's images carry no suffix; the others carry _VIEW.
const suffix = (view) => (view === opt.views[0] ? '' : `_${view.replace(/[^a-z0-9]+/gi, '_')}`);
const viewsOf = (kind) => (kind === 'sylva' ? [...opt.views, ...opt.closeUps] : opt.views);

const species = fs
  .readdirSync(opt.presetDir)
  .filter((f) => /^species_.+\.json$/.test(f) && !EXCLUDED_PRESETS.includes(f.replace(/\.json$/, '')))
  .map((f) => f.replace(/^species_|\.json$/g, ''))
  .sort();
const missing = species.filter((sp) => !fs.existsSync(path.join(opt.glbDir, `species_${sp}.glb`)));
if (missing.length) process.stderr.write(`blind-pairs: no GLB for ${missing.join(', ')} (export failed?); left out\n`);
const judged = species.filter((sp) => !missing.includes(sp));
if (!judged.length) {
  process.stderr.write(`blind-pairs: no species GLBs in ${opt.glbDir}\n`);
  process.exit(1);
}
const unmapped = judged.filter((sp) => !EZ_FOR_SPECIES[sp]);
if (unmapped.length) process.stderr.write(`blind-pairs: no ez-tree preset chosen for ${unmapped.join(', ')}; using the default (lib/blind.js)\n`);

const key = makeKey(judged, opt.seed);
const ezPresets = [...new Set(key.pairs.map((p) => p.ez_preset))];

const renderDir = path.join(opt.outDir, 'renders'); // named by species: never shown to a reader
const judgeDir = path.join(opt.outDir, 'judge');
for (const d of [renderDir, judgeDir]) fs.rmSync(d, { recursive: true, force: true });
for (const d of [renderDir, path.join(judgeDir, 'pairs'), path.join(judgeDir, 'recognition')]) fs.mkdirSync(d, { recursive: true });

const files = judged.map((sp) => path.join(opt.glbDir, `species_${sp}.glb`));
const slug = (s) => s.toLowerCase().replace(/[^a-z0-9]+/g, '_');
const renderPath = (kind, name, view) => path.join(renderDir, `${kind}_${slug(name)}${suffix(view)}.png`);

const t0 = Date.now();
const viewer = await openViewer(files, { size: opt.size });
const failed = [];
const info = {};
try {
  const jobs = [
    ...judged.map((sp, i) => ({ kind: 'sylva', name: sp, spec: { kind: 'glb', file: i } })),
    ...ezPresets.map((p) => ({ kind: 'ez', name: p, spec: { kind: 'ez', preset: p } })),
  ];
  for (const job of jobs) {
    for (const view of viewsOf(job.kind)) {
      try {
        const r = await viewer.show(job.spec, { view, size: opt.size });
        writeDataURL(r.image, renderPath(job.kind, job.name, view));
        info[`${job.kind} ${job.name}`] = { triangles: r.triangles, draw_calls: r.draw_calls, bbox: r.bbox };
      } catch (e) {
        failed.push(`${job.kind} ${job.name} ${view}: ${e.message}`);
      }
    }
    process.stderr.write(`blind-pairs: rendered ${job.kind} ${job.name} (${((Date.now() - t0) / 1000).toFixed(0)} s)\n`);
  }
} finally {
  await viewer.close();
}

// Pairs: left tile labelled A, right tile B; nothing else on the image.
const montage = (tiles, out) =>
  execFileSync('montage', [...tiles.flatMap(([label, img]) => ['-label', label, img]), '-tile', `${tiles.length}x1`, '-geometry', `${opt.size}x${opt.size}+8+8`,
    '-font', 'DejaVu-Sans', '-pointsize', '44', '-background', 'white', out], { stdio: ['ignore', 'inherit', 'inherit'] });
for (const p of key.pairs) {
  for (const view of opt.views) {
    const img = (who) => (who === 'sylva' ? renderPath('sylva', p.species, view) : renderPath('ez', p.ez_preset, view));
    const a = img(p.A);
    const b = img(p.B);
    if (!fs.existsSync(a) || !fs.existsSync(b)) continue;
    montage([['A', a], ['B', b]], path.join(judgeDir, 'pairs', `${p.pair}${suffix(view)}.png`));
  }
}
for (const r of key.recognition) {
  for (const view of viewsOf('sylva')) {
    const src = renderPath('sylva', r.species, view);
    if (fs.existsSync(src)) fs.copyFileSync(src, path.join(judgeDir, 'recognition', `${r.image}${suffix(view)}.png`));
  }
}

// What the reader fills in: every pair and image, blank.
const template = {
  reader: '',
  pairs: Object.fromEntries(key.pairs.map((p) => [p.pair, { A: null, B: null, prefer: null, note: '' }])),
  recognition: Object.fromEntries(key.recognition.map((r) => [r.image, { species: '', confidence: null, note: '' }])),
};
fs.writeFileSync(path.join(judgeDir, 'answers-template.json'), JSON.stringify(template, null, 2) + '\n');
const viewNote = (opt.views.length > 1 ? ` Each image has a second view (${opt.views.slice(1).map((v) => `\`_${v}\``).join(', ')}) of the same trees, in the same order.` : '') +
  (opt.closeUps.length ? ` In part 1 each tree also has close-ups (${opt.closeUps.map((v) => `\`_${v}\``).join(', ')}): about 1.4 m of the crown's surface at mid-height, and the trunk at breast height.` : '');
fs.writeFileSync(
  path.join(judgeDir, 'INSTRUCTIONS.md'),
  `# Tree judging

Please do part 1 before you open the \`pairs/\` folder. Judge each image on its own: do not
compare it with the others or reason by elimination. Fill in a copy of \`answers-template.json\`
(your name or role as \`reader\`) and send it back.${viewNote}

## Part 1: recognition (\`recognition/\`)

Each \`tree_NN.png\` shows one tree. For each, write the species (or genus) you see in
\`species\`, and how sure you are in \`confidence\`, from 1 (a guess) to 5 (certain). Judge each
image alone: if two images look like the same species, say so for both.

## Part 2: pairs (\`pairs/\`)

Each \`pair_NN_SPECIES.png\` shows two trees, A (left) and B (right), meant to be that species.
For each tree answer: **would you ship this as a hero asset of that species?** Score it from
1 to 10 in \`A\` and \`B\`, where **10 is SpeedTree library quality** and **5 is background
filler**. Then say which of the two you would rather ship in \`prefer\` (\`A\` or \`B\`; \`=\`
only when you truly cannot choose). A short \`note\` on what is wrong helps most.
`,
);

const report = {
  ...reportHeader(opt, viewer),
  views: opt.views,
  close_ups: opt.closeUps,
  size: opt.size,
  excluded: EXCLUDED_PRESETS,
  ez_for_species: Object.fromEntries(judged.map((sp) => [sp, key.pairs.find((p) => p.species === sp).ez_preset])),
  ...key,
  trees: info,
  render_seconds: (Date.now() - t0) / 1000,
  failed,
  page_errors: viewer.errors,
};
fs.writeFileSync(path.join(opt.outDir, 'key.json'), JSON.stringify(report, null, 2) + '\n');
process.stdout.write(
  `blind-pairs: ${key.pairs.length} pairs and ${key.recognition.length} recognition images (${opt.views.join(', ')}) in ${judgeDir}; key in ${path.join(opt.outDir, 'key.json')}; ` +
    `${((Date.now() - t0) / 1000).toFixed(0)} s\n`,
);
if (failed.length || viewer.errors.length) process.stderr.write(`blind-pairs: problems:\n  ${[...failed, ...viewer.errors].join('\n  ')}\n`);
process.exit(failed.length || viewer.errors.length ? 1 : 0);
