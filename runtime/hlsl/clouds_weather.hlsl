// Decoding skybake's cloud textures (docs/clouds.md, docs/runtime.md
// "Weather map" and after). The names match their C++ counterparts where
// there are some (clouds/weather_map.hpp, cloud_types.hpp, height_profile.hpp).
//
//   weather           2D, tiles. Layout "schneider": R coverage, G
//                     precipitation, B type (0 stratus, 0.5 stratocumulus,
//                     1 cumulus; G = B = 1 cumulonimbus). Layout
//                     "frostbite": R density, G the u of the type's column
//                     in cloud_types.
//   cloud_types       2D, clamp: u = type (type_u_from_index), v = normalized
//                     height h in the layer (row 0 = bottom); R density,
//                     G erosion.
//   height_gradients  2D, 1 texel wide, clamp: v = h; R stratus,
//                     G stratocumulus, B cumulus, A cumulonimbus density.
//   cirrus            2D, tiles: R streaks (along x), G cirrocumulus cells,
//                     B altostratus sheets.
// Every texture is linear (not sRGB), with values in [0, 1].
#ifndef SKYBAKE_CLOUDS_WEATHER_HLSL
#define SKYBAKE_CLOUDS_WEATHER_HLSL

// The weather layouts (metadata "weather_layout").
#define SKYBAKE_WEATHER_SCHNEIDER 0
#define SKYBAKE_WEATHER_FROSTBITE 1

// Coverage never below 0.7 x precipitation (Schneider, GPU Pro 7 4.3.3);
// clouds/weather_map.hpp kRainCoverage.
#define SKYBAKE_RAIN_COVERAGE 0.7

// The rain rule the bake applies on every texel (weather_map.hpp); exposed
// for engines that change coverage or precipitation at run time.
float coverage_with_rain(float coverage, float precipitation) {
  return max(coverage, SKYBAKE_RAIN_COVERAGE * precipitation);
}
float type_with_rain(float type, float precipitation) {
  return (1.0 - precipitation) * type + precipitation;
}

// The fractional type index (0 stratus, 1 stratocumulus, 2 cumulus,
// 3 cumulonimbus) of a type before the rain rule and the precipitation p:
// (1 - p) 2 type + 3 p, exactly 3 where p = 1 (what the Frostbite layout's G
// holds as a u).
float frostbite_type_index(float type, float precipitation) {
  return (1.0 - precipitation) * 2.0 * type + 3.0 * precipitation;
}

// The same index from a Schneider texel, whose B already had the rain rule
// (B = (1 - p) type + p): 2 B + p = (1 - p) 2 type + 3 p.
float type_index_from_schneider(float type_with_rain, float precipitation) {
  return 2.0 * type_with_rain + precipitation;
}

// Texture u of the centre of type `index` (fractional: a blend) among
// `types` columns of cloud_types, and its inverse (cloud_types.hpp).
float type_u_from_index(float index, int types) { return (index + 0.5) / float(types); }
float index_from_type_u(float u, int types) { return u * float(types) - 0.5; }

// Normalized height of the centre of row j of `rows` (row 0 = bottom) and its
// inverse (height_profile.hpp); v = h in cloud_types and height_gradients.
float height_from_row(int j, int rows) { return (float(j) + 0.5) / float(rows); }
float row_from_height(float h, int rows) { return h * float(rows) - 0.5; }

// Normalized height in a layer of radii [r_bottom, r_top], clamped to [0, 1].
float cloud_height_fraction(float r, float r_bottom, float r_top) {
  return clamp((r - r_bottom) / (r_top - r_bottom), 0.0, 1.0);
}

// The fractional type index of a weather texel in either layout: Schneider
// folds precipitation into the index (a raining texel is a cumulonimbus),
// Frostbite stores the column's u in G.
float weather_type_index(float4 weather, int weather_layout, int types) {
  if (weather_layout == SKYBAKE_WEATHER_FROSTBITE) return index_from_type_u(weather.g, types);
  return type_index_from_schneider(weather.b, weather.g);
}

// Weather map coordinates of a world position (metres, the plane of the
// map): the map covers world_size_m (metadata world_size_km x 1000) and
// repeats, so sample it with WRAP addressing.
float2 weather_uv_from_world(float2 position_m, float world_size_m) {
  return position_m / world_size_m;
}

// density(h) = smoothstep(a, b, h) - smoothstep(c, d, h) with ramp = (a, b,
// c, d), the closed form the cloud_types and height_gradients texels hold
// (height_profile.hpp); a < b and c < d.
float compute_height_density(float4 ramp, float h) {
  return clamp(smoothstep(ramp.x, ramp.y, h) - smoothstep(ramp.z, ramp.w, h), 0.0, 1.0);
}

// Erosion: erosion.x (base) at h <= a, erosion.y (top) at h >= d, linear
// between (height_profile.hpp).
float compute_height_erosion(float4 ramp, float2 erosion, float h) {
  float t = clamp((h - ramp.x) / (ramp.w - ramp.x), 0.0, 1.0);
  return erosion.x + t * (erosion.y - erosion.x);
}

// (density, erosion) of the fractional type `index` at normalized height h
// from the cloud_types texture (bilinear, clamp to edge): the column centre
// returns the type exactly, between centres two types blend.
float2 lookup_cloud_type(Texture2D<float4> cloud_types, SamplerState clamp_linear, float index,
                         int types, float h) {
  return cloud_types.SampleLevel(clamp_linear, float2(type_u_from_index(index, types), h), 0.0).rg;
}

// Weights of the four standard gradients for a fractional index in [0, 3]:
// the hat functions of linear interpolation between columns, so that
// lookup_height_gradient equals lookup_cloud_type's density for the first
// four types (Schneider 4.3.2: "a weighted sum of the three functions").
float4 height_gradient_weights(float index) {
  float i = clamp(index, 0.0, 3.0);
  return max(0.0, 1.0 - abs(i - float4(0.0, 1.0, 2.0, 3.0)));
}

// Density at normalized height h of the fractional type `index` from the
// height_gradients table (1 texel wide, bilinear, clamp to edge).
float lookup_height_gradient(Texture2D<float4> height_gradients, SamplerState clamp_linear,
                             float index, float h) {
  return dot(height_gradient_weights(index),
             height_gradients.SampleLevel(clamp_linear, float2(0.5, h), 0.0));
}

// Cirrus coordinates of a position on the sky plane (metres): `tile_m`
// across one repeat, the streaks (fibres along the texture's x) turned to
// run along the unit vector wind_dir; sample with WRAP addressing.
float2 cirrus_uv_from_world(float2 position_m, float tile_m, float2 wind_dir) {
  float2 along =
      float2(dot(position_m, wind_dir), dot(position_m, float2(-wind_dir.y, wind_dir.x)));
  return along / tile_m;
}

#endif  // SKYBAKE_CLOUDS_WEATHER_HLSL
