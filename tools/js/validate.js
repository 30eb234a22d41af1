// The Khronos glTF validator (npm gltf-validator, pinned in package.json) on .glb files:
// prints one JSON line per file with its counts and messages (tests/export_gltf.rs reads them).
//
//   node validate.js FILE.glb ...
'use strict';
const fs = require('fs');
const validator = require('gltf-validator');

async function main() {
  for (const file of process.argv.slice(2)) {
    const bytes = new Uint8Array(fs.readFileSync(file));
    const r = await validator.validateBytes(bytes, { maxIssues: 100 });
    const i = r.issues;
    process.stdout.write(
      JSON.stringify({
        file,
        errors: i.numErrors,
        warnings: i.numWarnings,
        infos: i.numInfos,
        messages: i.messages.map((m) => `${m.severity} ${m.code} ${m.pointer || ''}: ${m.message}`),
      }) + '\n'
    );
  }
}

main().catch((e) => {
  console.error(String(e));
  process.exit(1);
});
