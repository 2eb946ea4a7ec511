// An independent LAS reader for the tests: copc.js's LAS code (npm package
// "copc", not hba's) reads a LAS file; a binary PCD written by hba gives the
// same points as reference. Prints "ok <count>" when the count matches and
// every point agrees to 1 mm (LAS stores millimetres), else what differs.
// Usage: node read_las_copc.mjs MAP.las MAP.pcd
import {readFileSync} from 'node:fs';
import {Las} from 'copc';

function readLas(path) {
  const file = new Uint8Array(readFileSync(path));
  const header = Las.Header.parse(file.subarray(0, Las.Constants.minHeaderLength));
  const view = Las.View.create(file.subarray(header.pointDataOffset), header);
  const get = ['X', 'Y', 'Z'].map((name) => view.getter(name));
  const points = [];
  for (let i = 0; i < view.pointCount; ++i) points.push(get.map((g) => g(i)));
  return {count: header.pointCount, points};
}

// A binary PCD with float x y z first (what hba map writes).
function readPcd(path) {
  const bytes = readFileSync(path);
  const end = bytes.indexOf('DATA binary\n') + 'DATA binary\n'.length;
  const header = bytes.subarray(0, end).toString();
  const sizes = header.match(/^SIZE (.*)$/m)[1].split(' ').map(Number);
  const fields = header.match(/^FIELDS (.*)$/m)[1].split(' ');
  if (fields[0] !== 'x' || fields[1] !== 'y' || fields[2] !== 'z') throw new Error('PCD: x y z not first');
  const count = Number(header.match(/^POINTS (\d+)$/m)[1]);
  const stride = sizes.reduce((a, b) => a + b, 0);
  const points = [];
  for (let i = 0; i < count; ++i) {
    const at = end + i * stride;
    points.push([bytes.readFloatLE(at), bytes.readFloatLE(at + 4), bytes.readFloatLE(at + 8)]);
  }
  return points;
}

const las = readLas(process.argv[2]);
const pcd = readPcd(process.argv[3]);
if (las.count !== pcd.length || las.points.length !== pcd.length) {
  console.log(`count: LAS header ${las.count}, parsed ${las.points.length}, PCD ${pcd.length}`);
  process.exit(1);
}
let worst = 0;
for (let i = 0; i < pcd.length; ++i) {
  for (let k = 0; k < 3; ++k) worst = Math.max(worst, Math.abs(las.points[i][k] - pcd[i][k]));
}
if (worst > 1e-3) {
  console.log(`largest coordinate difference ${worst} m`);
  process.exit(1);
}
console.log(`ok ${pcd.length} points, largest difference ${worst.toExponential(2)} m`);
