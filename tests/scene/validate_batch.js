#!/usr/bin/env node
// Validates many glTF files in one process with the Khronos glTF Validator and prints one
// JSON line per file: {"file", "errors": [codes], "warnings": [codes]} (validator_diff.py),
// or {"file", "crash": message} when the validator throws on the file.
'use strict';
const fs = require('fs');
const validator = require('gltf-validator');

(async () => {
  for (const file of process.argv.slice(2)) {
    let report;
    try {
      report = await validator.validateBytes(new Uint8Array(fs.readFileSync(file)), {
        uri: file,
        maxIssues: 1000,
        externalResourceFunction: () => Promise.reject(new Error('external resources are not used')),
      });
    } catch (e) { // the validator itself failed on this file: no verdict
      console.log(JSON.stringify({file, crash: String(e).split('\n')[0]}));
      continue;
    }
    const errors = [], warnings = [];
    for (const m of report.issues.messages) {
      if (m.severity === 0) errors.push(`${m.code} ${m.pointer || ''}`);
      else if (m.severity === 1) warnings.push(`${m.code} ${m.pointer || ''}`);
    }
    console.log(JSON.stringify({file, errors, warnings}));
  }
})().catch((e) => { console.error(e); process.exit(2); });
