// Tabulated spectral data (core/spectrum.h). Numbers are published data; see each table's citation.
#include <array>

#include "core/spectrum.h"

namespace firmament {
namespace {

// CIE 1931 2° colour-matching functions, 360, 365, ..., 830 nm (95 values). Source: CIE 15:2004,
// "Colorimetry", 3rd ed., table T.4, with the digits of the CVRL database file ciexyz31.txt
// (http://www.cvrl.org). Σȳ·5 nm = 106.857; the three sums agree to 0.04 %, so an equal-energy
// spectrum lands on x = y = 1/3.
constexpr std::array<double, 95> kCie1931X = {
    0.0001299,    0.0002321,    0.0004149,    0.0007416,    0.001368,     0.002236,     0.004243,
    0.00765,  // 360 nm
    0.01431,      0.02319,      0.04351,      0.07763,      0.13438,      0.21477,      0.2839,
    0.3285,  // 400 nm
    0.34828,      0.34806,      0.3362,       0.3187,       0.2908,       0.2511,       0.19536,
    0.1421,  // 440 nm
    0.09564,      0.05795001,   0.03201,      0.0147,       0.0049,       0.0024,       0.0093,
    0.0291,  // 480 nm
    0.06327,      0.1096,       0.1655,       0.2257499,    0.2904,       0.3597,       0.4334499,
    0.5120501,  // 520 nm
    0.5945,       0.6784,       0.7621,       0.8425,       0.9163,       0.9786,       1.0263,
    1.0567,  // 560 nm
    1.0622,       1.0456,       1.0026,       0.9384,       0.8544499,    0.7514,       0.6424,
    0.5419,  // 600 nm
    0.4479,       0.3608,       0.2835,       0.2187,       0.1649,       0.1212,       0.0874,
    0.0636,  // 640 nm
    0.04677,      0.0329,       0.0227,       0.01584,      0.01135916,   0.008110916,  0.005790346,
    0.004109457,  // 680 nm
    0.002899327,  0.00204919,   0.001439971,  0.0009999493, 0.0006900786, 0.0004760213, 0.0003323011,
    0.0002348261,  // 720 nm
    0.0001661505, 0.000117413,  8.307527e-05, 5.870652e-05, 4.150994e-05, 2.935326e-05, 2.067383e-05,
    1.455977e-05,                                                                                      // 760 nm
    1.025398e-05, 7.221456e-06, 5.085868e-06, 3.581652e-06, 2.522525e-06, 1.776509e-06, 1.251141e-06,  // 800 nm
};
constexpr std::array<double, 95> kCie1931Y = {
    3.917e-06,  6.965e-06,  1.239e-05,  2.202e-05,  3.9e-05,    6.4e-05,    0.00012,    0.000217,    // 360 nm
    0.000396,   0.00064,    0.00121,    0.00218,    0.004,      0.0073,     0.0116,     0.01684,     // 400 nm
    0.023,      0.0298,     0.038,      0.048,      0.06,       0.0739,     0.09098,    0.1126,      // 440 nm
    0.13902,    0.1693,     0.20802,    0.2586,     0.323,      0.4073,     0.503,      0.6082,      // 480 nm
    0.71,       0.7932,     0.862,      0.9148501,  0.954,      0.9803,     0.9949501,  1,           // 520 nm
    0.995,      0.9786,     0.952,      0.9154,     0.87,       0.8163,     0.757,      0.6949,      // 560 nm
    0.631,      0.5668,     0.503,      0.4412,     0.381,      0.321,      0.265,      0.217,       // 600 nm
    0.175,      0.1382,     0.107,      0.0816,     0.061,      0.04458,    0.032,      0.0232,      // 640 nm
    0.017,      0.01192,    0.00821,    0.005723,   0.004102,   0.002929,   0.002091,   0.001484,    // 680 nm
    0.001047,   0.00074,    0.00052,    0.0003611,  0.0002492,  0.0001719,  0.00012,    8.48e-05,    // 720 nm
    6e-05,      4.24e-05,   3e-05,      2.12e-05,   1.499e-05,  1.06e-05,   7.4657e-06, 5.2578e-06,  // 760 nm
    3.7029e-06, 2.6078e-06, 1.8366e-06, 1.2934e-06, 9.1093e-07, 6.4153e-07, 4.5181e-07,              // 800 nm
};
constexpr std::array<double, 95> kCie1931Z = {
    0.0006061,   0.001086,    0.001946, 0.003486, 0.006450001, 0.01054999, 0.02005001,
    0.03621,  // 360 nm
    0.06785001,  0.1102,      0.2074,   0.3713,   0.6456,      1.0390501,  1.3856,
    1.62296,  // 400 nm
    1.74706,     1.7826,      1.77211,  1.7441,   1.6692,      1.5281,     1.28764,
    1.0419,  // 440 nm
    0.8129501,   0.6162,      0.46518,  0.3533,   0.272,       0.2123,     0.1582,
    0.1117,  // 480 nm
    0.07824999,  0.05725001,  0.04216,  0.02984,  0.0203,      0.0134,     0.008749999,
    0.005749999,  // 520 nm
    0.0039,      0.002749999, 0.0021,   0.0018,   0.001650001, 0.0014,     0.0011,
    0.001,  // 560 nm
    0.0008,      0.0006,      0.00034,  0.00024,  0.00019,     0.0001,     4.999999e-05,
    3e-05,  // 600 nm
    2e-05,       1e-05,       0,        0,        0,           0,          0,
    0,  // 640 nm
    0,           0,           0,        0,        0,           0,          0,
    0,  // 680 nm
    0,           0,           0,        0,        0,           0,          0,
    0,  // 720 nm
    0,           0,           0,        0,        0,           0,          0,
    0,                                                                         // 760 nm
    0,           0,           0,        0,        0,           0,          0,  // 800 nm
};

// Solar spectral irradiance at the top of the atmosphere, 1 au, W m^-2 nm^-1, for the bins
// [360, 370), [370, 380), ..., [830, 840) nm (48 values): the mean of the ASTM G-173-03 extraterrestrial
// spectrum (ASTM International, "Standard Tables for Reference Solar Spectral Irradiances", 2003; from
// the Wehrli 1985 spectrum) over each bin, as tabulated in Bruneton (2017), "Precomputed Atmospheric
// Scattering: a New Implementation", github.com/ebruneton/precomputed_atmospheric_scattering.
constexpr std::array<double, 48> kSolarIrradiance = {
    1.11776, 1.14259, 1.01249, 1.14716, 1.72765, 1.73054, 1.6887,  1.61253, 1.91198, 2.03474, 2.02042, 2.02212,
    1.93377, 1.95809, 1.91686, 1.8298,  1.8685,  1.8931,  1.85149, 1.8504,  1.8341,  1.8345,  1.8147,  1.78158,
    1.7533,  1.6965,  1.68194, 1.64654, 1.6048,  1.52143, 1.55622, 1.5113,  1.474,   1.4482,  1.41018, 1.36775,
    1.34188, 1.31429, 1.28303, 1.26758, 1.2367,  1.2082,  1.18737, 1.14683, 1.12362, 1.1058,  1.07124, 1.04992,
};

// Ozone absorption cross-section at 233 K, m^2, for the same 10 nm bins: Serdyuchenko, Gorshelev,
// Weber, Chehade & Burrows (2014), Atmos. Meas. Tech. 7, 625-636 (IUP Bremen "o3spectra2011"), averaged
// over each bin as tabulated in Bruneton (2017). The peak is the Chappuis band near 600 nm.
constexpr std::array<double, 48> kOzoneCrossSection = {
    1.18e-27,  2.182e-28, 2.818e-28, 6.636e-28, 1.527e-27, 2.763e-27, 5.52e-27,  8.451e-27, 1.582e-26, 2.316e-26,
    3.669e-26, 4.924e-26, 7.752e-26, 9.016e-26, 1.48e-25,  1.602e-25, 2.139e-25, 2.755e-25, 3.091e-25, 3.5e-25,
    4.266e-25, 4.672e-25, 4.398e-25, 4.701e-25, 5.019e-25, 4.305e-25, 3.74e-25,  3.215e-25, 2.662e-25, 2.238e-25,
    1.852e-25, 1.473e-25, 1.209e-25, 9.423e-26, 7.455e-26, 6.566e-26, 5.105e-26, 4.15e-26,  4.228e-26, 3.237e-26,
    2.451e-26, 2.801e-26, 2.534e-26, 1.624e-26, 1.465e-26, 2.078e-26, 1.383e-26, 7.105e-27,
};

}  // namespace

const TabulatedSpectrum& cie1931X() {
  static const TabulatedSpectrum spectrum{360.0, 5.0, {kCie1931X.begin(), kCie1931X.end()}};
  return spectrum;
}
const TabulatedSpectrum& cie1931Y() {
  static const TabulatedSpectrum spectrum{360.0, 5.0, {kCie1931Y.begin(), kCie1931Y.end()}};
  return spectrum;
}
const TabulatedSpectrum& cie1931Z() {
  static const TabulatedSpectrum spectrum{360.0, 5.0, {kCie1931Z.begin(), kCie1931Z.end()}};
  return spectrum;
}
const TabulatedSpectrum& solarIrradianceTopOfAtmosphere() {
  static const TabulatedSpectrum spectrum{360.0, 10.0, {kSolarIrradiance.begin(), kSolarIrradiance.end()}};
  return spectrum;
}
const TabulatedSpectrum& ozoneAbsorptionCrossSection() {
  static const TabulatedSpectrum spectrum{360.0, 10.0, {kOzoneCrossSection.begin(), kOzoneCrossSection.end()}};
  return spectrum;
}

}  // namespace firmament
