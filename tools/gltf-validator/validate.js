// Validates GLB files with the Khronos glTF validator: prints one report line per file (and
// every issue of files with errors), exits 1 when any file has errors, 2 on bad usage.
'use strict';
const fs = require('fs');
const validator = require('gltf-validator');

async function main(files) {
  if (files.length === 0) {
    console.error('usage: node validate.js FILE.glb...');
    return 2;
  }
  let failed = 0;
  for (const file of files) {
    const report = await validator.validateBytes(new Uint8Array(fs.readFileSync(file)), {
      uri: file,
      maxIssues: 100,
    });
    const i = report.issues;
    console.log(`${file}: ${i.numErrors} errors, ${i.numWarnings} warnings, ${i.numInfos} infos, ${i.numHints} hints`);
    for (const m of i.messages) {
      if (m.severity <= 1 || i.numErrors > 0) {
        console.log(`  [${m.severity}] ${m.code} ${m.pointer || ''}: ${m.message}`);
      }
    }
    if (i.numErrors > 0) {
      failed += 1;
    }
  }
  console.log(`${files.length - failed} valid, ${failed} with errors`);
  return failed > 0 ? 1 : 0;
}

main(process.argv.slice(2)).then(
  (code) => process.exit(code),
  (e) => {
    console.error(e);
    process.exit(2);
  },
);
