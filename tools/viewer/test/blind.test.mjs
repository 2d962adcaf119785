// Tests for lib/blind.js: the seeded key, the recognition matching and the unblinding.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { execFileSync } from 'node:child_process';
import fs from 'node:fs';
import os from 'node:os';
import path from 'node:path';
import { fileURLToPath } from 'node:url';
import { makeKey, recognises, unblind, median, markdown, rng, shuffle, EZ_FOR_SPECIES, SPECIES_NAMES } from '../lib/blind.js';

const SPECIES = ['ash', 'beech', 'birch', 'bush', 'cedar', 'cypress', 'fir', 'maple', 'oak', 'palm', 'pine', 'poplar', 'sapling', 'spruce', 'willow'];
const EZ_PRESETS = ['Ash Small', 'Ash Medium', 'Ash Large', 'Aspen Small', 'Aspen Medium', 'Aspen Large', 'Bush 1', 'Bush 2', 'Bush 3',
  'Oak Small', 'Oak Medium', 'Oak Large', 'Pine Small', 'Pine Medium', 'Pine Large'];

test('every species has a real ez-tree 1.1.0 preset and accepted names', () => {
  for (const sp of SPECIES) {
    assert.ok(EZ_PRESETS.includes(EZ_FOR_SPECIES[sp]), `${sp} -> ${EZ_FOR_SPECIES[sp]}`);
    assert.ok(SPECIES_NAMES[sp].length > 0, sp);
  }
});

test('the key is a function of the seed, and different seeds give different keys', () => {
  const a = makeKey(SPECIES, 23);
  assert.deepEqual(makeKey(SPECIES, 23), a);
  const b = makeKey(SPECIES, 24);
  assert.notDeepEqual(b.pairs.map((p) => p.A), a.pairs.map((p) => p.A));
});

test('each pair holds one Sylva and one ez-tree side; every species once in pairs and images', () => {
  const k = makeKey(SPECIES, 7);
  assert.equal(k.pairs.length, SPECIES.length);
  assert.deepEqual(k.pairs.map((p) => p.species).sort(), [...SPECIES].sort());
  for (const p of k.pairs) assert.deepEqual([p.A, p.B].sort(), ['ez-tree', 'sylva']);
  assert.deepEqual(k.recognition.map((r) => r.species).sort(), [...SPECIES].sort());
  const names = k.recognition.map((r) => r.image);
  assert.equal(new Set(names).size, names.length);
  for (const n of names) assert.match(n, /^tree_\d\d$/);
  // The image names do not follow the species' alphabetical order.
  const inOrder = [...k.recognition].sort((x, y) => x.species.localeCompare(y.species)).map((r) => r.image);
  assert.notDeepEqual(inOrder, [...names].sort());
});

test('Sylva lands on both sides over many seeds, about half the time', () => {
  let left = 0;
  let n = 0;
  for (let s = 1; s <= 40; s++) {
    for (const p of makeKey(SPECIES, s).pairs) {
      n++;
      if (p.A === 'sylva') left++;
    }
  }
  assert.ok(left / n > 0.4 && left / n < 0.6, `${left} of ${n}`);
});

test('shuffle keeps the items; rng stays in [0, 1)', () => {
  const r = rng(5);
  for (let i = 0; i < 1000; i++) {
    const x = r();
    assert.ok(x >= 0 && x < 1);
  }
  assert.deepEqual(shuffle([1, 2, 3, 4, 5], rng(1)).sort(), [1, 2, 3, 4, 5]);
});

test('recognition matches whole words and aliases, not neighbours', () => {
  assert.ok(recognises('Norway spruce', 'spruce'));
  assert.ok(recognises('weeping willow (Salix)', 'willow'));
  assert.ok(recognises('Abies alba', 'fir'));
  assert.ok(recognises('shrub', 'bush'));
  assert.ok(recognises('Horse chestnut (Aesculus hippocastanum), young tree', 'sapling'));
  assert.ok(!recognises('Maple (Acer sp.), young tree / sapling', 'sapling'));
  assert.ok(!recognises('spruce', 'fir'));
  assert.ok(!recognises('ashwood', 'ash'));
  assert.ok(!recognises('firethorn', 'fir'));
  assert.ok(!recognises('', 'oak'));
  assert.ok(!recognises(null, 'oak'));
});

test('median of odd, even and partly missing lists', () => {
  assert.equal(median([3, 1, 2]), 2);
  assert.equal(median([4, 1, 3, 2]), 2.5);
  assert.equal(median([null, 5, undefined]), 5);
  assert.equal(median([]), null);
});

// What a reader who knows the tree writes: its first listed name (the sapling's is horse chestnut).
const nameOf = (sp) => SPECIES_NAMES[sp][0];

function answersFor(key, sylvaScore, ezScore, preferSylva, names) {
  const pairs = {};
  for (const p of key.pairs) {
    const s = p.A === 'sylva' ? 'A' : 'B';
    const e = s === 'A' ? 'B' : 'A';
    pairs[p.pair] = { [s]: sylvaScore, [e]: ezScore, prefer: preferSylva ? s : e };
  }
  const recognition = {};
  for (const r of key.recognition) recognition[`${r.image}.png`] = { species: names(r.species), confidence: 4 };
  return { reader: 'test', pairs, recognition };
}

test('unblind puts each score on the right tree and checks the goals', () => {
  const key = makeKey(SPECIES, 11);
  const good = unblind(key, answersFor(key, 8, 5, true, nameOf));
  assert.deepEqual(good.problems, []);
  for (const r of good.rows) {
    assert.equal(r.sylva_score, 8);
    assert.equal(r.ez_score, 5);
    assert.equal(r.preferred, 'sylva');
    assert.equal(r.recognised, true);
  }
  assert.equal(good.summary.sylva_median, 8);
  assert.equal(good.summary.ez_median, 5);
  assert.equal(good.summary.sylva_preferred, SPECIES.length);
  assert.ok(good.summary.goal_preferred_every_pair && good.summary.goal_median_7 && good.summary.goal_recognition);

  // The reader prefers ez-tree and calls every fir a spruce.
  const bad = unblind(key, answersFor(key, 4, 6, false, (sp) => (sp === 'fir' ? 'spruce' : nameOf(sp))));
  assert.equal(bad.summary.sylva_median, 4);
  assert.equal(bad.summary.ez_preferred, SPECIES.length);
  assert.equal(bad.rows.find((r) => r.species === 'fir').recognised, false);
  assert.equal(bad.summary.recognised, SPECIES.length - 1);
  assert.ok(!bad.summary.goal_preferred_every_pair && !bad.summary.goal_median_7 && !bad.summary.goal_recognition);
});

test('unanswered pairs and images are reported, ties counted', () => {
  const key = makeKey(['oak', 'pine'], 3);
  const [p0] = key.pairs;
  const res = unblind(key, { reader: 'r', pairs: { [p0.pair]: { A: 5, B: 5, prefer: '=' } }, recognition: {} });
  assert.equal(res.summary.ties, 1);
  assert.equal(res.problems.length, 3); // one pair, two images
  assert.match(markdown(key, [res]), /\| oak \|/);
});

test('judge-score.mjs prints the unblinded table for a key and an answers file', () => {
  const dir = fs.mkdtempSync(path.join(os.tmpdir(), 'judge-score-'));
  const key = makeKey(SPECIES, 23);
  fs.writeFileSync(path.join(dir, 'key.json'), JSON.stringify(key));
  fs.writeFileSync(path.join(dir, 'a.json'), JSON.stringify({ ...answersFor(key, 7, 6, true, nameOf), reader: 'artist' }));
  const script = path.join(path.dirname(fileURLToPath(import.meta.url)), '..', 'judge-score.mjs');
  const out = execFileSync('node', [script, path.join(dir, 'key.json'), path.join(dir, 'a.json')], { encoding: 'utf8' });
  fs.rmSync(dir, { recursive: true });
  assert.match(out, /### Reader: artist/);
  assert.match(out, /\| willow \| Ash Large \| 7 \| 6 \| sylva \| willow \| yes \| 4 \|/);
  assert.match(out, /\| artist \| 7 \| 6 \| 15 of 15 \| 15 of 15 \| 4 \| yes \| yes \| yes \|/);
});
