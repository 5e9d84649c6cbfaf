// SPDX-License-Identifier: MIT
// Converts a mesh module of an npm package (the stackgl form: `positions`, an array of [x, y, z],
// and `cells`, an array of [i, j, k] 0-based triangles) to a Wavefront OBJ file, for
// `ttd bench points`. Called by scripts/fetch-open-models.sh.
// Usage: node scripts/npm-mesh-to-obj.js MODULE OUTPUT.obj "WHAT (a comment line)"
'use strict';
const fs = require('fs');
const path = require('path');

function fail(msg) {
    process.stderr.write('npm-mesh-to-obj: ' + msg + '\n');
    process.exit(1);
}

if (process.argv.length !== 5)
    fail('usage: node npm-mesh-to-obj.js MODULE OUTPUT.obj WHAT');
const mod = path.resolve(process.argv[2]);
let mesh;
try {
    mesh = require(mod);
} catch (e) {
    fail('cannot load ' + mod + ': ' + e.message);
}
const pos = mesh.positions, cells = mesh.cells;
if (!pos || !cells || pos.length === 0 || cells.length === 0)
    fail('the module has no positions/cells arrays');

const lines = ['# ' + process.argv[4],
               '# ' + pos.length + ' vertices, ' + cells.length + ' triangles; written by ttd scripts/npm-mesh-to-obj.js'];
for (const p of pos) {
    if (p.length !== 3 || !Array.from(p).every(Number.isFinite))
        fail('a position is not three finite numbers: ' + JSON.stringify(p));
    lines.push('v ' + Array.from(p).map(String).join(' ')); // String(x): the shortest text that reads back as x
}
for (const c of cells) {
    if (c.length !== 3 || !Array.from(c).every(i => Number.isInteger(i) && i >= 0 && i < pos.length))
        fail('a cell is not three vertex indices: ' + JSON.stringify(c));
    lines.push('f ' + Array.from(c).map(i => String(i + 1)).join(' '));
}
fs.writeFileSync(process.argv[3], lines.join('\n') + '\n');
process.stderr.write('npm-mesh-to-obj: ' + pos.length + ' vertices, ' + cells.length + ' triangles\n');
