#!/usr/bin/env node
// Runs the Khronos glTF validator on each file given; prints a summary per file and exits 1 when
// any file has errors or warnings (the export tests demand 0 of each).
'use strict';
const fs = require('fs');
const path = require('path');

let validator;
try {
  validator = require(path.join(__dirname, '..', 'tools', 'node_modules', 'gltf-validator'));
} catch (e) {
  console.error('validate-gltf: gltf-validator is not installed; run scripts/install-gltf-validator.sh');
  process.exit(2);
}

async function check(file) {
  const bytes = new Uint8Array(fs.readFileSync(file));
  const report = await validator.validateBytes(bytes, {
    uri: path.basename(file),
    maxIssues: 50,
    externalResourceFunction: (uri) =>
      new Promise((resolve, reject) => {
        fs.readFile(path.join(path.dirname(file), decodeURIComponent(uri)), (err, data) =>
          err ? reject(err.toString()) : resolve(new Uint8Array(data)));
      }),
  });
  const i = report.issues;
  console.log(`${file}: ${i.numErrors} errors, ${i.numWarnings} warnings, ${i.numInfos} infos, ${i.numHints} hints`);
  for (const m of i.messages) {
    if (m.severity <= 1) console.log(`  ${m.severity === 0 ? 'error' : 'warning'} ${m.code} ${m.pointer || ''}: ${m.message}`);
  }
  return i.numErrors === 0 && i.numWarnings === 0;
}

(async () => {
  const files = process.argv.slice(2);
  if (files.length === 0) {
    console.error('usage: validate-gltf.js FILE.glb|FILE.gltf...');
    process.exit(2);
  }
  let ok = true;
  for (const f of files) {
    try {
      ok = (await check(f)) && ok;
    } catch (e) {
      console.log(`${f}: cannot validate: ${e}`);
      ok = false;
    }
  }
  process.exit(ok ? 0 : 1);
})();
