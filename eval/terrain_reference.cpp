#include "eval/terrain_reference.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <random>
#include <thread>

#include "atmosphere/atmosphere_spectra.h"
#include "atmosphere/reference_medium.h"
#include "atmosphere/reference_renderer.h"
#include "common/cloud_density.glsl"
#include "common/geometry.glsl"
#include "common/terrain_albedo.glsl"
#include "common/terrain_geometry.glsl"
#include "core/color.h"
#include "terrain/terrain_intersection.h"

namespace firmament {
namespace {

// The sun's angular radius (rad): 0.53 deg across (Allen's Astrophysical Quantities, 4th ed.: 959.6").
constexpr double kSunAngularRadius = 0.004653;

// The shading normal of the GPU cast (shaders/terrain/terrain_cast.glsl terrainSmoothNormal): the
// samples' central-difference gradients interpolated bilinearly.
glm::dvec2 vertexGradient(const terrain::HeightField& f, int i, int j) {
  const int i0 = std::max(i - 1, 0), i1 = std::min(i + 1, f.nx - 1);
  const int j0 = std::max(j - 1, 0), j1 = std::min(j + 1, f.ny - 1);
  return {(f.at(i1, j) - f.at(i0, j)) / ((i1 - i0) * f.dx), (f.at(i, j1) - f.at(i, j0)) / ((j1 - j0) * f.dy)};
}

glm::dvec3 smoothNormal(const terrain::HeightField& f, glm::dvec2 plane, double R) {
  const glm::dvec2 g((plane.x - f.x0) / f.dx, (plane.y - f.y0) / f.dy);
  const int i = std::clamp(int(std::floor(g.x)), 0, f.nx - 2);
  const int j = std::clamp(int(std::floor(g.y)), 0, f.ny - 2);
  const glm::dvec2 t = glm::clamp(g - glm::dvec2(i, j), 0.0, 1.0);
  const glm::dvec2 gradient =
      glm::mix(glm::mix(vertexGradient(f, i, j), vertexGradient(f, i + 1, j), t.x),
               glm::mix(vertexGradient(f, i, j + 1), vertexGradient(f, i + 1, j + 1), t.x), t.y);
  return shared::terrainSurfaceNormal(plane, f.sample(plane.x, plane.y), gradient, R);
}

void basis(glm::dvec3 n, glm::dvec3& a, glm::dvec3& b) {
  a = glm::normalize(glm::cross(std::abs(n.z) < 0.9 ? glm::dvec3(0, 0, 1) : glm::dvec3(1, 0, 0), n));
  b = glm::cross(n, a);
}

// The clear sky's radiance (three wavelengths) over the upper hemisphere of the camera's ground point,
// at two heights, from the atmosphere's CPU reference: a midpoint grid in zenith and azimuth,
// interpolated bilinearly (azimuth wraps, zenith clamps: directions under the horizon take the lowest
// band), linearly in height.
class SkyRadianceTable {
 public:
  SkyRadianceTable(const AtmosphereSettings& atmosphere, glm::dvec3 sun, double R, double h0, double h1,
                   const TerrainReferenceSettings& s, int threads)
      : nz_(s.skyTableZenith), na_(2 * s.skyTableZenith), h0_(h0), h1_(std::max(h1, h0 + 1.0)) {
    ReferenceQuality quality;
    quality.samplesPerPixel = s.skyTableSamples;
    quality.sunDisc = false;
    quality.threads = 1;
    const std::vector<double> wavelengths{kDefaultWavelengthsNm.x, kDefaultWavelengthsNm.y, kDefaultWavelengthsNm.z};
    const ReferenceRenderer renderer(reference::SpectralMedium::fromSettings(atmosphere, wavelengths), sun, quality);
    values_.assign(size_t(2 * nz_ * na_), glm::dvec3(0.0));
    std::atomic<int> next{0};
    auto work = [&] {
      for (int k = next++; k < 2 * nz_ * na_; k = next++) {
        const int level = k / (nz_ * na_), rest = k % (nz_ * na_), iz = rest / na_, ia = rest % na_;
        const double theta = (iz + 0.5) * 0.5 * shared::kPi / nz_, phi = (ia + 0.5) * 2.0 * shared::kPi / na_;
        const glm::dvec3 d(std::sin(theta) * std::sin(phi), std::sin(theta) * std::cos(phi), std::cos(theta));
        const double r = R + (level == 0 ? h0_ : h1_);
        const std::vector<double> l = renderer.radiance(glm::dvec3(0.0, 0.0, r), d, uint64_t(k)).total();
        values_[size_t(k)] = glm::dvec3(l[0], l[1], l[2]);
      }
    };
    std::vector<std::thread> pool;
    for (int t = 0; t < threads; ++t) pool.emplace_back(work);
    for (auto& t : pool) t.join();
  }

  glm::dvec3 operator()(glm::dvec3 d, double height) const {
    const double theta = std::acos(std::clamp(d.z, -1.0, 1.0));
    double phi = std::atan2(d.x, d.y);
    if (phi < 0.0) phi += 2.0 * shared::kPi;
    const double z = std::clamp(theta / (0.5 * shared::kPi) * nz_ - 0.5, 0.0, nz_ - 1.0);
    const double a = phi / (2.0 * shared::kPi) * na_ - 0.5;
    const int iz = std::min(int(z), nz_ - 2 < 0 ? 0 : nz_ - 2);
    const double fz = std::clamp(z - iz, 0.0, 1.0);
    const int ia = int(std::floor(a));
    const double fa = a - ia;
    const double w = std::clamp((height - h0_) / (h1_ - h0_), 0.0, 1.0);
    glm::dvec3 out(0.0);
    for (int level = 0; level < 2; ++level) {
      auto at = [&](int i, int j) {
        const int jj = ((j % na_) + na_) % na_;
        return values_[size_t(level * nz_ * na_ + std::min(i, nz_ - 1) * na_ + jj)];
      };
      const glm::dvec3 v = glm::mix(glm::mix(at(iz, ia), at(iz, ia + 1), fa),
                                    glm::mix(at(iz + 1, ia), at(iz + 1, ia + 1), fa), nz_ > 1 ? fz : 0.0);
      out += (level == 0 ? 1.0 - w : w) * v;
    }
    return out;
  }

 private:
  int nz_, na_;
  double h0_, h1_;
  std::vector<glm::dvec3> values_;
};

}  // namespace

double cloudOpticalDepthAlong(const CloudMedium& medium, glm::dvec3 p, glm::dvec3 direction, double step_m) {
  double r = 0.0, mu = 0.0;
  shared::rayRadiusAndCosine(p, direction, r, mu);
  double tau = 0.0;
  for (const shared::CloudLayer& l : medium.layers()) {
    glm::dvec2 a, b;
    shared::cloudShellSegments(r, mu, l.bottom_radius, l.top_radius, 1.0e7, a, b);
    for (glm::dvec2 s : {a, b}) {
      if (!(s.y > s.x)) continue;
      const int n = std::max(1, int(std::ceil((s.y - s.x) / step_m)));
      const double dt = (s.y - s.x) / n;
      for (int k = 0; k < n; ++k) tau += medium.extinction(p + direction * (s.x + (k + 0.5) * dt)) * dt;
    }
  }
  return tau;
}

TerrainReferenceImage renderTerrainReference(const Scene& scene, const SceneView& view,
                                             const terrain::ResolvedTerrain& terrain, const CloudMedium& medium,
                                             const CloudLightingSettings& lighting,
                                             const TerrainReferenceSettings& settings) {
  const auto start = std::chrono::steady_clock::now();
  const double R = view.atmosphere.bottomRadius;
  const terrain::HeightField& field = terrain.field;
  const terrain::TerrainIntersector walk(field, R);
  const glm::dvec3 sun = glm::normalize(view.sunDirection);
  const glm::dvec3 camera(0.0, 0.0, double(float(view.cameraRadius)));
  const int threads = settings.threads > 0 ? settings.threads : std::max(1, int(std::thread::hardware_concurrency()));
  TerrainReferenceImage out;
  out.width = view.camera.width;
  out.height = view.camera.height;
  out.pixels.resize(size_t(out.width) * size_t(out.height));

  // The view rays' hits first (pixelSide² per pixel): the sky table spans their heights.
  const int pixelSide = std::max(settings.pixelSide, 1);
  const size_t perPixel = size_t(pixelSide) * size_t(pixelSide);
  std::vector<terrain::TerrainHit> hits(out.pixels.size() * perPixel);
  double hMin = 1e30, hMax = -1e30;
  for (int y = 0; y < out.height; ++y)
    for (int x = 0; x < out.width; ++x)
      for (size_t j = 0; j < perPixel; ++j) {
        bool valid = false;
        const glm::dvec2 at(x + (double(j % size_t(pixelSide)) + 0.5) / pixelSide,
                            y + (double(j / size_t(pixelSide)) + 0.5) / pixelSide);
        const glm::dvec3 d = shared::cameraRayDirection(view.camera, at, valid);
        if (!valid) continue;
        terrain::TerrainRay ray;
        ray.origin = camera;
        ray.direction = d;
        terrain::TerrainHit& h = hits[(size_t(y) * size_t(out.width) + size_t(x)) * perPixel + j];
        h = walk.intersect(ray);
        if (h.hit) hMin = std::min(hMin, h.height), hMax = std::max(hMax, h.height);
      }
  if (hMin > hMax) hMin = hMax = 0.0;
  const SkyRadianceTable sky(view.atmosphere, sun, R, hMin, hMax, settings, threads);

  const bool clouds = !medium.layers().empty();
  CloudEnvironment environment;
  if (clouds) {
    double middle = 0.0;
    for (const auto& l : medium.layers())
      middle += 0.5 * (l.bottom_radius + l.top_radius) / double(medium.layers().size());
    environment = cloudEnvironmentFromReference(view.atmosphere, sun, middle);
    // Paths that leave the clouds downwards find a black ground: no ground-to-cloud bounce, as in the
    // fast path (the environment's ground is lit by the clear sun, several times what the ground under
    // a deck receives).
    environment.groundSun = environment.groundSky = glm::dvec3(0.0);
  }
  CloudReferenceSettings tracerSettings;
  tracerSettings.samplesPerPixel = 1;
  tracerSettings.seed = settings.seed;
  const CloudPathTracer tracer(medium, lighting, view.atmosphere, sun, environment, tracerSettings);
  const glm::dmat3 skyToRgb = threeWavelengthRadianceToRgb(kDefaultWavelengthsNm, kSkyLambdaPower);
  const glm::dmat3 sunToRgb = threeWavelengthRadianceToRgb(kDefaultWavelengthsNm, kSunLambdaPower);
  const shared::TerrainAlbedoParameters albedoParameters = terrain.settings.albedo;

  // Sun disc directions: stratified over the disc (a ring of sunDiscSamples - 1 around the centre).
  glm::dvec3 sa, sb;
  basis(sun, sa, sb);
  std::vector<glm::dvec3> disc;
  const int nDisc = std::max(settings.sunDiscSamples, 1);
  disc.push_back(sun);
  for (int k = 1; k < nDisc; ++k) {
    // Equal-area rings: the k-th of nDisc - 1 points at radius sqrt((k - 0.5) / (nDisc - 1)) of the
    // disc, golden-angle azimuths.
    const double rr = kSunAngularRadius * std::sqrt((k - 0.5) / (nDisc - 1));
    const double phi = 2.399963229728653 * k;
    disc.push_back(glm::normalize(sun + std::tan(rr) * (std::cos(phi) * sa + std::sin(phi) * sb)));
  }
  if (nDisc > 1) disc.erase(disc.begin());  // the centre stands in only for a single sample

  const int side =
      std::max(1, int(std::lround(std::sqrt(double(std::max(settings.skyDirections, 1)) / double(perPixel)))));
  const int nSky = side * side;
  std::atomic<size_t> next{0};
  auto work = [&] {
    for (size_t pixel = next++; pixel < out.pixels.size(); pixel = next++) {
      TerrainReferencePixel& px = out.pixels[pixel];
      TerrainReferencePixel sum;
      double errors2 = 0.0;
      int count = 0;
      for (size_t j = 0; j < perPixel; ++j) {
        // Sample i: the sub-pixel's (the pixel's own index for pixelSide 1).
        const size_t i = pixel * perPixel + j;
        const terrain::TerrainHit& h = hits[i];
        if (!h.hit) continue;
        if (count == 0 || h.t < px.t) px.t = h.t;
        ++count;
        px.hit = true;
        const glm::dvec3 p = h.position;
        const glm::dvec3 up = glm::normalize(p);
        glm::dvec3 n = h.normal;
        if (h.surface == terrain::TerrainSurface::Field) n = smoothNormal(field, h.plane, R);
        const glm::dvec3 origin = p + 0.01 * h.normal + 0.01 * up;
        auto blocked = [&](glm::dvec3 d) {
          terrain::TerrainRay ray;
          ray.origin = origin;
          ray.direction = d;
          ray.tMin = 0.02;
          return walk.intersect(ray).hit;
        };
        // The sun over its disc.
        double sunShare = 0.0, visibility = 0.0;
        for (const glm::dvec3& s : disc) {
          const double cosine = glm::dot(n, s);
          if (cosine <= 0.0 || blocked(s)) continue;
          const double transmittance =
              clouds ? std::exp(-cloudOpticalDepthAlong(medium, p, s, settings.cloudStep_m)) : 1.0;
          sunShare += cosine * transmittance / disc.size();
          visibility += transmittance / disc.size();
        }
        const glm::dvec3 sunRgb = sunToRgb * tracer.sunIrradianceAt(p) * (sunShare / shared::kPi);
        // The hemisphere, cosine-weighted about the shading normal, jittered strata.
        std::mt19937_64 random(settings.seed * 0x9E3779B97F4A7C15ull + i);
        std::uniform_real_distribution<double> unit(0.0, 1.0);
        glm::dvec3 na, nb;
        basis(n, na, nb);
        glm::dvec3 skySum(0.0);
        double sumY = 0.0, sumY2 = 0.0;
        int occluded = 0;
        for (int k = 0; k < nSky; ++k) {
          const double u1 = ((k / side) + unit(random)) / side, u2 = ((k % side) + unit(random)) / side;
          const double rr = std::sqrt(u1), phi = 2.0 * shared::kPi * u2;
          const glm::dvec3 d =
              glm::normalize(rr * std::cos(phi) * na + rr * std::sin(phi) * nb + std::sqrt(1.0 - u1) * n);
          glm::dvec3 l(0.0);
          if (blocked(d)) {
            ++occluded;
          } else {
            const glm::dvec3 clear = skyToRgb * sky(d, h.height);
            if (clouds) {
              const CloudPathTracer::PixelResult c = tracer.pixel(origin, d, i * uint64_t(nSky) + uint64_t(k));
              l = c.rgb + c.transmittance * clear;
            } else {
              l = clear;
            }
          }
          skySum += l;
          const double y = luminanceRec709(l.x, l.y, l.z);
          sumY += y, sumY2 += y * y;
        }
        const double slopeCosine = std::clamp(glm::dot(n, up), -1.0, 1.0);
        const glm::dvec3 albedo = shared::terrainAlbedo(h.height, slopeCosine, albedoParameters);
        const glm::dvec3 skyRgb = skySum / double(nSky);
        const double sunY = luminanceRec709(albedo.x * sunRgb.x, albedo.y * sunRgb.y, albedo.z * sunRgb.z);
        const double skyY = luminanceRec709(albedo.x * skyRgb.x, albedo.y * skyRgb.y, albedo.z * skyRgb.z);
        sum.sunLuminance += sunY;
        sum.skyLuminance += skyY;
        sum.sunVisibility += visibility;
        sum.skyOcclusion += double(occluded) / nSky;
        // The hemisphere's standard error, scaled by the albedo's luminance weight (grey enough).
        const double meanY = sumY / nSky;
        const double var = std::max(sumY2 / nSky - meanY * meanY, 0.0) / std::max(nSky - 1, 1);
        const double skyRgbY = luminanceRec709(skyRgb.x, skyRgb.y, skyRgb.z);
        const double error = std::sqrt(var) * (skyRgbY > 0.0 ? skyY / skyRgbY : 0.0);
        errors2 += error * error;
      }
      if (count == 0) continue;
      // The mean over the sub-pixels that see terrain (the ground's light where the pixel shows ground).
      px.sunLuminance = sum.sunLuminance / count;
      px.skyLuminance = sum.skyLuminance / count;
      px.luminance = px.sunLuminance + px.skyLuminance;
      px.sunVisibility = sum.sunVisibility / count;
      px.skyOcclusion = sum.skyOcclusion / count;
      px.standardError = std::sqrt(errors2) / count;
    }
  };
  std::vector<std::thread> pool;
  for (int t = 0; t < threads; ++t) pool.emplace_back(work);
  for (auto& t : pool) t.join();
  (void)scene;
  out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return out;
}

TerrainReferenceError compareWithTerrainReference(const Image& groundOnly, const std::vector<float>& depth,
                                                  const TerrainReferenceImage& reference) {
  TerrainReferenceError e;
  double sumD2 = 0.0, sumY2 = 0.0, sumSe2 = 0.0, sumA = 0.0, sumY = 0.0;
  double shadowA = 0.0, shadowY = 0.0, litA = 0.0, litY = 0.0;
  for (size_t i = 0; i < reference.pixels.size() && i < depth.size(); ++i) {
    const TerrainReferencePixel& r = reference.pixels[i];
    if (!r.hit || !(depth[i] < 1e29f) || std::abs(double(depth[i]) - r.t) > 0.01 * r.t + 1.0) continue;
    const double a = luminanceRec709(groundOnly.pixels.data() + 4 * i);
    const double y = r.luminance;
    sumD2 += (a - y) * (a - y), sumY2 += y * y, sumSe2 += r.standardError * r.standardError;
    sumA += a, sumY += y;
    ++e.pixels;
    if (r.sunVisibility < 0.5) {
      shadowA += a, shadowY += y;
      ++e.shadowPixels;
    } else {
      litA += a, litY += y;
    }
  }
  if (e.pixels == 0 || sumY2 <= 0.0) return e;
  e.relRmse = std::sqrt(sumD2 / sumY2);
  e.noiseFloor = std::sqrt(sumSe2 / sumY2);
  e.noiseCorrected = std::sqrt(std::max(sumD2 - sumSe2, 0.0) / std::max(sumY2 - sumSe2, 1e-30));
  e.meanBias = sumA / sumY - 1.0;
  e.shadowBias = shadowY > 0.0 ? shadowA / shadowY - 1.0 : 0.0;
  e.litBias = litY > 0.0 ? litA / litY - 1.0 : 0.0;
  e.meanTest = sumA / e.pixels;
  e.meanReference = sumY / e.pixels;
  return e;
}

}  // namespace firmament
