// cloud_weather.glsl: how the cloud medium reads the weather map (GPU march and CPU path tracer alike;
// compat.glsl rules). docs/clouds.md, "Weather map"; docs/weather.md for the map itself.
//
// The map (RGBA): R coverage WM_c in [0, 1], G cloud type (0 St, 1/3 Cu, 2/3 Cg, 1 Cb), B precipitation
// (mm/h, unused here), A cloud-top height above the ground (m). It covers a square region of
// width x height metres centred on the scene's location, row 0 at the north, and repeats.
//
// Placement (weather/weather_map.h): in the cloud frame (planet-centred, z up through the scene's
// location, x east, y north) a point p maps to
//     east = R atan2(p.x, p.z),   north = R atan2(p.y, p.z)
// (R the planet radius: the tangent-plane angles times R, the local distance near the centre), moved
// downwind with height z above the ground by the shear skew s (m per m: shear x the thermal's rise
// time, 300 s), moved with the clouds' wind by the layer's wind offset o (the noise is read at p + o,
// cloudLocalPosition, so the map is read at east + o.x: the whole field, coverage included, drifts
// with the wind as one), and to texture coordinates
//     u = (east + o.x - s.x z) / width + 1/2,   v = 1/2 - (north + o.y - s.y z) / height,
// read with a linear, repeating sampler (texel centres at (i + 1/2) / N), as WeatherMap::sampleMap.
//
// Use in the density: the layer's coverage becomes g_c WM_c (Häggström eq. 15's threshold 1 - g_c WM_c),
// the layer's top is lowered to the map's cloud top (a column whose top lies below the layer bottom
// has no cloud; the height fraction p_h runs from the bottom to that top), and the map's type picks
// the column's height profiles (Häggström 2018's WM_t), continuously:
//   type 0 -> 1/3:  the stratiform profiles (stratocumulus in a stratocumulus layer, else stratus)
//                   blended into cumulus's, weight SAT(1 - 3 type);
//   type 1/3 -> 1:  the convective profiles, cumulus's with the cumulonimbus anvil (eqs. 17, 18)
//                   weighted by how far the type is past congestus, SAT(3 type - 2) (0 for Cu and Cg,
//                   1 for Cb; the cumulonimbus profiles with no anvil are cumulus's exactly).
// Cirrus layers keep their own profiles. A map without types (the procedural map of a scene without a
// weather section, clouds/cloud_weather_map.h) holds kCloudWeatherLayerType: the layer's own kind and
// anvil. Its top is kCloudWeatherNoTop, so the layer also keeps its top.
#ifndef FIRMAMENT_CLOUD_WEATHER_GLSL
#define FIRMAMENT_CLOUD_WEATHER_GLSL

#include "common/cloud_density.glsl"

SHARED_BEGIN

const Real kCloudWeatherNoTop = 100000.0;  // m: a top above every layer (the layer's own top applies)
const Real kCloudWeatherMinThickness = 10.0;  // m: thinner columns hold no cloud
const Real kCloudWeatherLayerType = -1.0;     // type channel: no type, the layer's own kind applies

// regionSize = (width, height) of the map (m); skew = downwind shift per metre of height (east, north);
// windOffset = the layer's wind_offset (m; its x and y are east and north).
SHARED_INLINE vec2 cloudWeatherCoordinate(vec3 p, Real planetRadius, vec2 regionSize, vec2 skew, vec3 windOffset) {
  Real z = length(p) - planetRadius;
  Real east = planetRadius * atan(p.x, p.z) + windOffset.x - skew.x * z;
  Real north = planetRadius * atan(p.y, p.z) + windOffset.y - skew.y * z;
  return vec2(east / regionSize.x + 0.5, 0.5 - north / regionSize.y);
}

// The layer as seen by one column of the map: top lowered to the map's cloud top (planetRadius + top),
// profiles picked by the type (above). `empty` is set where the column holds no cloud of this layer.
SHARED_INLINE CloudLayer cloudColumnLayer(CloudLayer layer, vec4 weather, Real planetRadius, OUT(bool) empty) {
  CloudLayer column = layer;
  Real top = min(layer.top_radius, planetRadius + weather.w);
  empty = weather.x <= 0.0 || top - layer.bottom_radius < kCloudWeatherMinThickness;
  column.top_radius = empty ? layer.top_radius : top;
  if (weather.y >= 0.0 && layer.kind != kCloudCirrus) {
    column.kind = kCloudCumulus;  // the cumulonimbus profiles with no anvil are cumulus's
    column.anvil = layer.anvil * clamp(3.0 * weather.y - 2.0, 0.0, 1.0);
    if (column.anvil > 0.0) column.kind = kCloudCumulonimbus;
    column.stratiform = clamp(1.0 - 3.0 * weather.y, 0.0, 1.0);
    column.stratiform_kind = layer.kind == kCloudStratocumulus ? kCloudStratocumulus : kCloudStratus;
  }
  return column;
}

SHARED_END

#endif  // FIRMAMENT_CLOUD_WEATHER_GLSL
