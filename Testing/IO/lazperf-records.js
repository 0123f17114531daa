// Decodes a LAZ file with laz-perf (the npm package: LASzip's format in an independent C++
// implementation, compiled to WebAssembly) and writes its point records, uncompressed, to a file;
// prints the decoding time without Node's start-up and the module's loading.
//   node lazperf-records.js LAZPERF_PACKAGE_DIR INPUT.laz OUTPUT.records
'use strict';
const fs = require('fs');
const path = require('path');

async function main() {
  const [packageDir, input, output] = process.argv.slice(2);
  const { createLazPerf } = require(path.resolve(packageDir, 'lib', 'node', 'index.js'));
  const lazPerf = await createLazPerf();
  const file = fs.readFileSync(input);
  const filePointer = lazPerf._malloc(file.length);
  lazPerf.HEAPU8.set(file, filePointer);
  const reader = new lazPerf.LASZip();
  const start = process.hrtime.bigint();
  reader.open(filePointer, file.length);
  const count = reader.getCount();
  const length = reader.getPointLength();
  // Each point straight into its place in WebAssembly's memory: no copy per point.
  const recordsPointer = lazPerf._malloc(count * length);
  for (let i = 0; i < count; ++i) {
    reader.getPoint(recordsPointer + i * length);
  }
  const seconds = Number(process.hrtime.bigint() - start) / 1e9;
  const records = Buffer.from(lazPerf.HEAPU8.subarray(recordsPointer, recordsPointer + count * length));
  reader.delete();
  lazPerf._free(recordsPointer);
  lazPerf._free(filePointer);
  fs.writeFileSync(output, records);
  console.log(`laz-perf: ${count} points of ${length} bytes in ${seconds.toFixed(4)} s ` +
    `(${(count / seconds / 1e6).toFixed(2)} million points/s)`);
}

main().catch((error) => {
  console.error(`laz-perf: ${error.message || error}`);
  process.exit(1);
});
