// Loads a KTX2 cube map with three.js's KTX2Loader (an independent reader)
// under node and prints what it built, as one JSON object: the texture's
// class, format and type, and per mip level its size and, for each of the
// six faces, the first texel's RGBA as floats. Used by
// tests/pipeline/sky_environment_test.cpp.
//   node ktx2_three_cube.mjs FILE
import { readFileSync } from 'node:fs';
import { DataUtils } from 'three';
import { KTX2Loader } from 'three/examples/jsm/loaders/KTX2Loader.js';

const file = readFileSync(process.argv[2]);
const buffer = file.buffer.slice(file.byteOffset, file.byteOffset + file.byteLength);
// Under node there is no WebGL: the loader is told of a renderer without
// compressed-texture extensions, which a float file does not need anyway.
const noExtensions = { extensions: { has: () => false } };
const loader = new KTX2Loader().detectSupport(noExtensions);
const texture = await new Promise((resolve, reject) => loader.parse(buffer, resolve, reject));
// three.js keeps an uncompressed KTX2 cube's faces one after the other in
// each level's data (CompressedCubeTexture is for block formats only).
const levels = texture.mipmaps.map((m) => {
  const perFace = m.data.length / 6;
  const faces = [];
  for (let f = 0; f < 6; ++f) {
    const texel = Array.from(m.data.subarray(f * perFace, f * perFace + 4));
    faces.push(texture.type === 1016 ? texel.map((h) => DataUtils.fromHalfFloat(h)) : texel);
  }
  return { width: m.width, height: m.height, values: m.data.length, faces };
});
const out = {
  className: texture.constructor.name,
  isCubeTexture: texture.isCubeTexture === true,
  format: texture.format,
  type: texture.type,
  levels,
};
process.stdout.write(JSON.stringify(out) + '\n');
