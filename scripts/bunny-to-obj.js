// SPDX-License-Identifier: MIT
// Converts the npm package `bunny` (the Stanford bunny as JavaScript arrays: positions, an
// array of [x, y, z], and cells, an array of [i, j, k] 0-based triangles) to a Wavefront OBJ
// file, for ttd's mesh benchmark. Called by scripts/fetch-bunny.sh.
// The mesh: Stanford 3D Scanning Repository (Greg Turk and Marc Levoy, 1994), packaged by
// Mikola Lysenko as npm `bunny` 1.0.1, licence "Public Domain" in its package.json.
// Usage: node scripts/bunny-to-obj.js PACKAGE_DIR OUTPUT.obj
'use strict';
const fs = require('fs');
const path = require('path');

function fail(msg) {
    process.stderr.write('bunny-to-obj: ' + msg + '\n');
    process.exit(1);
}

if (process.argv.length !== 4)
    fail('usage: node bunny-to-obj.js PACKAGE_DIR OUTPUT.obj');
const pkgDir = path.resolve(process.argv[2]);
let bunny;
try {
    bunny = require(pkgDir);
} catch (e) {
    fail('cannot load the package at ' + pkgDir + ': ' + e.message);
}
const pos = bunny.positions, cells = bunny.cells;
if (!Array.isArray(pos) || !Array.isArray(cells) || pos.length === 0 || cells.length === 0)
    fail('the package has no positions/cells arrays');

const lines = [
    '# The Stanford bunny (Stanford 3D Scanning Repository, Turk and Levoy 1994),',
    '# from the npm package bunny 1.0.1 (Mikola Lysenko; licence: Public Domain).',
    '# ' + pos.length + ' vertices, ' + cells.length + ' triangles; written by ttd scripts/bunny-to-obj.js',
];
for (const p of pos) {
    if (!Array.isArray(p) || p.length !== 3 || !p.every(Number.isFinite))
        fail('a position is not three finite numbers: ' + JSON.stringify(p));
    lines.push('v ' + p.map(String).join(' ')); // String(x): the shortest text that reads back as x
}
for (const c of cells) {
    if (!Array.isArray(c) || c.length !== 3 || !c.every(i => Number.isInteger(i) && i >= 0 && i < pos.length))
        fail('a cell is not three vertex indices: ' + JSON.stringify(c));
    lines.push('f ' + c.map(i => String(i + 1)).join(' '));
}
fs.writeFileSync(process.argv[3], lines.join('\n') + '\n');
process.stderr.write('bunny-to-obj: ' + pos.length + ' vertices, ' + cells.length + ' triangles\n');
