#pragma once
// Measured clear skies in the format of Kider et al. 2014 (../shared/data/kider2014/README.md): one
// folder per capture, 81 spectral radiance files named
//   <capture>_-_<index>____<azimuth>___<elevation>.asd.rad.txt
// with the azimuth counter-clockwise from north, and the conventions of Bruneton's published
// evaluation (IEEE TVCG 2017) that make results comparable: the azimuth flip, the replacement of
// sample 0, and the re-fit of the sun's azimuth by mirror symmetry (docs/validation.md).
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

namespace firmament {

// One measured direction.
struct KiderSample {
  int index = 0;
  double fileAzimuthDeg = 0.0;  // as in the file name: counter-clockwise from north
  double elevationDeg = 0.0;
  double azimuth = 0.0;  // rad, clockwise from north (east = pi/2): kiderAzimuthFromFileDeg
  double zenith = 0.0;   // rad, pi/2 - elevation
  // Spectral radiance, W m^-2 sr^-1 nm^-1, at firstWavelengthNm + i * spacingNm.
  double firstWavelengthNm = 0.0, spacingNm = 1.0;
  std::vector<double> radiance;
  std::filesystem::path file;

  // Linear interpolation of the spectrum; the end values outside the measured range.
  double radianceAt(double wavelengthNm) const;
};

struct KiderCapture {
  std::string name;                  // the folder name, e.g. "2013-05-27___11.45.00" (local time)
  std::string utc;                   // ISO 8601 UTC of the capture
  std::vector<KiderSample> samples;  // sorted by index
};

// The clockwise-from-north azimuth (degrees, [0, 360)) of a file's counter-clockwise one:
// (360 - a) mod 360.
double kiderAzimuthFromFileDeg(double fileAzimuthDeg);

// "2013-05-27___11.45.00" at local time UTC + utcOffsetHours -> "2013-05-27T15:45:00.000Z" for
// offset -4 (EDT). InputError when the name is not of that form.
std::string kiderCaptureUtc(const std::string& captureName, double utcOffsetHours);

// The capture folders under `dataDir`: its radiance/ subfolder when there is one, else dataDir
// itself; every folder holding *.asd.rad.txt files is a capture, sorted by name. InputError when
// there is none.
std::vector<std::filesystem::path> findKiderCaptureFolders(const std::filesystem::path& dataDir);

// Reads every *.asd.rad.txt file of a capture folder. InputError on a malformed file name or file,
// a repeated index, or spectra on different wavelength grids.
KiderCapture readKiderCapture(const std::filesystem::path& folder, double utcOffsetHours);

// Sample 0 (north, lowest ring) reads systematically wrong: its spectrum becomes the mean of its
// two ring neighbours, samples 1 and 31 (README). It stays one of the directions. Returns false
// (and changes nothing) when the capture lacks sample 0, 1 or 31.
bool replaceKiderSampleZero(KiderCapture& capture);

// A scalar measurement in one direction, for the symmetry fit.
struct RingSample {
  double azimuth = 0.0;    // rad, clockwise from north
  double elevation = 0.0;  // rad; samples with equal elevation (to 1e-6 rad) form a ring
  double value = 0.0;
};

// Mirror asymmetry of the sky about the vertical plane at azimuth `sunAzimuth`: the mean over the
// samples on rings of at least 3 of (value - ring(2 sunAzimuth - azimuth))^2, the ring read by
// linear interpolation in azimuth (periodic). The validation passes log radiances, so that each
// direction weighs by its relative asymmetry (else the few circumsolar samples decide alone).
double mirrorAsymmetry(const std::vector<RingSample>& samples, double sunAzimuth);

// The azimuth in [computed - halfRange, computed + halfRange], on a grid of `step` from the low end,
// that minimises `asymmetry` (the first minimum on ties, as the published search): the search both
// re-fits share.
double minimiseOnAzimuthGrid(double computedAzimuth, double halfRange, double step,
                             const std::function<double(double)>& asymmetry);

// minimiseOnAzimuthGrid of mirrorAsymmetry. Defaults: +-20 deg in 0.2 deg steps.
double refitSunAzimuthBySymmetry(const std::vector<RingSample>& samples, double computedAzimuth,
                                 double halfRange = 20.0 * 3.14159265358979323846 / 180.0,
                                 double step = 0.2 * 3.14159265358979323846 / 180.0);

}  // namespace firmament
