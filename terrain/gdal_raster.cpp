#include "terrain/gdal_raster.h"

#include <cpl_conv.h>
#include <cpl_error.h>
#include <gdal.h>
#include <gdal_priv.h>
#include <ogr_spatialref.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <mutex>
#include <sstream>

#include "core/error.h"
#include "terrain/terrain_settings.h"

namespace firmament::terrain {
namespace fs = std::filesystem;

namespace {

constexpr double kDegree = 3.14159265358979323846 / 180.0;

void registerGdal() {
  static std::once_flag once;
  std::call_once(once, [] { GDALAllRegister(); });
}

// GDAL reports through a global handler; while we call it, messages are kept for our own errors.
struct QuietGdal {
  QuietGdal() {
    CPLPushErrorHandler(CPLQuietErrorHandler);
    CPLErrorReset();
  }
  ~QuietGdal() { CPLPopErrorHandler(); }
  static std::string last() {
    const char* m = CPLGetLastErrorMsg();
    return m && *m ? std::string(m) : std::string("no reason given");
  }
};

std::string number(double v, int precision = 10) {
  std::ostringstream s;
  s.precision(precision);
  s << v;
  return s.str();
}

struct DatasetCloser {
  void operator()(GDALDataset* d) const { GDALClose(GDALDataset::ToHandle(d)); }
};

}  // namespace

GdalRaster readGdalRaster(const fs::path& file) {
  registerGdal();
  const std::string name = file.string();
  std::error_code ec;
  if (!fs::exists(file, ec)) throw InputError("'" + name + "': no such raster file");
  if (fs::is_directory(file, ec)) throw InputError("'" + name + "': is a folder, expected a raster file");
  QuietGdal quiet;
  std::unique_ptr<GDALDataset, DatasetCloser> dataset(
      GDALDataset::FromHandle(GDALOpenEx(name.c_str(), GDAL_OF_RASTER | GDAL_OF_READONLY, nullptr, nullptr, nullptr)));
  if (!dataset) throw InputError("'" + name + "': not a raster GDAL reads (GDAL: " + QuietGdal::last() + ")");
  if (dataset->GetRasterCount() < 1) throw InputError("'" + name + "': the raster has no band");
  GdalRaster r;
  r.file = name;
  r.driver = dataset->GetDriver() ? dataset->GetDriver()->GetDescription() : "?";
  r.width = dataset->GetRasterXSize();
  r.height = dataset->GetRasterYSize();
  if (r.width < 2 || r.height < 2 || int64_t(r.width) * r.height > int64_t(1) << 28)
    throw InputError("'" + name + "': a raster of " + std::to_string(r.width) + " x " + std::to_string(r.height) +
                     " pixels; allowed: at least 2 x 2 and at most 2^28 pixels");
  double gt[6];
  if (dataset->GetGeoTransform(gt) != CE_None)
    throw InputError("'" + name + "': no georeference: the raster has no geotransform (GDAL " + r.driver +
                     "); a terrain raster must say where its pixels are");
  std::copy(gt, gt + 6, r.geoTransform.begin());
  const OGRSpatialReference* srs = dataset->GetSpatialRef();
  if (!srs || srs->IsEmpty())
    throw InputError("'" + name + "': no georeference: the raster has no coordinate system (GDAL " + r.driver +
                     "); a terrain raster must say in which system its geotransform is");
  r.srsName = srs->GetName() ? srs->GetName() : "?";
  char* wkt = nullptr;
  const char* options[] = {"FORMAT=WKT2", nullptr};
  if (srs->exportToWkt(&wkt, options) == OGRERR_NONE && wkt) r.srsWkt = wkt;
  CPLFree(wkt);

  GDALRasterBand* band = dataset->GetRasterBand(1);
  r.dataType = GDALGetDataTypeName(band->GetRasterDataType());
  int hasNodata = 0;
  r.nodata = band->GetNoDataValue(&hasNodata);
  r.hasNodata = hasNodata != 0;
  r.values.resize(size_t(r.width) * size_t(r.height));
  if (band->RasterIO(GF_Read, 0, 0, r.width, r.height, r.values.data(), r.width, r.height, GDT_Float32, 0, 0,
                     nullptr) != CE_None)
    throw InputError("'" + name + "': cannot read its pixels (GDAL: " + QuietGdal::last() + ")");
  r.valid.assign(r.values.size(), 1);
  // The nodata value compared as the band stores it, rounded to float as the values were.
  const float nodata = float(r.nodata);
  r.minimum = std::numeric_limits<double>::infinity();
  r.maximum = -std::numeric_limits<double>::infinity();
  for (size_t k = 0; k < r.values.size(); ++k) {
    const float v = r.values[k];
    if (std::isnan(v) || (r.hasNodata && (v == nodata || (std::isnan(nodata) && std::isnan(v))))) {
      r.valid[k] = 0;
      continue;
    }
    if (!std::isfinite(v) || v < kLowestHeight_m || v > kHighestHeight_m)
      throw InputError("'" + name + "': height " + number(v) + " at pixel (column " +
                       std::to_string(k % size_t(r.width)) + ", row " + std::to_string(k / size_t(r.width)) +
                       ") is absurd; allowed: [" + number(kLowestHeight_m) + ", " + number(kHighestHeight_m) +
                       "] m above sea level (Challenger Deep to above Everest). Is the raster in feet or "
                       "centimetres, or is its nodata value " +
                       (r.hasNodata ? "(" + number(r.nodata) + ") not the one it uses" : std::string("undeclared")) +
                       "?");
    r.minimum = std::min(r.minimum, double(v));
    r.maximum = std::max(r.maximum, double(v));
    ++r.validCount;
  }
  if (r.validCount == 0)
    throw InputError("'" + name + "': every pixel is nodata" +
                     (r.hasNodata ? " (" + number(r.nodata) + ")" : std::string()));
  return r;
}

struct GdalPlacement::Impl {
  OGRSpatialReference wgs84;
  OGRSpatialReference rasterSrs;
  std::unique_ptr<OGRCoordinateTransformation> toRaster;
  std::unique_ptr<OGRCoordinateTransformation> fromRaster;
  double inverse[6];
  std::mutex mutex;  // OGR transformations are not re-entrant
};

GdalPlacement::GdalPlacement(const GdalRaster& raster, const TerrainFrame& frame)
    : raster_(&raster), frame_(&frame), impl_(std::make_unique<Impl>()) {
  registerGdal();
  QuietGdal quiet;
  impl_->wgs84.SetWellKnownGeogCS("WGS84");
  impl_->wgs84.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);  // x = longitude, y = latitude
  if (impl_->rasterSrs.importFromWkt(raster.srsWkt.c_str()) != OGRERR_NONE)
    throw InputError("'" + raster.file + "': no georeference: its coordinate system cannot be read back (" +
                     QuietGdal::last() + ")");
  impl_->rasterSrs.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
  impl_->toRaster.reset(OGRCreateCoordinateTransformation(&impl_->wgs84, &impl_->rasterSrs));
  impl_->fromRaster.reset(OGRCreateCoordinateTransformation(&impl_->rasterSrs, &impl_->wgs84));
  if (!impl_->toRaster || !impl_->fromRaster)
    throw InputError("'" + raster.file + "': no georeference: no transformation from WGS 84 to its coordinate system " +
                     raster.srsName + " (" + QuietGdal::last() + ")");
  if (!GDALInvGeoTransform(const_cast<double*>(raster.geoTransform.data()), impl_->inverse))
    throw InputError("'" + raster.file + "': no georeference: its geotransform is singular");
}

GdalPlacement::~GdalPlacement() = default;

glm::dvec2 GdalPlacement::pixelOfPlane(glm::dvec2 plane) const {
  const glm::dvec2 ll = frame_->planeToGeodetic(plane);
  double x = ll.y / kDegree, y = ll.x / kDegree;
  {
    std::lock_guard<std::mutex> lock(impl_->mutex);
    if (!impl_->toRaster->Transform(1, &x, &y)) return glm::dvec2(std::numeric_limits<double>::quiet_NaN());
  }
  const double* g = impl_->inverse;
  return {g[0] + x * g[1] + y * g[2], g[3] + x * g[4] + y * g[5]};
}

glm::dvec2 GdalPlacement::planeOfPixel(glm::dvec2 pixel) const {
  const auto& g = raster_->geoTransform;
  double x = g[0] + pixel.x * g[1] + pixel.y * g[2];
  double y = g[3] + pixel.x * g[4] + pixel.y * g[5];
  {
    std::lock_guard<std::mutex> lock(impl_->mutex);
    if (!impl_->fromRaster->Transform(1, &x, &y)) return glm::dvec2(std::numeric_limits<double>::quiet_NaN());
  }
  return frame_->geodeticToPlane({y * kDegree, x * kDegree});
}

namespace {
double bilinearWithNodata(const GdalRaster& r, glm::dvec2 pixel) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  if (!(pixel.x >= 0.0 && pixel.x <= r.width && pixel.y >= 0.0 && pixel.y <= r.height)) return nan;
  // Pixel centres at +0.5; the rim beyond the outer centres reads the edge pixels.
  const double u = std::clamp(pixel.x - 0.5, 0.0, double(r.width - 1));
  const double v = std::clamp(pixel.y - 0.5, 0.0, double(r.height - 1));
  const int i = std::min(int(std::floor(u)), r.width - 2), j = std::min(int(std::floor(v)), r.height - 2);
  const double fx = u - i, fy = v - j;
  double sum = 0.0, weight = 0.0;
  for (int dj = 0; dj < 2; ++dj)
    for (int di = 0; di < 2; ++di) {
      const size_t k = size_t(j + dj) * size_t(r.width) + size_t(i + di);
      const double w = (di ? fx : 1.0 - fx) * (dj ? fy : 1.0 - fy);
      if (!r.valid[k] || w <= 0.0) continue;
      sum += w * r.values[k];
      weight += w;
    }
  return weight > 0.0 ? sum / weight : nan;
}
}  // namespace

double GdalPlacement::heightAt(glm::dvec2 plane) const { return bilinearWithNodata(*raster_, pixelOfPlane(plane)); }

HeightField GdalPlacement::resample(const TileRegion& region) const {
  HeightField out(region.nx, region.ny, region.x0, region.y0, region.dx, region.dy);
  std::vector<double> xs(size_t(region.nx)), ys(size_t(region.nx));
  std::vector<int> ok(size_t(region.nx));
  for (int j = 0; j < region.ny; ++j) {
    for (int i = 0; i < region.nx; ++i) {
      const glm::dvec2 ll = frame_->planeToGeodetic({out.xAt(i), out.yAt(j)});
      xs[size_t(i)] = ll.y / kDegree;
      ys[size_t(i)] = ll.x / kDegree;
    }
    {
      std::lock_guard<std::mutex> lock(impl_->mutex);
      impl_->toRaster->Transform(region.nx, xs.data(), ys.data(), nullptr, ok.data());
    }
    const double* g = impl_->inverse;
    for (int i = 0; i < region.nx; ++i) {
      double h = std::numeric_limits<double>::quiet_NaN();
      if (ok[size_t(i)]) {
        const double x = xs[size_t(i)], y = ys[size_t(i)];
        h = bilinearWithNodata(*raster_, {g[0] + x * g[1] + y * g[2], g[3] + x * g[4] + y * g[5]});
      }
      out.at(i, j) = float(h);
    }
  }
  out.source = "GDAL raster " + raster_->file + " (" + raster_->driver + ", " + raster_->srsName + ")";
  return out;
}

void GdalPlacement::checkCoversLocation(const std::string& sceneSource) const {
  const glm::dvec2 pixel = pixelOfPlane({0.0, 0.0});
  if (pixel.x >= 0.0 && pixel.x <= raster_->width && pixel.y >= 0.0 && pixel.y <= raster_->height) return;
  // The raster's corners in latitude and longitude, for the message.
  double lat[4], lon[4];
  const double cx[4] = {0.0, double(raster_->width), 0.0, double(raster_->width)};
  const double cy[4] = {0.0, 0.0, double(raster_->height), double(raster_->height)};
  std::string corners;
  for (int k = 0; k < 4; ++k) {
    const auto& g = raster_->geoTransform;
    double x = g[0] + cx[k] * g[1] + cy[k] * g[2], y = g[3] + cx[k] * g[4] + cy[k] * g[5];
    {
      std::lock_guard<std::mutex> lock(impl_->mutex);
      impl_->fromRaster->Transform(1, &x, &y);
    }
    lon[k] = x;
    lat[k] = y;
  }
  const double latMin = *std::min_element(lat, lat + 4), latMax = *std::max_element(lat, lat + 4);
  const double lonMin = *std::min_element(lon, lon + 4), lonMax = *std::max_element(lon, lon + 4);
  corners = "latitude " + number(latMin, 8) + " to " + number(latMax, 8) + ", longitude " + number(lonMin, 8) + " to " +
            number(lonMax, 8);
  const auto& loc = frame_->location();
  throw InputError(sceneSource + ": /terrain/file: the raster '" + raster_->file +
                   "' does not cover the scene: it spans " + corners + " (degrees); the scene's location is latitude " +
                   number(loc.latitude / kDegree, 8) + ", longitude " + number(loc.longitude / kDegree, 8) +
                   " (/location). Move the location onto the raster or use a raster that covers it");
}

std::array<double, 4> GdalPlacement::planeBounds() const {
  std::array<double, 4> b = {std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity(),
                             -std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity()};
  const int n = 64;
  for (int side = 0; side < 4; ++side)
    for (int k = 0; k <= n; ++k) {
      const double s = double(k) / n;
      glm::dvec2 pixel = side == 0   ? glm::dvec2(s * raster_->width, 0.0)
                         : side == 1 ? glm::dvec2(s * raster_->width, double(raster_->height))
                         : side == 2 ? glm::dvec2(0.0, s * raster_->height)
                                     : glm::dvec2(double(raster_->width), s * raster_->height);
      const glm::dvec2 p = planeOfPixel(pixel);
      if (!(p.x == p.x)) continue;
      b[0] = std::min(b[0], p.x);
      b[1] = std::min(b[1], p.y);
      b[2] = std::max(b[2], p.x);
      b[3] = std::max(b[3], p.y);
    }
  return b;
}

void writeGdalGeoTiff(const fs::path& file, int width, int height, const std::vector<float>& values,
                      const std::array<double, 6>& geoTransform, const std::string& srs, const double* nodata) {
  registerGdal();
  QuietGdal quiet;
  GDALDriver* driver = GetGDALDriverManager()->GetDriverByName("GTiff");
  if (!driver) throw RuntimeError("GDAL has no GTiff driver");
  std::unique_ptr<GDALDataset, DatasetCloser> dataset(
      driver->Create(file.c_str(), width, height, 1, GDT_Float32, nullptr));
  if (!dataset) throw RuntimeError("cannot create '" + file.string() + "': " + QuietGdal::last());
  double gt[6];
  std::copy(geoTransform.begin(), geoTransform.end(), gt);
  dataset->SetGeoTransform(gt);
  if (!srs.empty()) {
    OGRSpatialReference reference;
    if (reference.SetFromUserInput(srs.c_str()) != OGRERR_NONE)
      throw RuntimeError("cannot read the coordinate system '" + srs + "': " + QuietGdal::last());
    dataset->SetSpatialRef(&reference);
  }
  GDALRasterBand* band = dataset->GetRasterBand(1);
  if (nodata) band->SetNoDataValue(*nodata);
  if (band->RasterIO(GF_Write, 0, 0, width, height, const_cast<float*>(values.data()), width, height, GDT_Float32, 0, 0,
                     nullptr) != CE_None)
    throw RuntimeError("cannot write '" + file.string() + "': " + QuietGdal::last());
}

}  // namespace firmament::terrain
