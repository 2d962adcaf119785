// Blind judging (issue 23): which ez-tree preset each Sylva species is set against, the seeded
// shuffles that hide which side of a pair is Sylva and which species a recognition image shows,
// and the scoring of a reader's answers against the key. Pure functions, no I/O: used by
// tools/viewer/blind-pairs.mjs (the images and key.json) and tools/viewer/judge-score.mjs (the
// table), and tested in test/blind.test.mjs.

// The nearest ez-tree 1.1.0 preset per Sylva species. ez-tree has Ash, Aspen, Oak and Pine in
// Small/Medium/Large and Bush 1/2/3; the reasons are in docs/JUDGING.md.
export const EZ_FOR_SPECIES = {
  oak: 'Oak Medium',
  beech: 'Oak Medium', // broad dense dome of a large broadleaf
  maple: 'Oak Medium', // rounded crown of a large broadleaf
  ash: 'Ash Medium',
  birch: 'Aspen Medium', // slender, tall clear trunk, small leaves, light bark
  poplar: 'Aspen Medium', // aspen is a poplar (Populus tremula)
  sapling: 'Ash Small', // the smallest single-stem tree ez-tree has
  bush: 'Bush 1', // a multi-stem broadleaf shrub
  pine: 'Pine Medium',
  spruce: 'Pine Medium',
  fir: 'Pine Medium',
  cedar: 'Pine Medium',
  cypress: 'Pine Medium',
  willow: 'Ash Large', // no weeping tree in ez-tree: a large broadleaf with long, drooping shoots
  palm: 'Aspen Large', // no palm in ez-tree: the tallest clear single trunk with a crown on top
};
export const EZ_DEFAULT = 'Oak Medium';

// Sylva presets that are not one tree of a species and stay out of the judging.
export const EXCLUDED_PRESETS = ['species_forest', 'species_maple_cards'];

// Names a reader may give for a species in the recognition test (matched as whole words,
// case-insensitive; only these, so a key that is not a species name, "sapling", does not count).
// A genus or a common variant counts; a neighbour does not (a "spruce" answer for the fir is wrong).
export const SPECIES_NAMES = {
  oak: ['oak', 'quercus'],
  beech: ['beech', 'fagus'],
  maple: ['maple', 'acer', 'sycamore'],
  ash: ['ash', 'fraxinus'],
  birch: ['birch', 'betula'],
  poplar: ['poplar', 'populus'],
  sapling: ['horse chestnut', 'horse-chestnut', 'horsechestnut', 'aesculus', 'buckeye'], // a young horse chestnut (docs/SPECIES.md)
  bush: ['bush', 'shrub', 'hazel', 'corylus'], // species_bush is a hazel (docs/SPECIES.md)
  pine: ['pine', 'pinus'],
  spruce: ['spruce', 'picea'],
  fir: ['fir', 'abies'],
  cedar: ['cedar', 'thuja', 'cedrus', 'arborvitae'],
  cypress: ['cypress', 'cupressus'],
  willow: ['willow', 'salix'],
  palm: ['palm', 'arecaceae'],
};

export function ezFor(species) {
  return EZ_FOR_SPECIES[species] || EZ_DEFAULT;
}

// Mulberry32: a small seeded PRNG, enough to make the shuffles reproducible from the seed.
export function rng(seed) {
  let a = seed >>> 0;
  return () => {
    a = (a + 0x6d2b79f5) >>> 0;
    let t = a;
    t = Math.imul(t ^ (t >>> 15), t | 1);
    t ^= t + Math.imul(t ^ (t >>> 7), t | 61);
    return ((t ^ (t >>> 14)) >>> 0) / 4294967296;
  };
}

// Fisher-Yates with the given random source; returns a new array.
export function shuffle(items, rand) {
  const a = items.slice();
  for (let i = a.length - 1; i > 0; i--) {
    const j = Math.floor(rand() * (i + 1));
    [a[i], a[j]] = [a[j], a[i]];
  }
  return a;
}

// The blind key for a list of Sylva species: per pair which side (A = left, B = right) is Sylva
// and which ez-tree preset it faces, in a shuffled order; per species a random recognition image
// name tree_NN. One seed decides both.
export function makeKey(species, seed, ezMap = EZ_FOR_SPECIES) {
  const rand = rng(seed);
  const pairs = shuffle(species, rand).map((sp, i) => {
    const sylvaSide = rand() < 0.5 ? 'A' : 'B';
    return {
      pair: `pair_${String(i + 1).padStart(2, '0')}_${sp}`,
      species: sp,
      ez_preset: ezMap[sp] || EZ_DEFAULT,
      A: sylvaSide === 'A' ? 'sylva' : 'ez-tree',
      B: sylvaSide === 'B' ? 'sylva' : 'ez-tree',
    };
  });
  const width = Math.max(2, String(species.length).length);
  const names = shuffle(species.map((_, i) => `tree_${String(i + 1).padStart(width, '0')}`), rand);
  const recognition = species.map((sp, i) => ({ image: names[i], species: sp })).sort((x, y) => x.image.localeCompare(y.image));
  return { seed, pairs, recognition };
}

export function median(values) {
  const v = values.filter((x) => typeof x === 'number' && Number.isFinite(x)).sort((a, b) => a - b);
  if (!v.length) return null;
  const m = v.length >> 1;
  return v.length % 2 ? v[m] : (v[m - 1] + v[m]) / 2;
}

const escapeRe = (s) => s.replace(/[.*+?^${}()|[\]\\]/g, '\\$&');

// Whether a reader's free-text name is the species: any accepted name as a whole word.
export function recognises(answer, species) {
  if (typeof answer !== 'string' || !answer.trim()) return false;
  const a = answer.toLowerCase();
  const names = SPECIES_NAMES[species] || [species];
  return names.some((n) => new RegExp(`(^|[^a-z])${escapeRe(n.toLowerCase())}([^a-z]|$)`).test(a));
}

// A preference as written by a reader ("A", "b", "=", "none") to 'A', 'B' or 'tie'.
function side(pref) {
  const p = String(pref ?? '').trim().toUpperCase();
  if (p === 'A' || p === 'B') return p;
  return p ? 'tie' : null;
}

// One reader's answers unblinded against the key: per species the Sylva and ez-tree scores,
// which one was preferred ('sylva', 'ez-tree', 'tie' or null when unanswered), and the
// recognition answer, whether it is right and its confidence.
// answers: { reader, pairs: { PAIR: { A, B, prefer } }, recognition: { IMAGE: { species, confidence } } }
// Pair and image keys may be given with or without ".png" / "_front.png".
export function unblind(key, answers) {
  const strip = (k) => k.replace(/(_front|_iso)?\.png$/i, '');
  const pairAns = {};
  for (const [k, v] of Object.entries(answers.pairs || {})) pairAns[strip(k)] = v;
  const recAns = {};
  for (const [k, v] of Object.entries(answers.recognition || {})) recAns[strip(k)] = v;
  const rows = {};
  const problems = [];
  for (const p of key.pairs) {
    const a = pairAns[p.pair] || {};
    if (!pairAns[p.pair]) problems.push(`no answer for ${p.pair}`);
    const sylvaSide = p.A === 'sylva' ? 'A' : 'B';
    const ezSide = sylvaSide === 'A' ? 'B' : 'A';
    const pref = side(a.prefer);
    rows[p.species] = {
      species: p.species,
      ez_preset: p.ez_preset,
      sylva_score: num(a[sylvaSide]),
      ez_score: num(a[ezSide]),
      preferred: pref === null ? null : pref === 'tie' ? 'tie' : pref === sylvaSide ? 'sylva' : 'ez-tree',
    };
  }
  for (const r of key.recognition) {
    const a = recAns[r.image];
    if (!a) problems.push(`no answer for ${r.image}`);
    const row = rows[r.species] || (rows[r.species] = { species: r.species });
    row.image = r.image;
    row.named = a ? a.species ?? null : null;
    row.recognised = a ? recognises(a.species, r.species) : false;
    row.confidence = a ? num(a.confidence) : null;
  }
  const list = Object.values(rows).sort((x, y) => x.species.localeCompare(y.species));
  const paired = list.filter((r) => 'sylva_score' in r);
  const summary = {
    reader: answers.reader || 'reader',
    pairs: paired.length,
    sylva_median: median(paired.map((r) => r.sylva_score)),
    ez_median: median(paired.map((r) => r.ez_score)),
    sylva_preferred: paired.filter((r) => r.preferred === 'sylva').length,
    ez_preferred: paired.filter((r) => r.preferred === 'ez-tree').length,
    ties: paired.filter((r) => r.preferred === 'tie').length,
    images: key.recognition.length,
    recognised: list.filter((r) => r.recognised).length,
    recognised_confident: list.filter((r) => r.recognised && r.confidence >= 4).length,
    confidence_median: median(list.map((r) => r.confidence)),
  };
  // Issue 23's goals for this reader.
  summary.goal_preferred_every_pair = paired.length > 0 && summary.sylva_preferred === paired.length;
  summary.goal_median_7 = summary.sylva_median !== null && summary.sylva_median >= 7;
  summary.goal_recognition = summary.images > 0 && summary.recognised_confident === summary.images;
  return { rows: list, summary, problems };
}

function num(x) {
  const n = typeof x === 'string' ? Number(x) : x;
  return typeof n === 'number' && Number.isFinite(n) ? n : null;
}

// The unblinded results of every reader as markdown: one table per reader, then a summary with
// each reader's medians and the goals.
export function markdown(key, results) {
  const fmt = (x) => (x === null || x === undefined ? '–' : String(x));
  const yes = (b) => (b ? 'yes' : 'no');
  const out = [];
  for (const { rows, summary, problems } of results) {
    out.push(`### Reader: ${summary.reader}`, '');
    out.push('| species | ez-tree preset | Sylva score | ez-tree score | preferred | named as | recognised | confidence |');
    out.push('| --- | --- | ---: | ---: | --- | --- | --- | ---: |');
    for (const r of rows) {
      out.push(`| ${r.species} | ${fmt(r.ez_preset)} | ${fmt(r.sylva_score)} | ${fmt(r.ez_score)} | ${fmt(r.preferred)} | ${fmt(r.named)} | ${'image' in r ? yes(r.recognised) : '–'} | ${fmt(r.confidence)} |`);
    }
    out.push(`| **median** | | **${fmt(summary.sylva_median)}** | **${fmt(summary.ez_median)}** | Sylva ${summary.sylva_preferred} / ez-tree ${summary.ez_preferred} / tie ${summary.ties} | | ${summary.recognised} of ${summary.images} | **${fmt(summary.confidence_median)}** |`);
    if (problems.length) out.push('', `Missing answers: ${problems.join('; ')}.`);
    out.push('');
  }
  out.push('### Summary', '');
  out.push('| reader | Sylva median | ez-tree median | Sylva preferred | recognised (confidence ≥ 4) | confidence median | preferred in every pair | median ≥ 7 | every species named with confidence ≥ 4 |');
  out.push('| --- | ---: | ---: | ---: | ---: | ---: | --- | --- | --- |');
  for (const { summary: s } of results) {
    out.push(`| ${s.reader} | ${fmt(s.sylva_median)} | ${fmt(s.ez_median)} | ${s.sylva_preferred} of ${s.pairs} | ${s.recognised_confident} of ${s.images} | ${fmt(s.confidence_median)} | ${yes(s.goal_preferred_every_pair)} | ${yes(s.goal_median_7)} | ${yes(s.goal_recognition)} |`);
  }
  out.push('', `Key seed ${key.seed}; ${key.pairs.length} pairs, ${key.recognition.length} recognition images.`);
  return out.join('\n') + '\n';
}
