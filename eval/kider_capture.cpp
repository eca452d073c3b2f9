#include "eval/kider_capture.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <map>
#include <set>
#include <sstream>

#include "astro/time.h"
#include "core/error.h"

namespace firmament {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kDegree = kPi / 180.0;
const std::string kSuffix = ".asd.rad.txt";

bool endsWith(const std::string& s, const std::string& suffix) {
  return s.size() >= suffix.size() && s.compare(s.size() - suffix.size(), suffix.size(), suffix) == 0;
}

double parseNumber(const std::string& text, const std::filesystem::path& file, const char* what) {
  size_t used = 0;
  double v = 0.0;
  try {
    v = std::stod(text, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used != text.size() || !std::isfinite(v))
    throw InputError(file.string() + ": the " + what + " '" + text + "' is not a number");
  return v;
}

// "<capture>_-_<index>____<azimuth>___<elevation>.asd.rad.txt"
void parseFileName(const std::filesystem::path& file, KiderSample& sample) {
  std::string name = file.filename().string();
  name = name.substr(0, name.size() - kSuffix.size());
  const size_t dash = name.rfind("_-_");
  const size_t four = dash == std::string::npos ? std::string::npos : name.find("____", dash + 3);
  const size_t three = four == std::string::npos ? std::string::npos : name.find("___", four + 4);
  if (three == std::string::npos)
    throw InputError(file.string() + ": the name is not <capture>_-_<index>____<azimuth>___<elevation>" + kSuffix);
  const double index = parseNumber(name.substr(dash + 3, four - dash - 3), file, "index");
  if (index < 0 || index != std::floor(index)) throw InputError(file.string() + ": the index is not a whole number");
  sample.index = int(index);
  sample.fileAzimuthDeg = parseNumber(name.substr(four + 4, three - four - 4), file, "azimuth");
  sample.elevationDeg = parseNumber(name.substr(three + 3), file, "elevation");
  if (sample.elevationDeg < -90.0 || sample.elevationDeg > 90.0)
    throw InputError(file.string() + ": the elevation is outside [-90, 90] degrees");
  sample.azimuth = kiderAzimuthFromFileDeg(sample.fileAzimuthDeg) * kDegree;
  sample.zenith = (90.0 - sample.elevationDeg) * kDegree;
}

void readSpectrum(const std::filesystem::path& file, KiderSample& sample) {
  std::ifstream in(file);
  if (!in) throw InputError(file.string() + ": cannot be read");
  std::string line;
  std::getline(in, line);  // header
  std::vector<double> wavelengths;
  while (std::getline(in, line)) {
    std::istringstream fields(line);
    double wavelength, value;
    if (!(fields >> wavelength)) continue;  // blank line
    if (!(fields >> value) || !std::isfinite(value))
      throw InputError(file.string() + ": line '" + line + "' is not 'wavelength<TAB>radiance'");
    wavelengths.push_back(wavelength);
    sample.radiance.push_back(value);
  }
  if (wavelengths.size() < 2) throw InputError(file.string() + ": fewer than two spectral samples");
  sample.firstWavelengthNm = wavelengths.front();
  sample.spacingNm = (wavelengths.back() - wavelengths.front()) / double(wavelengths.size() - 1);
  for (size_t i = 0; i < wavelengths.size(); ++i)
    if (std::abs(wavelengths[i] - (sample.firstWavelengthNm + double(i) * sample.spacingNm)) >
            1e-6 * sample.spacingNm ||
        !(sample.spacingNm > 0))
      throw InputError(file.string() + ": the wavelengths are not evenly spaced and increasing");
}

// Linear interpolation of a periodic function of azimuth given at sorted azimuths.
double ringValue(const std::vector<std::pair<double, double>>& ring, double azimuth) {
  const double twoPi = 2.0 * kPi;
  azimuth = std::fmod(azimuth, twoPi);
  if (azimuth < 0) azimuth += twoPi;
  auto upper = std::lower_bound(ring.begin(), ring.end(), std::make_pair(azimuth, -double(INFINITY)));
  const auto& b = upper == ring.end() ? ring.front() : *upper;
  const auto& a = upper == ring.begin() ? ring.back() : *(upper - 1);
  double span = b.first - a.first;
  double offset = azimuth - a.first;
  if (span <= 0) span += twoPi;
  if (offset < 0) offset += twoPi;
  return a.second + (b.second - a.second) * (offset / span);
}

}  // namespace

double KiderSample::radianceAt(double wavelengthNm) const {
  if (radiance.empty()) return 0.0;
  const double u = (wavelengthNm - firstWavelengthNm) / spacingNm;
  if (u <= 0) return radiance.front();
  if (u >= double(radiance.size() - 1)) return radiance.back();
  const size_t i = size_t(u);
  const double t = u - double(i);
  return radiance[i] * (1.0 - t) + radiance[i + 1] * t;
}

double kiderAzimuthFromFileDeg(double fileAzimuthDeg) {
  double a = std::fmod(360.0 - fileAzimuthDeg, 360.0);
  if (a < 0) a += 360.0;
  return a;
}

std::string kiderCaptureUtc(const std::string& captureName, double utcOffsetHours) {
  int year, month, day, hour, minute;
  double second;
  char tail;
  if (std::sscanf(captureName.c_str(), "%4d-%2d-%2d___%2d.%2d.%lf%c", &year, &month, &day, &hour, &minute, &second,
                  &tail) != 6)
    throw InputError("capture '" + captureName + "': the name is not YYYY-MM-DD___hh.mm.ss (local time)");
  char iso[64];
  std::snprintf(iso, sizeof(iso), "%04d-%02d-%02dT%02d:%02d:%06.3fZ", year, month, day, hour, minute, second);
  astro::UtcTime local = astro::parseUtc(iso);  // range checks
  return astro::formatUtc(astro::addSeconds(local, -utcOffsetHours * 3600.0));
}

std::vector<std::filesystem::path> findKiderCaptureFolders(const std::filesystem::path& dataDir) {
  namespace fs = std::filesystem;
  std::error_code ec;
  if (!fs::is_directory(dataDir, ec)) throw InputError(dataDir.string() + ": not a folder");
  const fs::path root = fs::is_directory(dataDir / "radiance", ec) ? dataDir / "radiance" : dataDir;
  std::set<fs::path> folders;
  for (const auto& entry : fs::recursive_directory_iterator(root, ec))
    if (entry.is_regular_file() && endsWith(entry.path().filename().string(), kSuffix))
      folders.insert(entry.path().parent_path());
  if (folders.empty())
    throw InputError(root.string() + ": no capture folder (a folder of *" + kSuffix + " files) found");
  return {folders.begin(), folders.end()};
}

KiderCapture readKiderCapture(const std::filesystem::path& folder, double utcOffsetHours) {
  KiderCapture capture;
  capture.name = folder.filename().string();
  capture.utc = kiderCaptureUtc(capture.name, utcOffsetHours);
  std::set<int> seen;
  for (const auto& entry : std::filesystem::directory_iterator(folder)) {
    if (!entry.is_regular_file() || !endsWith(entry.path().filename().string(), kSuffix)) continue;
    KiderSample sample;
    sample.file = entry.path();
    parseFileName(entry.path(), sample);
    if (!seen.insert(sample.index).second)
      throw InputError(folder.string() + ": sample index " + std::to_string(sample.index) + " appears twice");
    readSpectrum(entry.path(), sample);
    capture.samples.push_back(std::move(sample));
  }
  std::sort(capture.samples.begin(), capture.samples.end(),
            [](const KiderSample& a, const KiderSample& b) { return a.index < b.index; });
  for (const auto& s : capture.samples)
    if (s.radiance.size() != capture.samples.front().radiance.size() ||
        s.firstWavelengthNm != capture.samples.front().firstWavelengthNm)
      throw InputError(s.file.string() + ": its wavelengths differ from the capture's other files");
  return capture;
}

bool replaceKiderSampleZero(KiderCapture& capture) {
  auto find = [&](int index) -> KiderSample* {
    for (auto& s : capture.samples)
      if (s.index == index) return &s;
    return nullptr;
  };
  KiderSample *zero = find(0), *a = find(1), *b = find(31);
  if (!zero || !a || !b || a->radiance.size() != zero->radiance.size() || b->radiance.size() != zero->radiance.size())
    return false;
  for (size_t i = 0; i < zero->radiance.size(); ++i) zero->radiance[i] = 0.5 * (a->radiance[i] + b->radiance[i]);
  return true;
}

double mirrorAsymmetry(const std::vector<RingSample>& samples, double sunAzimuth) {
  std::map<long long, std::vector<std::pair<double, double>>> rings;  // elevation (µrad) -> (azimuth, value)
  for (const auto& s : samples) {
    double a = std::fmod(s.azimuth, 2.0 * kPi);
    if (a < 0) a += 2.0 * kPi;
    rings[std::llround(s.elevation * 1e6)].push_back({a, s.value});
  }
  double sum = 0.0;
  size_t count = 0;
  for (auto& [key, ring] : rings) {
    if (ring.size() < 3) continue;
    std::sort(ring.begin(), ring.end());
    for (const auto& [azimuth, value] : ring) {
      const double d = value - ringValue(ring, 2.0 * sunAzimuth - azimuth);
      sum += d * d;
      ++count;
    }
  }
  return count ? sum / double(count) : 0.0;
}

double minimiseOnAzimuthGrid(double computedAzimuth, double halfRange, double step,
                             const std::function<double(double)>& asymmetry) {
  const int n = int(std::floor(2.0 * halfRange / step + 1e-9));
  double best = computedAzimuth - halfRange, bestAsymmetry = INFINITY;
  for (int i = 0; i <= n; ++i) {
    const double azimuth = computedAzimuth - halfRange + i * step;
    const double a = asymmetry(azimuth);
    if (a < bestAsymmetry) bestAsymmetry = a, best = azimuth;
  }
  return best;
}

double refitSunAzimuthBySymmetry(const std::vector<RingSample>& samples, double computedAzimuth, double halfRange,
                                 double step) {
  return minimiseOnAzimuthGrid(computedAzimuth, halfRange, step,
                               [&](double azimuth) { return mirrorAsymmetry(samples, azimuth); });
}

}  // namespace firmament
