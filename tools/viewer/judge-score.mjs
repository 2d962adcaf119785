#!/usr/bin/env node
// Unblinds readers' answers from the blind-judging kit (tools/viewer/blind-pairs.mjs) and prints
// the results as markdown for docs/JUDGING.md: per reader and species the Sylva and ez-tree
// scores, the preferred tree, the recognition answer and its confidence, and each reader's
// medians against issue 23's goals.
//
//   node tools/viewer/judge-score.mjs KEY.json ANSWERS.json [ANSWERS2.json ...] [--json]
//
// ANSWERS is a filled-in copy of judge/answers-template.json:
//   { "reader": "...", "pairs": { "pair_01_oak": { "A": 6, "B": 4, "prefer": "A" }, ... },
//     "recognition": { "tree_01": { "species": "spruce", "confidence": 4 }, ... } }
// --json prints the unblinded rows and summaries as JSON instead.
import fs from 'node:fs';
import path from 'node:path';
import { unblind, markdown } from './lib/blind.js';

const args = process.argv.slice(2);
const asJson = args.includes('--json');
const files = args.filter((a) => a !== '--json');
if (files.length < 2 || files.some((f) => f.startsWith('--'))) {
  process.stderr.write('usage: node tools/viewer/judge-score.mjs KEY.json ANSWERS.json [ANSWERS2.json ...] [--json]\n');
  process.exit(2);
}
const read = (f) => {
  try {
    return JSON.parse(fs.readFileSync(f, 'utf8'));
  } catch (e) {
    process.stderr.write(`judge-score: cannot read ${f}: ${e.message}\n`);
    process.exit(2);
  }
};
const key = read(files[0]);
if (!Array.isArray(key.pairs) || !Array.isArray(key.recognition)) {
  process.stderr.write(`judge-score: ${files[0]} is not a key.json from blind-pairs (no pairs/recognition)\n`);
  process.exit(2);
}
const results = files.slice(1).map((f) => {
  const answers = read(f);
  if (!answers.reader) answers.reader = path.basename(f, '.json');
  return unblind(key, answers);
});
for (const r of results) for (const p of r.problems) process.stderr.write(`judge-score: ${r.summary.reader}: ${p}\n`);
process.stdout.write(asJson ? JSON.stringify(results, null, 2) + '\n' : markdown(key, results));
