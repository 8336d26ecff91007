#!/usr/bin/env node
// The Khronos glTF Validator on each wrapper (samples/assets/<Name>/<Name>.lit.gltf, and
// <Name>.punctual.gltf where lights.json lists punctual lights for the asset) and on the
// asset it wraps (<Name>.gltf): a wrapper must add no error and no warning to what the
// published asset already has (some published assets have a few, e.g. ClearCoatTest's
// MESH_PRIMITIVE_NO_TANGENT_SPACE). Infos and hints are not compared: the added
// EXT_lights_area is an info (an extension the validator does not know); KHR_lights_punctual
// is one it knows, so the punctual lights themselves are checked.
// usage: NODE_PATH=DIR/node_modules node validate_wrappers.js ASSETS_DIR NAME...
'use strict';
const fs = require('fs');
const path = require('path');
let validator;
try {
  validator = require('gltf-validator');
} catch (e) {
  console.error('validate_wrappers: the gltf-validator npm package is not installed (scripts/setup.sh installs it)');
  process.exit(2);
}

async function problems(file) {
  const bytes = new Uint8Array(fs.readFileSync(file));
  const report = await validator.validateBytes(bytes, {
    uri: path.basename(file),
    maxIssues: 1000,
    externalResourceFunction: (uri) => new Promise((resolve, reject) => {
      const full = path.resolve(path.dirname(file), decodeURIComponent(uri));
      fs.readFile(full, (err, data) => (err ? reject(err.toString()) : resolve(new Uint8Array(data))));
    }),
  });
  return report.issues.messages
    .filter((m) => m.severity <= 1)
    .map((m) => `[${m.severity === 0 ? 'error' : 'warning'}] ${m.code} ${m.pointer || ''}`);
}

(async () => {
  const [dir, ...names] = process.argv.slice(2);
  if (!dir || !names.length) {
    console.error('usage: validate_wrappers.js ASSETS_DIR NAME...');
    process.exit(2);
  }
  const spec = JSON.parse(fs.readFileSync(path.join(dir, 'lights.json'), 'utf8')).assets;
  let ok = true;
  for (const name of names) {
    const wrappers = [name + '.lit.gltf'];
    if (spec[name] && spec[name].punctual) wrappers.push(name + '.punctual.gltf');
    try {
      const published = new Set(await problems(path.join(dir, name, name + '.gltf')));
      for (const wrapper of wrappers) {
        const found = await problems(path.join(dir, name, wrapper));
        const added = found.filter((p) => !published.has(p));
        console.log(`${wrapper}: published ${published.size} errors+warnings, wrapper adds ${added.length}`);
        for (const p of added) console.log('  ' + p);
        ok = ok && added.length === 0;
      }
    } catch (e) {
      console.log(`${name}: cannot validate: ${e}`);
      ok = false;
    }
  }
  process.exit(ok ? 0 : 1);
})();
