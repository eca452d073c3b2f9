#pragma once
// Atmospheric refraction: how much higher a body appears than its geometric (airless) direction.

namespace firmament::astro {

enum class RefractionModel {
  None,  // geometric topocentric direction, as if there were no air
  Spa,   // NREL SPA's Bennett-type formula (Reda & Andreas 2008, eq. 42): the SPA reference values use it
  Erfa,  // ERFA's A tan z + B tan^3 z model (eraRefco + eraAtioq), from pressure, temperature, humidity and
         // wavelength; better above 15 degrees elevation, saturates near the horizon
};

// The air at the observer; it only affects refraction.
struct ObservingConditions {
  double pressureHpa = 1013.25;         // hPa = mbar (ISO standard atmosphere at sea level)
  double temperatureCelsius = 15.0;     // °C
  double relativeHumidity = 0.0;        // 0..1; only the ERFA model uses it (SPA assumes dry air)
  double wavelengthMicrometres = 0.55;  // only the ERFA model uses it (0.55 µm: the middle of the visible)
  RefractionModel refraction = RefractionModel::Spa;
};

// NREL SPA's refraction correction in radians for a geometric topocentric elevation (radians), from
// Reda & Andreas (2008), "Solar position algorithm for solar radiation applications", NREL/TP-560-34302,
// eq. 42, itself after Bennett (1982):
//   Δe = P/1010 · 283/(273 + T) · 1.02 / (60 · tan(e0 + 10.3/(e0 + 5.11)))   [degrees, e0 in degrees]
// SPA applies it only while the body's upper limb can be above the horizon, e0 >= -(0.26667° + 0.5667°)
// (solar semi-diameter + horizontal refraction); below, it is zero.
double spaRefraction(double geometricElevation, double pressureHpa, double temperatureCelsius);

}  // namespace firmament::astro
