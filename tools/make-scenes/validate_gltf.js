#!/usr/bin/env node
// Validates glTF files with the Khronos glTF Validator (npm package gltf-validator).
// usage: NODE_PATH=DIR/node_modules node validate_gltf.js FILE.gltf...
// Exit 0 only if every file has no errors and no warnings; prints each file's counts.
'use strict';
const fs = require('fs');
const path = require('path');
let validator;
try {
  validator = require('gltf-validator');
} catch (e) {
  console.error('validate_gltf: the gltf-validator npm package is not installed (scripts/setup.sh installs it)');
  process.exit(2);
}

async function validate(file) {
  const bytes = new Uint8Array(fs.readFileSync(file));
  const report = await validator.validateBytes(bytes, {
    uri: path.basename(file),
    maxIssues: 100,
    externalResourceFunction: (uri) => new Promise((resolve, reject) => {
      const full = path.resolve(path.dirname(file), decodeURIComponent(uri));
      fs.readFile(full, (err, data) => (err ? reject(err.toString()) : resolve(new Uint8Array(data))));
    }),
  });
  const i = report.issues;
  console.log(`${file}: ${i.numErrors} errors, ${i.numWarnings} warnings, ${i.numInfos} infos, ${i.numHints} hints`);
  for (const m of i.messages) {
    if (m.severity <= 1) console.log(`  [${m.severity === 0 ? 'error' : 'warning'}] ${m.code} ${m.pointer || ''}: ${m.message}`);
  }
  return i.numErrors === 0 && i.numWarnings === 0;
}

(async () => {
  const files = process.argv.slice(2);
  if (!files.length) {
    console.error('usage: validate_gltf.js FILE.gltf...');
    process.exit(2);
  }
  let ok = true;
  for (const f of files) {
    try {
      ok = (await validate(f)) && ok;
    } catch (e) {
      console.log(`${f}: cannot validate: ${e}`);
      ok = false;
    }
  }
  process.exit(ok ? 0 : 1);
})();
