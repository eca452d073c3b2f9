#pragma once
// Where data ends: the samples of a resolved tile that no raster or height map covers (beyond its
// edge, or nodata) take the scene's fallback, blended from the data's edge over a band.
//
// A missing sample at distance δ from the nearest valid one (a two-pass 3 × 3 chamfer distance over the
// grid, with the nearest valid sample carried along: Borgefors 1986, "Distance transformations in
// digital images", CVGIP 34:344–371; the 1, √2 weights overestimate Euclidean distance by at most
// 8 %) gets
//     h = mix(h_nearest, fallback(x, y), smoothstep(0, blend, δ)),
// so the surface is continuous at the data's edge (no wall), reaches the fallback `blend` metres out,
// and the data itself is untouched. blend = 0 is a step.
#include <functional>

#include "terrain/height_field.h"
#include "terrain/procedural_terrain.h"

namespace firmament::terrain {

// Replaces every NaN height of `field`; returns the fraction of samples that were valid (1: nothing
// to fill; 0: the whole tile is the fallback).
double fillFromFallback(HeightField& field, const std::function<double(double x, double y)>& fallback, double blend_m);

// A field's samples on another grid: bilinear inside the source's rectangle, the edge sample within
// `margin` metres outside it (an image covers half a pixel beyond its outer pixel centres), NaN
// farther out. NaN source samples make the samples that read them NaN.
HeightField resampleField(const HeightField& source, const TileRegion& region, double marginX, double marginY);

}  // namespace firmament::terrain
