// node --test tools/viewer/test/ : the coverage metric on hand-made masks (no browser needed).
import test from 'node:test';
import assert from 'node:assert/strict';
import { convexHull, rasterizeHull, computeCoverage } from '../lib/coverage.js';

function mask(w, h, fn) {
  const m = new Uint8Array(w * h);
  for (let y = 0; y < h; y++) for (let x = 0; x < w; x++) m[y * w + x] = fn(x, y) ? 1 : 0;
  return m;
}
const sum = (m) => m.reduce((a, b) => a + b, 0);

test('hull of a square keeps its four corners', () => {
  const pts = [];
  for (let y = 0; y < 5; y++) for (let x = 0; x < 5; x++) pts.push([x, y]);
  assert.deepEqual(convexHull(pts).sort(), [[0, 0], [0, 4], [4, 0], [4, 4]].sort());
});

test('rasterised hull of a square counts its pixels', () => {
  const hull = [[2, 2], [6, 2], [6, 5], [2, 5]];
  assert.equal(sum(rasterizeHull(hull, 10, 10)), 5 * 4);
});

test('rasterised triangle holds the pixel centres on or inside its edges', () => {
  const hull = [[0, 0], [4, 4], [0, 4]];
  // rows 0..4 hold 1, 2, 3, 4, 5 pixels
  assert.equal(sum(rasterizeHull(hull, 8, 8)), 15);
});

test('a full crown is fully covered and the trunk below it does not count', () => {
  const w = 20;
  const h = 20;
  const leaf = mask(w, h, (x, y) => x >= 4 && x < 16 && y >= 2 && y < 12);
  const bark = mask(w, h, (x, y) => x >= 9 && x < 11 && y >= 8 && y < 19);
  const whole = leaf.map((v, i) => v | bark[i]);
  const r = computeCoverage({ width: w, height: h, whole, leaf, bark });
  assert.equal(r.crown_base_row, 11);
  assert.equal(r.hull_px, 12 * 10);
  assert.equal(r.leaf_px, 120);
  assert.equal(r.coverage, 1);
  assert.equal(r.bark_px, 2 * 11);
});

test('gaps in the crown lower coverage; the hull spans the branch tips', () => {
  const w = 30;
  const h = 30;
  // bark: a trunk and one long branch out to the right at row 5
  const bark = mask(w, h, (x, y) => (x === 10 && y >= 5 && y < 29) || (y === 5 && x >= 10 && x < 28));
  // leaves: a 6x6 block left of the trunk, rows 2..7
  const leaf = mask(w, h, (x, y) => x >= 4 && x < 10 && y >= 2 && y < 8);
  const whole = leaf.map((v, i) => v | bark[i]);
  const r = computeCoverage({ width: w, height: h, whole, leaf, bark });
  assert.equal(r.crown_base_row, 7);
  assert.ok(r.hull_px > 36 + 18, `hull ${r.hull_px} must reach the branch tip`);
  assert.equal(r.leaf_px, 36);
  assert.ok(Math.abs(r.coverage - 36 / r.hull_px) < 1e-12);
});

test('no leaves: coverage 0 over the whole silhouette', () => {
  const w = 10;
  const h = 10;
  const bark = mask(w, h, (x, y) => x === 5 && y > 1);
  const leaf = new Uint8Array(w * h);
  const r = computeCoverage({ width: w, height: h, whole: bark, leaf, bark });
  assert.equal(r.crown_base_row, -1);
  assert.equal(r.coverage, 0);
  assert.equal(r.hull_px, 8);
});
