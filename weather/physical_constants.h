#pragma once
// Physical constants of the weather model, SI units. Sources are named next to each value.

namespace firmament::weather {

inline constexpr double kGravity = 9.80665;           // m s^-2, standard gravity (CGPM 1901)
inline constexpr double kDryAirGasConstant = 287.05;  // J kg^-1 K^-1 (Wallace & Hobbs 2006, table)
inline constexpr double kVapourGasConstant = 461.5;   // J kg^-1 K^-1 (Wallace & Hobbs 2006)
inline constexpr double kEpsilon = kDryAirGasConstant / kVapourGasConstant;  // ≈ 0.622
inline constexpr double kDryAirHeatCapacity = 1005.0;                        // c_p, J kg^-1 K^-1 (Wallace & Hobbs 2006)
inline constexpr double kLatentHeatVaporization = 2.501e6;  // L_v at 0 °C, J kg^-1 (Wallace & Hobbs 2006)
inline constexpr double kDryAdiabaticLapseRate = kGravity / kDryAirHeatCapacity;  // Γ_d ≈ 9.76e-3 K m^-1
inline constexpr double kWaterDensity = 1000.0;                                   // kg m^-3
inline constexpr double kPressureScaleHeight = 8434.0;  // m, H = R_d T / g at T = 288 K (US Std. Atm. 1976)
inline constexpr double kSeaLevelPressure = 101325.0;   // Pa (US Std. Atm. 1976)

// Espy's rule: the lifting condensation level rises ≈ 125 m per kelvin of dew-point depression
// (Espy 1836; Lawrence 2005, BAMS 86:225, eq. 24).
inline constexpr double kLclMetresPerKelvin = 125.0;

}  // namespace firmament::weather
