// The .glb files `radiosity solve --export` writes, through the Khronos glTF validator (the
// gltf-validator npm package): the lightmap atlas export, the vertex-colour export and the
// textured one. Fails on any error the validator reports; its warnings and infos are printed.
// Usage: node validate_exports.mjs BINARY WEB_DIR OFFICE_SCENE OUT_DIR   (the .glb files go to OUT_DIR)
import { execFileSync } from 'node:child_process';
import { mkdirSync, readFileSync } from 'node:fs';
import { createRequire } from 'node:module';
import path from 'node:path';

const [binary, webDir, office, outDir] = process.argv.slice(2);
const require = createRequire(path.resolve(webDir, 'package.json'));
const validator = require('gltf-validator');
mkdirSync(outDir, { recursive: true });

const exports = [
  ['cornell_lightmap.glb', ['cornell', '--method', 'patch', '--patches', '600', '--lightmap', '256']],
  ['cornell_voxel_lightmap.glb', ['cornell', '--method', 'voxel', '--voxels', '20000',
    '--sphere-radius', '6', '--lightmap', '256']],
  ['cornell_colors.glb', ['cornell', '--method', 'patch', '--patches', '600']],
  ['office_textured.glb', [office, '--method', 'patch', '--patches', '2000']],
  ['office_lightmap.glb', [office, '--method', 'patch', '--patches', '2000',
    '--lightmap', '1024']],
];

let failed = false;
for (const [name, args] of exports) {
  const file = path.join(outDir, name);
  execFileSync(binary, ['solve', ...args, '--cache-dir', 'none', '--quiet', '--export', file],
    { stdio: ['ignore', 'inherit', 'inherit'] });
  const report = await validator.validateBytes(new Uint8Array(readFileSync(file)), { maxIssues: 100 });
  const { numErrors, numWarnings, numInfos } = report.issues;
  console.log(`${name}: ${numErrors} errors, ${numWarnings} warnings, ${numInfos} infos`);
  for (const m of report.issues.messages)
    console.log(`  ${['error', 'warning', 'info', 'hint'][m.severity]} ${m.code} ${m.pointer ?? ''}: ${m.message}`);
  if (numErrors > 0) failed = true;
}
process.exitCode = failed ? 1 : 0;
