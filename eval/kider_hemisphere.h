#pragma once
// The published evaluation's sun-azimuth re-fit (Bruneton, "A Qualitative and Quantitative
// Evaluation of 8 Clear Sky Models", IEEE TVCG 2017, and its code `clear-sky-models`), reproduced as a
// convention so that totals are comparable with the published ones (docs/validation.md).
//
// Kider's scanner measures 81 directions that are the cell centres of a 9 x 9 grid mapped onto the
// hemisphere by Shirley and Chiu's concentric map ("A low distortion map between disk and square",
// 1997) followed by cos(zenith) = 1 - r^2. Grid ring k (k = 0 the zenith, 4 the lowest) has radius
// r_k = 2k / 9 and 8k cells at azimuths n pi / (4k). The evaluation reads the sky between samples by
// a cubic (Catmull-Rom) interpolation along each ring in azimuth, then across rings in u = 4.5 r,
// with two kinds of ghost rings: ring -1 from an estimate of the zenith gradient and rings beyond 4
// by holding the second difference, out to the horizon.
#include <optional>
#include <vector>

#include "eval/kider_capture.h"

namespace firmament {

class KiderHemisphere {
 public:
  // The samples (azimuth clockwise from north) arranged on the grid's rings; nullopt when they are
  // not exactly the 81 directions of that layout, one value per direction.
  static std::optional<KiderHemisphere> fromSamples(const std::vector<RingSample>& samples);

  // The interpolated value in a direction (zenith 0 ... pi/2, any azimuth, clockwise from north).
  double operator()(double zenith, double azimuth) const;

 private:
  double ring(int k, double azimuth) const;  // ring k at an azimuth, ghost rings included
  double zenithSlope(double azimuth) const;  // d value / d ring index at the zenith, along azimuth
  std::vector<double> rings_[5];             // ring k: 8k values (ring 0: one), n-th at n pi / (4k)
};

// The published asymmetry about the vertical plane at `axisAzimuth`: the sum over 16 zeniths with
// cos = (i + 0.5) / 16 and 64 azimuths 2 pi j / 64 of |v(zenith, a) - v(zenith, 2 axis - a)|, v
// interpolated. (Linear values: the evaluation mirrors the spectrally integrated radiance.)
double publishedMirrorAsymmetry(const KiderHemisphere& sky, double axisAzimuth);

// minimiseOnAzimuthGrid (kider_capture.h) of publishedMirrorAsymmetry.
double refitSunAzimuthByPublishedSymmetry(const KiderHemisphere& sky, double computedAzimuth,
                                          double halfRange = 20.0 * 3.14159265358979323846 / 180.0,
                                          double step = 0.2 * 3.14159265358979323846 / 180.0);

}  // namespace firmament
