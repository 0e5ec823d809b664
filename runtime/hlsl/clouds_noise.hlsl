// Decoding skybake's cloud noise textures (docs/runtime.md "Cloud noise").
// The names match their C++ counterparts where there are some.
//
//   noise_shape   3D, RGBA: R Perlin-Worley, G B A inverted-Worley fBm
//                 (noise/noise_volume.hpp). Values in [0, 1], stored as is:
//                 an unorm8 texel is the value, no remap.
//   noise_detail  3D, RGB: inverted-Worley fBm at rising frequencies.
//   pack "dilate" / "sum": one channel R, already packed with
//                 pack_single_channel below.
//   curl          2D, RGB: signed vectors stored c = 0.5 + 0.5 v / scale;
//                 curl_value_from_texel undoes that with the manifest's
//                 curl_scale_rg and curl_scale_b.
//
// Every texture is linear (not sRGB), tiles on every axis: sample it with
// WRAP addressing and trilinear filtering; texture coordinates are in tiles
// (uvw = position / tile size).
#ifndef SKYBAKE_CLOUDS_NOISE_HLSL
#define SKYBAKE_CLOUDS_NOISE_HLSL

// The variants of Perlin-Worley (noise/perlin_worley.hpp PerlinWorleyRemap);
// a bake records the one it used as the metadata "remap".
#define SKYBAKE_REMAP_WORLEY_NEW_MIN 0
#define SKYBAKE_REMAP_WORLEY_OLD_MIN 1
#define SKYBAKE_REMAP_DILATE 2

// pack_single_channel modes (noise/noise_volume.hpp PackMode).
#define SKYBAKE_PACK_DILATE_BASE 0
#define SKYBAKE_PACK_WEIGHTED_SUM 1

// Perlin-Worley from a Perlin fBm value (about [-1, 1]) and an inverted
// Worley fBm value in [0, 1]; result in [0, 1]. noise/perlin_worley.hpp.
float perlin_worley(float perlin_fbm, float worley_fbm, int remap) {
  float p = clamp(perlin_fbm * 0.5 + 0.5, 0.0, 1.0);
  float w = clamp(worley_fbm, 0.0, 1.0);
  if (remap == SKYBAKE_REMAP_WORLEY_OLD_MIN)
    return w >= 1.0 ? 0.0 : clamp((p - w) / (1.0 - w), 0.0, 1.0);
  if (remap == SKYBAKE_REMAP_DILATE) return min((p + 1.0 - w) / (2.0 - w), 1.0);
  return min(w + p * (1.0 - w), 1.0);
}

// Weight of octave `octave` of a Worley fBm of `octaves` octaves: 0.625,
// 0.25, 0.125 for three (Schneider), halving after that, the first octave
// taking what the others leave so that the weights sum to 1 (noise/fbm.hpp).
float worley_fbm_weight(int octave, int octaves) {
  // The tail: 0.5^(o + 1) for o >= 1.
  if (octave > 0) return 1.0 / float(1 << (octave + 1));
  float rest = 0.0;
  for (int o = 1; o < octaves; ++o) rest += 1.0 / float(1 << (o + 1));
  return 1.0 - rest;
}

// The weights the packed products use (GPU Pro 7 sec. 4.3.4 low_freq_FBM and
// high_freq_FBM), per input channel R G B A.
float4 shape_pack_weights() { return float4(0.0, 0.625, 0.25, 0.125); }
float4 detail_pack_weights() { return float4(0.625, 0.25, 0.125, 0.0); }

// One texel of noise_shape or noise_detail packed into one value, as the
// packed products hold it (noise/noise_volume.hpp pack_single_channel):
//   dilate_base:  saturate((R + 1 - fbm) / (2 - fbm)), fbm = w.g G + w.b B + w.a A
//                 (the base_cloud of the GPU Pro 7 sampler);
//   weighted_sum: saturate(dot(w, texel)).
// Channels the texture lacks must be 0 in `texel` (a sample of an R texture
// returns 1 in A: pass float4(t.rgb, 0) for a 3-channel detail).
float pack_single_channel(float4 texel, int mode, float4 weights) {
  if (mode == SKYBAKE_PACK_DILATE_BASE) {
    float fbm = dot(weights.yzw, texel.yzw);
    return clamp((texel.x + 1.0 - fbm) / (2.0 - fbm), 0.0, 1.0);
  }
  return clamp(dot(weights, texel), 0.0, 1.0);
}

// The base cloud shape from an unpacked noise_shape volume at uvw (tiles).
float lookup_base_cloud(Texture3D<float4> noise_shape, SamplerState wrap_linear, float3 uvw,
                        float lod) {
  return pack_single_channel(noise_shape.SampleLevel(wrap_linear, uvw, lod),
                             SKYBAKE_PACK_DILATE_BASE,
                             shape_pack_weights());
}

// The detail fBm from an unpacked noise_detail volume at uvw (tiles).
float lookup_detail_fbm(Texture3D<float4> noise_detail, SamplerState wrap_linear, float3 uvw,
                        float lod) {
  float3 t = noise_detail.SampleLevel(wrap_linear, uvw, lod).rgb;
  return pack_single_channel(float4(t, 0.0), SKYBAKE_PACK_WEIGHTED_SUM, detail_pack_weights());
}

// One curl component from its texel value c in [0, 1] and the scale the
// manifest records for it ("curl_scale_rg" for R and G, "curl_scale_b" for B):
// v = (2 c - 1) scale, per lattice cell of the base period
// (noise/curl_texture.hpp curl_texel_from_value is the inverse).
float curl_value_from_texel(float c, float scale) { return (2.0 * c - 1.0) * scale; }
float curl_texel_from_value(float v, float scale) {
  float k = scale > 0.0 ? 0.5 / scale : 0.0;
  return clamp(0.5 + v * k, 0.0, 1.0);
}

// The 2D curl (R, G) and the 3D curl's z (B) of a curl texel.
float3 curl_from_texel(float3 c, float curl_scale_rg, float curl_scale_b) {
  return float3(curl_value_from_texel(c.x, curl_scale_rg),
                curl_value_from_texel(c.y, curl_scale_rg),
              curl_value_from_texel(c.z, curl_scale_b));
}

// The curl vector at uv (tiles): filtering the encoded texels and decoding
// is the same as filtering the vectors (the decode is affine).
float3 lookup_curl(Texture2D<float4> curl, SamplerState wrap_linear, float2 uv, float lod,
                   float curl_scale_rg, float curl_scale_b) {
  return curl_from_texel(curl.SampleLevel(wrap_linear, uv, lod).rgb, curl_scale_rg, curl_scale_b);
}

#endif  // SKYBAKE_CLOUDS_NOISE_HLSL
