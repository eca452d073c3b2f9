#pragma once
// Procedural height fields: seeded, deterministic, band-limited sums of gradient noise in four named
// styles, evaluated anywhere on the plane, so any region at any resolution (a tile) agrees with every
// other where they overlap.
//
// The model (docs/terrain.md, "Procedural terrain"; decision 0200):
//   - octaves of gradient noise (terrain/gradient_noise.h), wavelength halving and amplitude × `gain`
//     per octave, each octave's lattice rotated by atan(3/4) and offset, so lattice axes do not line up;
//   - ridged styles use Musgrave's ridged multifractal (Ebert et al. 2003, "Texturing and Modeling",
//     3rd ed., ch. 16): octave signal (1 − |n|)², weighted by the previous octave's signal × 2 clamped to
//     [0, 1], so detail gathers on ridges and valleys stay smooth;
//   - erosion-like shaping: every octave is damped by 1 / (1 + k |∇h|²), with ∇h the slope (m/m) of the
//     octaves above it (Quilez 2008, "Terrain raymarching", iquilezles.org; the derivative-damped
//     "eroded" fBm of de Carpentier & Bidarra 2009, "Interactive GPU-based procedural heightfield
//     brushes", FDG): steep flanks lose fine relief (talus-like slopes) and flats keep it, and the
//     shaping is pointwise, so tiles and levels of detail agree (a simulated erosion would not);
//   - a per-style profile on the normalised sum: alpine squares it (broad valley floors, sharp
//     peaks), canyon cuts it into terraces with steep risers.
// Level of detail: the octaves stop at the finest wavelength asked for (a tile's two sample spacings,
// or the scene's detail), the last fading in linearly between 1× and 2× that wavelength, so a
// coarser tile is the finer one without its finest octaves and detail grows without popping.
// The field passes through `baseHeight` at the location (x = y = 0, evaluated at the finest detail),
// so the scene's /location/height_m is the ground there.
#include <cstdint>
#include <string>
#include <vector>

#include "terrain/height_field.h"

namespace firmament::terrain {

enum class TerrainStyle { Alpine, Hills, Plains, Canyon };

// A style's constants at horizontal and vertical scale 1.
struct TerrainStyleParameters {
  const char* name;
  const char* description;
  double wavelength_m;  // the largest octave's wavelength
  double relief_m;      // height of the normalised profile's range
  double gain;          // amplitude ratio of successive octaves
  bool ridged;          // ridged multifractal (else signed fBm)
  double slopeDamping;  // k of 1 / (1 + k |∇h|²)
  int terraces;         // > 0: the profile cut into this many steps (canyon)
};

const TerrainStyleParameters& styleParameters(TerrainStyle style);
// "alpine", "hills", "plains", "canyon"; an unknown name is a std::logic_error (the scene schema lists
// the names, so a scene cannot reach it).
TerrainStyle styleFromName(const std::string& name);
std::vector<TerrainStyle> allStyles();

struct ProceduralTerrain {
  TerrainStyle style = TerrainStyle::Alpine;
  uint64_t seed = 3;
  double horizontalScale = 1.0;  // multiplies the style's wavelengths
  double verticalScale = 1.0;    // multiplies its relief
  double detail_m = 1.0;         // finest wavelength ever summed (m), and the one the location is fixed at
  double baseHeight = 0.0;       // m above sea level at the location
  bool erosion = true;           // the slope damping (false only to measure what it does)
};

// A regular grid of samples to produce: sample (i, j) at (x0 + i dx, y0 + j dy).
struct TileRegion {
  double x0 = 0.0;
  double y0 = 0.0;
  int nx = 2;
  int ny = 2;
  double dx = 1.0;
  double dy = 1.0;
  // The square of `size` metres centred on (cx, cy) with n × n samples (spacing size / (n − 1)).
  static TileRegion centred(double cx, double cy, double size, int n);
};

class ProceduralTerrainField {
 public:
  explicit ProceduralTerrainField(const ProceduralTerrain& settings);

  const ProceduralTerrain& settings() const { return settings_; }
  // The height (m above sea level) at a plane point, summing octaves down to `finestWavelength_m`
  // (clamped below by settings.detail_m).
  double height(double x, double y, double finestWavelength_m) const;
  // The normalised profile before the location shift and the relief (for statistics and tests).
  double profile(double x, double y, double finestWavelength_m) const;
  // Every sample of a region, its octaves stopping at max(2 × spacing, detail_m); rows in parallel on
  // the machine's cores (the result does not depend on their number).
  HeightField tile(const TileRegion& region) const;

 private:
  ProceduralTerrain settings_;
  double shift_ = 0.0;  // relief × profile at the location
};

}  // namespace firmament::terrain
