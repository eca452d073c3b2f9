#include "terrain/procedural_terrain.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <thread>

#include "terrain/gradient_noise.h"

namespace firmament::terrain {
namespace {

// Wavelengths and reliefs: alpine after the Bernese Oberland (ridge spacing ~10–20 km, 2–3 km from
// valley floor to summit), hills a rolling upland (a few km, a few hundred m), plains a low-relief
// lowland (tens of km, tens of m), canyon a plateau cut into terraces (Colorado-plateau-like steps).
const TerrainStyleParameters kStyles[] = {
    {"alpine", "ridged mountains with smooth valley floors (20 km ridges, 3 km relief)", 20000.0, 3000.0, 0.5, true,
     1.0, 0},
    {"hills", "rolling hills (6 km, 300 m)", 6000.0, 300.0, 0.5, false, 1.0, 0},
    {"plains", "low-relief lowland (40 km, 40 m)", 40000.0, 40.0, 0.5, false, 0.5, 0},
    {"canyon", "plateau cut into terraces with steep risers (8 km, 600 m, 6 steps)", 8000.0, 600.0, 0.5, false, 0.5, 6},
};

constexpr int kMaxOctaves = 28;
constexpr double kRidgeSoftness = 0.08;
// Octave rotation: (cos, sin) = (4/5, 3/5), an angle of 36.87°, irrational in degrees, so lattices of
// successive octaves never align.
constexpr double kRotationCos = 0.8, kRotationSin = 0.6;

double smoothstep01(double t) {
  t = std::clamp(t, 0.0, 1.0);
  return t * t * (3.0 - 2.0 * t);
}

// The per-octave lattice offset in [0, 1)² from the seed (53 hash bits, exact).
void octaveOffset(uint64_t seed, int octave, double& ox, double& oy) {
  uint64_t h = latticeHash(octave, -7, seed);
  ox = double(h >> 11) * 0x1.0p-53;
  oy = double(latticeHash(octave, -11, seed) >> 11) * 0x1.0p-53;
}

}  // namespace

const TerrainStyleParameters& styleParameters(TerrainStyle style) { return kStyles[int(style)]; }

TerrainStyle styleFromName(const std::string& name) {
  for (TerrainStyle s : allStyles())
    if (name == styleParameters(s).name) return s;
  throw std::logic_error("unknown terrain style '" + name + "'");
}

std::vector<TerrainStyle> allStyles() {
  return {TerrainStyle::Alpine, TerrainStyle::Hills, TerrainStyle::Plains, TerrainStyle::Canyon};
}

TileRegion TileRegion::centred(double cx, double cy, double size, int n) {
  TileRegion r;
  r.nx = r.ny = n;
  r.dx = r.dy = size / double(n - 1);
  r.x0 = cx - 0.5 * size;
  r.y0 = cy - 0.5 * size;
  return r;
}

ProceduralTerrainField::ProceduralTerrainField(const ProceduralTerrain& settings) : settings_(settings) {
  const TerrainStyleParameters& p = styleParameters(settings.style);
  shift_ = p.relief_m * settings.verticalScale * profile(0.0, 0.0, settings.detail_m);
}

double ProceduralTerrainField::profile(double x, double y, double finest) const {
  const TerrainStyleParameters& p = styleParameters(settings_.style);
  finest = std::max(finest, settings_.detail_m);
  const double relief = p.relief_m * settings_.verticalScale;
  // Normalisation: the geometric series of the amplitudes, independent of how many octaves are summed,
  // so every level of detail shares one scale.
  const double norm = 1.0 / (1.0 - p.gain);
  double wavelength = p.wavelength_m * settings_.horizontalScale;
  double amplitude = 1.0, sum = 0.0, weight = 1.0;
  double slopeX = 0.0, slopeY = 0.0;  // ∇ of relief × sum / norm so far (m/m)
  double rc = 1.0, rs = 0.0;          // rotation of this octave's lattice
  for (int octave = 0; octave < kMaxOctaves; ++octave) {
    const double fade = std::clamp(wavelength / finest - 1.0, 0.0, 1.0);
    if (fade <= 0.0) break;
    double ox, oy;
    octaveOffset(settings_.seed, octave, ox, oy);
    const double u = (rc * x - rs * y) / wavelength + ox;
    const double v = (rs * x + rc * y) / wavelength + oy;
    const NoiseSample n = gradientNoise(u, v, settings_.seed + uint64_t(octave) * 0x632BE59BD9B4E019ull);
    // d/du, d/dv back to the plane: the lattice is the plane rotated by (rc, rs) and scaled by 1/λ.
    double signal, dsu, dsv;
    if (p.ridged) {
      // |n| softened to √(n² + ε²) − ε: a crest rounded over ε of the noise's range instead of a
      // one-sample crease (sqrt is correctly rounded in IEEE, so this stays deterministic).
      const double soft = std::sqrt(n.value * n.value + kRidgeSoftness * kRidgeSoftness);
      const double r = 1.0 - (soft - kRidgeSoftness);
      const double dabs = n.value / soft;
      signal = r * r * weight;
      dsu = -2.0 * r * dabs * n.dx * weight;
      dsv = -2.0 * r * dabs * n.dy * weight;
      weight = std::clamp(signal * 2.0, 0.0, 1.0);
    } else {
      signal = n.value;
      dsu = n.dx;
      dsv = n.dy;
    }
    const double gx = (rc * dsu + rs * dsv) / wavelength, gy = (-rs * dsu + rc * dsv) / wavelength;
    const double damping = settings_.erosion ? 1.0 / (1.0 + p.slopeDamping * (slopeX * slopeX + slopeY * slopeY)) : 1.0;
    const double a = amplitude * damping * fade;
    sum += a * signal;
    slopeX += relief * a * gx / norm;
    slopeY += relief * a * gy / norm;
    amplitude *= p.gain;
    wavelength *= 0.5;
    const double c = rc * kRotationCos - rs * kRotationSin;
    rs = rs * kRotationCos + rc * kRotationSin;
    rc = c;
  }
  double value = sum / norm;  // ridged: [0, 1]; fBm: about [−1, 1]
  if (p.ridged) value = value * value;
  if (p.terraces > 0) {
    const double t = (0.5 + 0.5 * value) * double(p.terraces);
    const double step = std::floor(t);
    value = (step + smoothstep01((t - step - 0.4) * 5.0)) / double(p.terraces);
  }
  return value;
}

double ProceduralTerrainField::height(double x, double y, double finest) const {
  const TerrainStyleParameters& p = styleParameters(settings_.style);
  return settings_.baseHeight + p.relief_m * settings_.verticalScale * profile(x, y, finest) - shift_;
}

HeightField ProceduralTerrainField::tile(const TileRegion& region) const {
  HeightField field(region.nx, region.ny, region.x0, region.y0, region.dx, region.dy);
  const double finest = std::max(2.0 * std::max(region.dx, region.dy), settings_.detail_m);
  const unsigned threads = std::max(1u, std::min(std::thread::hardware_concurrency(), unsigned(region.ny)));
  auto rows = [&](unsigned first) {
    for (int j = int(first); j < region.ny; j += int(threads))
      for (int i = 0; i < region.nx; ++i) field.at(i, j) = float(height(field.xAt(i), field.yAt(j), finest));
  };
  std::vector<std::thread> pool;
  for (unsigned t = 1; t < threads; ++t) pool.emplace_back(rows, t);
  rows(0);
  for (auto& t : pool) t.join();
  field.source =
      std::string("procedural ") + styleParameters(settings_.style).name + ", seed " + std::to_string(settings_.seed);
  return field;
}

}  // namespace firmament::terrain
