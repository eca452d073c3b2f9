#pragma once
// Luminance of linear Rec.709 / sRGB-primaries RGB. Images are in absolute units, so this is cd/m².
// Coefficients: ITU-R BT.709-6, item 3.2 (the Y row of the RGB → XYZ matrix for D65).

namespace firmament {

inline constexpr double kLuminanceR = 0.2126;
inline constexpr double kLuminanceG = 0.7152;
inline constexpr double kLuminanceB = 0.0722;

inline double luminanceRec709(double r, double g, double b) {
  return kLuminanceR * r + kLuminanceG * g + kLuminanceB * b;
}
inline double luminanceRec709(const float* rgb) { return luminanceRec709(rgb[0], rgb[1], rgb[2]); }

}  // namespace firmament
