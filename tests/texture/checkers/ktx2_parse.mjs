// Reads each KTX 2.0 file named on the command line with ktx-parse (npm), an independent parser,
// and prints one JSON line per file: header, data format descriptor, key/value data, and where
// each level's bytes are (offset and length in the file) with its uncompressed length.
// Usage: node ktx2_parse.mjs NPM_DIR FILE.ktx2...
import fs from 'fs';
import path from 'path';
import { pathToFileURL } from 'url';

const [npm, ...files] = process.argv.slice(2);
const ktx = await import(pathToFileURL(path.join(npm, 'node_modules', 'ktx-parse', 'dist', 'index.mjs')).href);
for (const file of files) {
  const bytes = new Uint8Array(fs.readFileSync(file));
  const c = ktx.read(bytes);
  const dfd = c.dataFormatDescriptor[0];
  const keyValue = {};
  for (const [k, v] of Object.entries(c.keyValue)) keyValue[k] = typeof v === 'string' ? v : Array.from(v);
  console.log(JSON.stringify({
    file, vkFormat: c.vkFormat, typeSize: c.typeSize, pixelWidth: c.pixelWidth, pixelHeight: c.pixelHeight,
    pixelDepth: c.pixelDepth, layerCount: c.layerCount, faceCount: c.faceCount, levelCount: c.levelCount,
    supercompressionScheme: c.supercompressionScheme,
    dfd: {
      vendorId: dfd.vendorId, descriptorType: dfd.descriptorType, versionNumber: dfd.versionNumber,
      colorModel: dfd.colorModel, colorPrimaries: dfd.colorPrimaries, transferFunction: dfd.transferFunction,
      flags: dfd.flags, texelBlockDimension: Array.from(dfd.texelBlockDimension), bytesPlane: Array.from(dfd.bytesPlane),
      samples: dfd.samples.map((s) => ({ bitOffset: s.bitOffset, bitLength: s.bitLength, channelType: s.channelType,
        sampleLower: s.sampleLower, sampleUpper: s.sampleUpper })),
    },
    keyValue,
    levels: c.levels.map((l) => ({ offset: l.levelData.byteOffset - bytes.byteOffset, length: l.levelData.byteLength,
      uncompressedByteLength: l.uncompressedByteLength })),
  }));
}
