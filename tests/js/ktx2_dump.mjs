// Prints what ktx-parse (an independent KTX2 reader) finds in a file, as one
// JSON object: header fields, the data format descriptor, key/value data
// (values as text, without the trailing NUL) and, per level, byte offset,
// lengths and the bytes as hex. Used by tests/io/ktx2_external_test.cpp.
//   node ktx2_dump.mjs FILE
import { readFileSync } from 'node:fs';
import { read } from 'ktx-parse';

const bytes = new Uint8Array(readFileSync(process.argv[2]));
const c = read(bytes);
const hex = (a) => Buffer.from(a.buffer, a.byteOffset, a.byteLength).toString('hex');
const text = (v) => {
  const s = typeof v === 'string' ? v : new TextDecoder().decode(v);
  return s.endsWith('\0') ? s.slice(0, -1) : s;
};
const dfd = c.dataFormatDescriptor[0];
const out = {
  vkFormat: c.vkFormat,
  typeSize: c.typeSize,
  pixelWidth: c.pixelWidth,
  pixelHeight: c.pixelHeight,
  pixelDepth: c.pixelDepth,
  layerCount: c.layerCount,
  faceCount: c.faceCount,
  levelCount: c.levelCount,
  supercompressionScheme: c.supercompressionScheme,
  dfd: {
    vendorId: dfd.vendorId,
    descriptorType: dfd.descriptorType,
    versionNumber: dfd.versionNumber,
    colorModel: dfd.colorModel,
    colorPrimaries: dfd.colorPrimaries,
    transferFunction: dfd.transferFunction,
    flags: dfd.flags,
    texelBlockDimension: dfd.texelBlockDimension,
    bytesPlane: dfd.bytesPlane,
    samples: dfd.samples.map((s) => ({
      bitOffset: s.bitOffset,
      bitLength: s.bitLength,
      channelType: s.channelType,
      samplePosition: s.samplePosition,
      sampleLower: s.sampleLower,
      sampleUpper: s.sampleUpper,
    })),
  },
  keyValue: Object.fromEntries(Object.entries(c.keyValue).map(([k, v]) => [k, text(v)])),
  levels: c.levels.map((l) => ({
    byteOffset: l.levelData.byteOffset - bytes.byteOffset,
    byteLength: l.levelData.byteLength,
    uncompressedByteLength: l.uncompressedByteLength,
    hex: hex(l.levelData),
  })),
  fileLength: bytes.byteLength,
};
process.stdout.write(JSON.stringify(out) + '\n');
