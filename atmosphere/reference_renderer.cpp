#include "atmosphere/reference_renderer.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <mutex>
#include <stdexcept>
#include <thread>

#include "atmosphere/reference_geometry.h"
#include "atmosphere/reference_path_tracer.h"
#include "atmosphere/reference_single_scattering.h"
#include "core/spectrum.h"

namespace firmament {

using reference::PathTracer;
using reference::SpectralMedium;

struct ReferenceRenderer::Engine {
  SpectralMedium medium;
  reference::SingleScatteringIntegrator singleScattering;
  PathTracer pathTracer;
  std::vector<glm::dvec3> xyzPerWavelength;  // column i: XYZ of a unit spectral radiance at wavelength i

  Engine(SpectralMedium m, glm::dvec3 sun, const ReferenceQuality& q)
      : medium(std::move(m)),
        singleScattering(medium, sun, q.quadratureTolerance),
        pathTracer(
            medium, sun,
            reference::PathTracerSettings{q.pathTolerance, q.maxBounces, q.rouletteStartBounce, q.forcedSegments}) {
    const std::vector<double>& w = medium.wavelengths();
    std::vector<double> unit(w.size(), 0.0);
    for (size_t i = 0; i < w.size(); ++i) {
      unit[i] = 1.0;
      xyzPerWavelength.push_back(spectrumToXyz(w, unit));
      unit[i] = 0.0;
    }
  }
};

namespace {

void checkQuality(const ReferenceQuality& q) {
  if (q.samplesPerPixel < 0) throw std::invalid_argument("ReferenceQuality: samplesPerPixel < 0");
  if (q.wavelengthCount < 1) throw std::invalid_argument("ReferenceQuality: wavelengthCount < 1");
  if (!(q.quadratureTolerance > 0.0) || !(q.pathTolerance > 0.0))
    throw std::invalid_argument("ReferenceQuality: tolerances must be > 0");
  if (q.maxBounces < 2) throw std::invalid_argument("ReferenceQuality: maxBounces < 2");
}

int threadCount(const ReferenceQuality& q) {
  if (q.threads > 0) return q.threads;
  return std::max(1u, std::thread::hardware_concurrency());
}

// Runs body(i) for i in [0, count) on `threads` threads (dynamic scheduling: the next free thread
// takes the next index), polls progress from the calling thread, and sums the path statistics.
void parallelFor(size_t count, int threads, const std::function<void(size_t)>& body,
                 const std::function<void(size_t, size_t)>& progress, PathTracer::PathStatistics* totals) {
  std::atomic<size_t> next{0}, done{0};
  std::mutex mutex;
  std::exception_ptr failure;
  auto worker = [&] {
    PathTracer::threadStatistics() = {};
    try {
      for (size_t i = next++; i < count; i = next++) {
        body(i);
        ++done;
      }
    } catch (...) {
      std::lock_guard<std::mutex> lock(mutex);
      if (!failure) failure = std::current_exception();
      next = count;
    }
    std::lock_guard<std::mutex> lock(mutex);
    const PathTracer::PathStatistics& s = PathTracer::threadStatistics();
    totals->paths += s.paths;
    totals->events += s.events;
    totals->rouletteKills += s.rouletteKills;
    totals->capped += s.capped;
    totals->longestPath = std::max(totals->longestPath, s.longestPath);
  };
  std::vector<std::thread> pool;
  const int n = int(std::min<size_t>(size_t(std::max(threads, 1)), std::max<size_t>(count, 1)));
  for (int t = 0; t < n; ++t) pool.emplace_back(worker);
  while (progress && done.load() < count && !failure) {
    progress(done.load(), count);
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
  }
  for (auto& t : pool) t.join();
  if (failure) std::rethrow_exception(failure);
  if (progress) progress(count, count);
}

}  // namespace

std::vector<double> ReferenceRadiance::total() const {
  std::vector<double> sum(sunDisc.size());
  for (size_t i = 0; i < sum.size(); ++i) sum[i] = sunDisc[i] + singleScattering[i] + multipleScattering[i];
  return sum;
}

ReferenceRenderer::ReferenceRenderer(const AtmosphereSettings& settings, glm::dvec3 sunDirection,
                                     const ReferenceQuality& quality)
    : ReferenceRenderer(SpectralMedium::fromSettings(
                            settings, reference::evenlySpacedWavelengths(std::max(quality.wavelengthCount, 1))),
                        sunDirection, quality) {}

ReferenceRenderer::ReferenceRenderer(SpectralMedium medium, glm::dvec3 sunDirection, const ReferenceQuality& quality)
    : quality_(quality), sun_(glm::normalize(sunDirection)) {
  checkQuality(quality);
  if (!(glm::length(sunDirection) > 0.0)) throw std::invalid_argument("ReferenceRenderer: zero sun direction");
  quality_.wavelengthCount = medium.wavelengthCount();
  engine_ = std::make_unique<Engine>(std::move(medium), sun_, quality_);
}

ReferenceRenderer::~ReferenceRenderer() = default;

const SpectralMedium& ReferenceRenderer::medium() const { return engine_->medium; }
const std::vector<double>& ReferenceRenderer::wavelengths() const { return engine_->medium.wavelengths(); }

glm::dvec3 ReferenceRenderer::toXyz(const std::vector<double>& spectralRadiance) const {
  glm::dvec3 xyz(0.0);
  for (size_t i = 0; i < spectralRadiance.size(); ++i) xyz += spectralRadiance[i] * engine_->xyzPerWavelength[i];
  return xyz;
}

ReferenceRadiance ReferenceRenderer::radiance(glm::dvec3 camera, glm::dvec3 direction, uint64_t stream) const {
  const Engine& e = *engine_;
  const size_t n = size_t(e.medium.wavelengthCount());
  const reference::ViewSegment view = reference::viewSegment(e.medium, camera, direction);
  const reference::DeterministicRadiance deterministic =
      e.singleScattering.integrate(view, quality_.sunDisc, quality_.singleScattering);

  ReferenceRadiance result;
  result.sunDisc = deterministic.sunDisc;
  result.singleScattering = deterministic.singleScattering;
  result.multipleScattering.assign(n, 0.0);
  result.multipleScatteringStandardError.assign(n, 0.0);

  if (quality_.multipleScattering && quality_.samplesPerPixel > 0 && view.inAtmosphere) {
    // Mean and standard error of the mean from the sums over m independent samples:
    // SE^2 = (Σ x² / m - mean²) / (m - 1), per wavelength and for the luminance.
    const reference::PreparedViewRay ray = e.pathTracer.prepare(view);
    reference::Random random(quality_.seed, stream);
    std::vector<double> contribution, sum(n, 0.0), sumSquares(n, 0.0);
    double sumY = 0.0, sumSquaresY = 0.0;
    const int m = quality_.samplesPerPixel;
    for (int s = 0; s < m; ++s) {
      e.pathTracer.sample(ray, random, contribution);
      double y = 0.0;
      for (size_t i = 0; i < n; ++i) {
        sum[i] += contribution[i];
        sumSquares[i] += contribution[i] * contribution[i];
        y += contribution[i] * e.xyzPerWavelength[i].y;
      }
      sumY += y;
      sumSquaresY += y * y;
    }
    auto standardError = [m](double s, double s2) {
      if (m < 2) return 0.0;
      const double mean = s / m;
      return std::sqrt(std::max(0.0, s2 / m - mean * mean) / double(m - 1));
    };
    for (size_t i = 0; i < n; ++i) {
      result.multipleScattering[i] = sum[i] / m;
      result.multipleScatteringStandardError[i] = standardError(sum[i], sumSquares[i]);
    }
    result.luminanceStandardError = standardError(sumY, sumSquaresY);
    result.samples = m;
  }
  result.xyz = toXyz(result.total());
  result.rgb = xyzToLinearRec709(result.xyz);
  return result;
}

ReferenceImage renderReferenceImage(const ReferenceRenderer& renderer, double cameraRadius,
                                    const shared::CameraParameters& camera,
                                    const std::function<void(size_t, size_t)>& progress) {
  if (camera.width < 1 || camera.height < 1) throw std::invalid_argument("renderReferenceImage: empty image");
  const auto start = std::chrono::steady_clock::now();
  ReferenceImage result;
  result.image = Image(camera.width, camera.height, 4);
  const size_t count = result.image.pixelCount();
  result.luminance.assign(count, 0.0);
  result.luminanceStandardError.assign(count, 0.0);
  const glm::dvec3 position(0.0, 0.0, cameraRadius);
  result.threads = threadCount(renderer.quality());
  PathTracer::PathStatistics totals;
  parallelFor(
      count, result.threads,
      [&](size_t index) {
        const int x = int(index % size_t(camera.width)), y = int(index / size_t(camera.width));
        bool valid = true;
        const glm::dvec3 direction =
            shared::cameraRayDirection(camera, glm::dvec2(double(x) + 0.5, double(y) + 0.5), valid);
        float* pixel = result.image.at(x, y);
        pixel[3] = 1.0f;
        if (!valid) {  // outside a fisheye's circle: black, as on the GPU
          pixel[0] = pixel[1] = pixel[2] = 0.0f;
          return;
        }
        const ReferenceRadiance r = renderer.radiance(position, direction, uint64_t(index));
        for (int c = 0; c < 3; ++c) pixel[c] = float(std::max(r.rgb[c], 0.0));
        result.luminance[index] = r.luminance();
        result.luminanceStandardError[index] = r.luminanceStandardError;
      },
      progress, &totals);

  std::vector<double> relative;
  for (size_t i = 0; i < count; ++i)
    if (result.luminance[i] > 0.0) relative.push_back(result.luminanceStandardError[i] / result.luminance[i]);
  if (!relative.empty()) {
    std::sort(relative.begin(), relative.end());
    result.medianRelativeError = relative[relative.size() / 2];
    result.p95RelativeError = relative[std::min(relative.size() - 1, size_t(0.95 * double(relative.size())))];
    result.maxRelativeError = relative.back();
    double sumSquares = 0.0;
    for (double v : relative) sumSquares += v * v;
    result.rmsRelativeError = std::sqrt(sumSquares / double(relative.size()));
  }
  result.paths = totals.paths;
  result.events = totals.events;
  result.rouletteKills = totals.rouletteKills;
  result.cappedPaths = totals.capped;
  result.longestPath = totals.longestPath;
  result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return result;
}

std::vector<ReferenceRadiance> renderReferenceDirections(const ReferenceRenderer& renderer, double cameraRadius,
                                                         const std::vector<ViewDirection>& directions) {
  std::vector<ReferenceRadiance> results(directions.size());
  const glm::dvec3 position(0.0, 0.0, cameraRadius);
  PathTracer::PathStatistics totals;
  parallelFor(
      directions.size(), threadCount(renderer.quality()),
      [&](size_t k) {
        results[k] = renderer.radiance(
            position, reference::enuFromZenithAzimuth(directions[k].zenith, directions[k].azimuth), uint64_t(k));
      },
      {}, &totals);
  return results;
}

}  // namespace firmament
