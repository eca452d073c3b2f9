#include "eval/cloud_field_statistics.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <numeric>
#include <thread>

#include "core/error.h"

namespace firmament {

CloudColumnField sampleCloudColumns(const CloudMedium& medium, const CloudVolumeRegion& region, double dz_m,
                                    double topExtinction_m, int threads) {
  validateCloudVolumeRegion(region);
  if (!(dz_m > 0.0)) throw InputError("sampleCloudColumns: the vertical step must be positive");
  CloudColumnField field;
  field.pixel_m = region.voxelSize_m;
  field.west_m = region.west_m;
  field.south_m = region.south_m;
  field.width = std::max(1, int(std::ceil((region.east_m - region.west_m) / region.voxelSize_m - 1e-9)));
  field.height = std::max(1, int(std::ceil((region.north_m - region.south_m) / region.voxelSize_m - 1e-9)));
  field.opticalDepth.assign(size_t(field.width) * field.height, 0.0f);
  field.top_m.assign(field.opticalDepth.size(), 0.0f);
  // Midpoint rule: n equal steps h <= dz over [bottom, top], τ = Σ σ(z_k) h at z_k = bottom + (k + 1/2) h.
  const int steps = std::max(1, int(std::ceil((region.top_m - region.bottom_m) / dz_m - 1e-9)));
  const double h = (region.top_m - region.bottom_m) / steps;
  const int workers =
      std::max(1, std::min(threads > 0 ? threads : int(std::thread::hardware_concurrency()), field.height));
  std::atomic<int> nextRow{0};
  std::vector<double> rowCoverage(field.height, 0.0);
  auto work = [&] {
    for (int j = nextRow++; j < field.height; j = nextRow++) {
      const double y = field.south_m + (j + 0.5) * field.pixel_m;
      for (int i = 0; i < field.width; ++i) {
        const double x = field.west_m + (i + 0.5) * field.pixel_m;
        double cover = 0.0;
        for (size_t l = 0; l < medium.layers().size(); ++l) {
          const double base = medium.layers()[l].bottom_radius - medium.groundRadius() + 1.0;
          cover = std::max(cover, medium.mapCoverage(l, cloudFrameFromLocalEnu({x, y, base}, medium.groundRadius())));
        }
        rowCoverage[j] += cover;
        double tau = 0.0, top = 0.0;
        for (int k = 0; k < steps; ++k) {
          const double z = region.bottom_m + (k + 0.5) * h;
          const double sigma = medium.extinction(cloudFrameFromLocalEnu({x, y, z}, medium.groundRadius()));
          tau += sigma * h;
          if (sigma > topExtinction_m) top = z;
        }
        const size_t p = size_t(j) * field.width + i;
        field.opticalDepth[p] = float(tau);
        field.top_m[p] = float(top);
      }
    }
  };
  std::vector<std::thread> pool;
  for (int t = 1; t < workers; ++t) pool.emplace_back(work);
  work();
  for (auto& t : pool) t.join();
  for (double c : rowCoverage) field.mapCoverage += c;
  field.mapCoverage /= double(field.opticalDepth.size());
  return field;
}

std::vector<CloudObject> findClouds(const std::vector<uint8_t>& mask, int width, int height, double pixel_m,
                                    const std::vector<float>& top_m) {
  if (width <= 0 || height <= 0 || mask.size() != size_t(width) * height)
    throw InputError("findClouds: the mask holds " + std::to_string(mask.size()) + " pixels, not " +
                     std::to_string(width) + " x " + std::to_string(height));
  std::vector<int> label(mask.size(), -1);
  std::vector<CloudObject> objects;
  std::vector<size_t> stack;
  for (size_t start = 0; start < mask.size(); ++start) {
    if (!mask[start] || label[start] >= 0) continue;
    const int id = int(objects.size());
    CloudObject cloud;
    long pixels = 0, edges = 0;
    stack.assign(1, start);
    label[start] = id;
    // Flood fill over the 4 neighbours; each of a pixel's 4 sides that borders a non-cloud pixel (or the
    // grid's edge) is one pixel length of perimeter.
    while (!stack.empty()) {
      const size_t p = stack.back();
      stack.pop_back();
      ++pixels;
      const int i = int(p % width), j = int(p / width);
      if (!top_m.empty()) cloud.top_m = std::max(cloud.top_m, double(top_m[p]));
      if (i == 0 || j == 0 || i == width - 1 || j == height - 1) cloud.touchesEdge = true;
      const int di[4] = {1, -1, 0, 0}, dj[4] = {0, 0, 1, -1};
      for (int n = 0; n < 4; ++n) {
        const int a = i + di[n], b = j + dj[n];
        if (a < 0 || b < 0 || a >= width || b >= height) {
          ++edges;
          continue;
        }
        const size_t q = size_t(b) * width + a;
        if (!mask[q]) {
          ++edges;
        } else if (label[q] < 0) {
          label[q] = id;
          stack.push_back(q);
        }
      }
    }
    cloud.area_m2 = double(pixels) * pixel_m * pixel_m;
    cloud.perimeter_m = double(edges) * pixel_m;
    cloud.size_m = std::sqrt(cloud.area_m2);
    objects.push_back(cloud);
  }
  std::sort(objects.begin(), objects.end(),
            [](const CloudObject& a, const CloudObject& b) { return a.area_m2 > b.area_m2; });
  return objects;
}

CloudFieldStatistics cloudObjectStatistics(std::vector<CloudObject> objects, double pixel_m,
                                           const CloudFieldStatisticsOptions& options) {
  CloudFieldStatistics s;
  std::sort(objects.begin(), objects.end(),
            [](const CloudObject& a, const CloudObject& b) { return a.area_m2 > b.area_m2; });
  s.clouds = int(objects.size());
  if (!objects.empty()) {
    s.largestArea_m2 = objects.front().area_m2;
    s.largestSize_m = objects.front().size_m;
  }
  const double pixelArea = pixel_m * pixel_m;

  // D: least squares of ln P on ln A, slope D / 2 (Lovejoy 1982, fig. 2).
  std::vector<double> x, y;
  for (const CloudObject& c : objects)
    if (!c.touchesEdge && c.area_m2 >= options.minPixelsForDimension * pixelArea - 1e-9) {
      x.push_back(std::log(c.area_m2));
      y.push_back(std::log(c.perimeter_m));
    }
  s.cloudsInDimensionFit = int(x.size());
  if (x.size() >= 3) {
    const double n = double(x.size());
    const double mx = std::accumulate(x.begin(), x.end(), 0.0) / n, my = std::accumulate(y.begin(), y.end(), 0.0) / n;
    double sxx = 0.0, sxy = 0.0;
    for (size_t k = 0; k < x.size(); ++k) sxx += (x[k] - mx) * (x[k] - mx), sxy += (x[k] - mx) * (y[k] - my);
    if (sxx > 0.0) {
      const double slope = sxy / sxx, intercept = my - slope * mx;
      double residual = 0.0;
      for (size_t k = 0; k < x.size(); ++k) residual += std::pow(y[k] - intercept - slope * x[k], 2.0);
      s.fractalDimension = 2.0 * slope;
      s.fractalDimensionError = 2.0 * std::sqrt(residual / std::max(n - 2.0, 1.0) / sxx);
    }
  }

  // β: the continuous power law's maximum-likelihood exponent above L_min (Clauset et al. 2009, eq. 3.1),
  // β = 1 + n / Σ ln(L_i / L_min), standard error (β - 1) / sqrt(n).
  s.sizeFitMin_m = std::sqrt(double(options.minPixelsForSizes)) * pixel_m;
  double logSum = 0.0;
  int n = 0;
  for (const CloudObject& c : objects)
    if (!c.touchesEdge && c.size_m >= s.sizeFitMin_m - 1e-9) {
      logSum += std::log(c.size_m / s.sizeFitMin_m);
      ++n;
    }
  s.cloudsInSizeFit = n;
  if (n >= 3 && logSum > 0.0) {
    s.sizeExponent = 1.0 + n / logSum;
    s.sizeExponentError = (s.sizeExponent - 1.0) / std::sqrt(double(n));
  }
  s.objects = std::move(objects);
  return s;
}

CloudFieldStatistics analyzeCloudField(const CloudColumnField& field, const CloudFieldStatisticsOptions& options) {
  const size_t count = size_t(field.width) * field.height;
  if (field.opticalDepth.size() != count)
    throw InputError("analyzeCloudField: the field holds " + std::to_string(field.opticalDepth.size()) +
                     " optical depths, not " + std::to_string(field.width) + " x " + std::to_string(field.height));
  std::vector<uint8_t> mask(count);
  std::vector<float> tops;
  size_t cloudy = 0;
  for (size_t p = 0; p < count; ++p) {
    mask[p] = field.opticalDepth[p] > options.opticalDepthThreshold ? 1 : 0;
    if (mask[p]) {
      ++cloudy;
      if (!field.top_m.empty()) tops.push_back(field.top_m[p]);
    }
  }
  CloudFieldStatistics s = cloudObjectStatistics(
      findClouds(mask, field.width, field.height, field.pixel_m, field.top_m), field.pixel_m, options);
  s.cloudFraction = count ? double(cloudy) / double(count) : 0.0;
  if (!tops.empty()) {
    std::sort(tops.begin(), tops.end());
    s.meanTop_m = std::accumulate(tops.begin(), tops.end(), 0.0) / double(tops.size());
    s.p90Top_m = tops[std::min(tops.size() - 1, size_t(0.9 * double(tops.size())))];
    s.maxTop_m = tops.back();
  }
  return s;
}

}  // namespace firmament
