#pragma once
// Statistics of a cloud field seen from above, the measures that observations of real cloud fields use
// (docs/clouds/shapes.md): the field's vertical optical depth on a grid of columns, thresholded into
// cloud and clear, cut into clouds (4-connected pixels), and then
//   - the cloud fraction and the number of clouds;
//   - the area-perimeter fractal dimension D: P ∝ A^(D/2) over the clouds (Lovejoy 1982, Science 216,
//     185: D = 1.35 ± 0.05 for clouds and rain areas from 1 to 1.2e6 km^2; a disc or a square gives 1);
//   - the exponent β of the size distribution n(L) ∝ L^-β, L = sqrt(A) (Neggers, Jonker and Siebesma
//     2003, J. Atmos. Sci. 60, 1060: β ≈ 1.7 below a scale break near 1 km for shallow cumulus; Benner
//     and Curry 1998, J. Geophys. Res. 103, 28753: 1.89–1.98), by maximum likelihood above L_min
//     (Clauset, Shalizi and Newman 2009, SIAM Rev. 51, 661, eq. 3.1, its standard error (β - 1)/sqrt(n));
//   - the largest cloud and the cloud-top heights.
// Clouds that touch the grid's edge are cut by it: they count in the fraction and the number, not in
// the fits of D and β.
#include <cstdint>
#include <vector>

#include "clouds/cloud_volume.h"
#include "clouds/reference_clouds.h"

namespace firmament {

// A field of columns seen from above: row-major, row 0 the southern edge, column 0 the western one.
struct CloudColumnField {
  int width = 0, height = 0;
  double pixel_m = 0.0;                // the columns' spacing
  double west_m = 0.0, south_m = 0.0;  // the south-west corner of pixel (0, 0), local ENU (m)
  std::vector<float> opticalDepth;     // vertical optical depth of all layers at 550 nm
  std::vector<float> top_m;            // highest height with cloud in the column (m above the ground); 0 if none
  // The mean over the columns of the coverage the weather map asks (CloudMedium::mapCoverage at each
  // layer's base, the largest of the layers): the cloud fraction the map means.
  double mapCoverage = 0.0;
};

// Samples the medium's columns over the region's horizontal box, one per pixel of size
// region.voxelSize_m, from region.bottom_m to region.top_m with steps of at most dz_m (midpoint rule on
// the extinction). A column's top is the highest step whose extinction exceeds topExtinction_m.
// threads 0: all cores.
CloudColumnField sampleCloudColumns(const CloudMedium& medium, const CloudVolumeRegion& region, double dz_m,
                                    double topExtinction_m = 1e-4, int threads = 0);

struct CloudObject {
  double area_m2 = 0.0, perimeter_m = 0.0;
  double size_m = 0.0;  // L = sqrt(area)
  double top_m = 0.0;   // highest top over its pixels
  bool touchesEdge = false;
};

struct CloudFieldStatisticsOptions {
  double opticalDepthThreshold = 1.0;  // a column with τ above it is cloud
  int minPixelsForDimension = 10;      // smaller clouds are pixel squares: left out of the D fit
  int minPixelsForSizes = 9;           // L_min = sqrt(this many pixels)
};

struct CloudFieldStatistics {
  double cloudFraction = 0.0;
  int clouds = 0;                      // all, edge ones included
  int cloudsInDimensionFit = 0;        // not on the edge, at least minPixelsForDimension
  double fractalDimension = 0.0;       // D; 0 with fewer than 3 clouds in the fit
  double fractalDimensionError = 0.0;  // standard error of D from the regression
  int cloudsInSizeFit = 0;             // not on the edge, L >= L_min
  double sizeExponent = 0.0;           // β; 0 with fewer than 3 clouds in the fit
  double sizeExponentError = 0.0;      // (β - 1) / sqrt(n)
  double sizeFitMin_m = 0.0;           // L_min
  double largestArea_m2 = 0.0;
  double largestSize_m = 0.0;                              // sqrt of the largest area
  double meanTop_m = 0.0, p90Top_m = 0.0, maxTop_m = 0.0;  // over the cloudy pixels
  std::vector<CloudObject> objects;                        // every cloud, largest first
};

// Cuts a field of cloud/clear pixels (mask: 1 cloud) into 4-connected clouds with their areas and
// perimeters (the edges between a cloud's pixels and any other pixel, holes included).
std::vector<CloudObject> findClouds(const std::vector<uint8_t>& mask, int width, int height, double pixel_m,
                                    const std::vector<float>& top_m = {});

// The statistics of clouds already found (cloudFraction and the tops are left to analyzeCloudField).
CloudFieldStatistics cloudObjectStatistics(std::vector<CloudObject> objects, double pixel_m,
                                           const CloudFieldStatisticsOptions& options = {});

// Thresholds the field and computes every statistic.
CloudFieldStatistics analyzeCloudField(const CloudColumnField& field, const CloudFieldStatisticsOptions& options = {});

}  // namespace firmament
