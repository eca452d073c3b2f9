#include "core/solar_spectrum_g173.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/spectrum.h"

namespace firmament {
namespace {

// ASTM G173-03, extraterrestrial ("Etr") column, W m^-2 nm^-1. The sample means over each 10-nm
// bin equal the 10-nm table of core/spectrum_tables.cpp (Bruneton 2017) to its digits: the test
// SolarSpectrumG173.BinMeansAreTheAtmospheresTable checks the transcription that way.
constexpr double kHalfNmFirst = 340.0, kHalfNmStep = 0.5;
constexpr std::array<double, 121> kHalfNm = {
    1.0544,  1.0463,  0.971,   0.959,   0.9957,  1.0277,  1.0417,  0.98301, 0.85416, 0.813,    // 340 nm
    0.91583, 0.97021, 0.94269, 0.95594, 0.96954, 0.93318, 0.92472, 0.93721, 0.899,   0.91969,  // 345 nm
    1.0122,  1.0849,  1.0534,  1.0129,  0.98383, 0.926,   0.98012, 1.0752,  1.1346,  1.144,    // 350 nm
    1.1406,  1.0964,  1.025,   0.95914, 0.842,   0.85015, 0.78916, 0.731,   0.85805, 1.0321,   // 355 nm
    1.089,   1.0265,  0.9415,  0.918,   0.958,   1.045,   1.071,   1.038,   1.0716,  1.059,    // 360 nm
    1.097,   1.2041,  1.286,   1.2843,  1.2577,  1.2317,  1.157,   1.1459,  1.1944,  1.2795,   // 365 nm
    1.2934,  1.166,   1.1811,  1.2249,  1.1444,  1.0876,  1.0445,  0.939,   0.93442, 0.925,    // 370 nm
    0.985,   1.0874,  1.124,   1.104,   1.1813,  1.3149,  1.4144,  1.3765,  1.226,   1.098,    // 375 nm
    1.152,   1.231,   1.249,   1.1224,  0.95426, 0.82313, 0.73603, 0.71095, 0.821,   0.9862,   // 380 nm
    1.0802,  1.0296,  0.99113, 1.0279,  1.0354,  1.0186,  1.0067,  0.99743, 1.081,   1.1958,   // 385 nm
    1.2519,  1.2601,  1.3322,  1.349,   1.24,    1.0312,  0.745,   0.5912,  0.76675, 1.0557,   // 390 nm
    1.245,   1.3245,  1.1626,  0.8433,  0.652,   0.96142, 1.301,   1.5342,  1.6245,  1.6717,   // 395 nm
    1.6885,                                                                                    // 400 nm
};
constexpr double kOneNmFirst = 401.0, kOneNmStep = 1.0;
constexpr std::array<double, 340> kOneNm = {
    1.752,  1.814,  1.74,   1.763,  1.715,  1.666,  1.63,   1.699,  1.809,  1.537,   // 401 nm
    1.715,  1.816,  1.7392, 1.7144, 1.7688, 1.815,  1.766,  1.685,  1.749,  1.599,   // 411 nm
    1.811,  1.782,  1.721,  1.708,  1.755,  1.699,  1.638,  1.651,  1.523,  1.212,   // 421 nm
    1.099,  1.822,  1.6913, 1.56,   1.709,  1.868,  1.9,    1.663,  1.601,  1.83,    // 431 nm
    1.799,  1.922,  1.949,  1.8941, 1.965,  1.7557, 1.99,   2.014,  2.001,  2.069,   // 441 nm
    2.142,  2.047,  1.8864, 2.018,  2.001,  2.063,  2.077,  2.032,  2.012,  1.9973,  // 451 nm
    2.0639, 2.078,  2.084,  2.015,  1.984,  2.021,  1.931,  2.012,  2.018,  1.939,   // 461 nm
    1.969,  2.07,   1.9882, 2.012,  2.08,   2.012,  2.025,  2.086,  2.04,   2.068,   // 471 nm
    2.061,  2.0623, 2.031,  1.989,  1.979,  1.601,  1.789,  1.935,  1.8224, 2.032,   // 481 nm
    1.949,  1.856,  1.983,  1.9339, 2.051,  1.949,  1.98,   1.924,  1.923,  1.916,   // 491 nm
    1.858,  1.86,   1.949,  1.833,  1.9472, 2.025,  1.9354, 1.88,   1.965,  1.91,    // 501 nm
    1.941,  1.989,  1.866,  1.824,  1.875,  1.891,  1.539,  1.759,  1.704,  1.86,    // 511 nm
    1.873,  1.915,  1.804,  1.941,  1.928,  1.874,  1.641,  1.88,   1.969,  1.892,   // 521 nm
    1.995,  1.958,  1.747,  1.869,  1.895,  1.974,  1.824,  1.913,  1.864,  1.8,     // 531 nm
    1.734,  1.888,  1.851,  1.919,  1.874,  1.8609, 1.882,  1.826,  1.88,   1.863,   // 541 nm
    1.859,  1.896,  1.842,  1.878,  1.889,  1.857,  1.812,  1.853,  1.755,  1.786,   // 551 nm
    1.89,   1.801,  1.871,  1.836,  1.849,  1.75,   1.868,  1.859,  1.831,  1.828,   // 561 nm
    1.762,  1.872,  1.881,  1.873,  1.834,  1.818,  1.862,  1.799,  1.816,  1.834,   // 571 nm
    1.833,  1.852,  1.863,  1.854,  1.836,  1.792,  1.838,  1.821,  1.624,  1.7218,  // 581 nm
    1.809,  1.788,  1.792,  1.789,  1.778,  1.796,  1.806,  1.772,  1.764,  1.77,    // 591 nm
    1.742,  1.715,  1.749,  1.779,  1.773,  1.758,  1.762,  1.751,  1.734,  1.724,   // 601 nm
    1.712,  1.736,  1.71,   1.655,  1.712,  1.664,  1.641,  1.702,  1.709,  1.711,   // 611 nm
    1.724,  1.6784, 1.682,  1.667,  1.644,  1.64,   1.693,  1.693,  1.687,  1.665,   // 621 nm
    1.659,  1.5901, 1.674,  1.637,  1.652,  1.6093, 1.661,  1.665,  1.653,  1.613,   // 631 nm
    1.61,   1.609,  1.625,  1.614,  1.627,  1.591,  1.606,  1.602,  1.551,  1.526,   // 641 nm
    1.613,  1.591,  1.598,  1.575,  1.523,  1.3233, 1.384,  1.539,  1.542,  1.558,   // 651 nm
    1.566,  1.571,  1.563,  1.554,  1.567,  1.555,  1.5354, 1.5348, 1.558,  1.534,   // 661 nm
    1.529,  1.506,  1.517,  1.513,  1.499,  1.515,  1.5,    1.507,  1.493,  1.494,   // 671 nm
    1.487,  1.493,  1.476,  1.466,  1.465,  1.433,  1.472,  1.476,  1.478,  1.479,   // 681 nm
    1.468,  1.454,  1.458,  1.457,  1.435,  1.442,  1.438,  1.417,  1.434,  1.422,   // 691 nm
    1.4131, 1.3987, 1.4095, 1.4187, 1.433,  1.4138, 1.404,  1.399,  1.39,   1.404,   // 701 nm
    1.397,  1.3818, 1.3702, 1.3819, 1.3502, 1.3694, 1.365,  1.357,  1.301,  1.3487,  // 711 nm
    1.348,  1.36,   1.351,  1.3607, 1.3465, 1.3429, 1.3444, 1.337,  1.2796, 1.3357,  // 721 nm
    1.3104, 1.3333, 1.3108, 1.339,  1.3271, 1.31,   1.312,  1.3,    1.2646, 1.283,   // 731 nm
};

std::vector<double> makeWavelengths() {
  std::vector<double> w;
  for (size_t i = 0; i < kHalfNm.size(); ++i) w.push_back(kHalfNmFirst + kHalfNmStep * double(i));
  for (size_t i = 0; i < kOneNm.size(); ++i) w.push_back(kOneNmFirst + kOneNmStep * double(i));
  return w;
}
std::vector<double> makeIrradiance() {
  std::vector<double> v(kHalfNm.begin(), kHalfNm.end());
  v.insert(v.end(), kOneNm.begin(), kOneNm.end());
  return v;
}

}  // namespace

std::span<const double> astmG173ExtraterrestrialWavelengths() {
  static const std::vector<double> w = makeWavelengths();
  return w;
}
std::span<const double> astmG173ExtraterrestrialIrradiance() {
  static const std::vector<double> v = makeIrradiance();
  return v;
}

double astmG173ExtraterrestrialSeenWithResolution(double wavelengthNm, double fwhmNm) {
  if (!(fwhmNm > 0.0)) throw std::out_of_range("instrument FWHM must be > 0 nm");
  const double sigma = fwhmNm / (2.0 * std::sqrt(2.0 * std::log(2.0)));
  const double lo = wavelengthNm - 4.0 * sigma, hi = wavelengthNm + 4.0 * sigma;
  if (lo < kAstmG173FineFirstNm || hi > kAstmG173FineLastNm)
    throw std::out_of_range("a " + std::to_string(fwhmNm) + "-nm line shape at " + std::to_string(wavelengthNm) +
                            " nm leaves the G-173 table (" + std::to_string(kAstmG173FineFirstNm) + "-" +
                            std::to_string(kAstmG173FineLastNm) + " nm)");
  const auto w = astmG173ExtraterrestrialWavelengths();
  const auto s = astmG173ExtraterrestrialIrradiance();
  // Midpoint rule at 0.01 nm: 50 points per 0.5-nm sample interval, so the piecewise-linear
  // spectrum times the smooth kernel is integrated to ~1e-6.
  const int n = std::max(8, int(std::ceil((hi - lo) / 0.01)));
  const double h = (hi - lo) / n;
  double num = 0.0, den = 0.0;
  for (int k = 0; k < n; ++k) {
    const double x = lo + (k + 0.5) * h;
    const double g = std::exp(-0.5 * std::pow((x - wavelengthNm) / sigma, 2));
    num += g * interpolateSpectrum(w, s, x);
    den += g;
  }
  return num / den;
}

}  // namespace firmament
