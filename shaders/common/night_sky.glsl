// night_sky.glsl: the light of the moonless night sky above the air, per direction and wavelength:
// airglow (a thin emitting layer near 90-250 km: OI 557.7 nm, Na D 589 nm, OI 630.0/636.4 nm and a
// continuum, brighter toward the horizon by the van Rhijn factor), the zodiacal light (Leinert et al.
// 1998, table 17) and the diffuse background of the stars too faint to be drawn one by one (stars
// fainter than the catalogue plus the diffuse galactic light). Spectral radiances in W m^-2 sr^-1 nm^-1
// arriving at the top of the air below the layers: the atmosphere's extinction and scattering apply
// after. Shared by the GPU passes and the C++ tests (docs/night.md, "Night-sky brightness").
#ifndef FIRMAMENT_NIGHT_SKY_GLSL
#define FIRMAMENT_NIGHT_SKY_GLSL

#include "common/compat.glsl"

// A constant array initialiser in both languages: C++ braces, GLSL's array constructor.
#ifdef __cplusplus
#define NIGHT_SKY_ARRAY(T, N) {
#define NIGHT_SKY_ARRAY_END }
#else
#define NIGHT_SKY_ARRAY(T, N) T[N](
#define NIGHT_SKY_ARRAY_END )
#endif

SHARED_BEGIN

// ---- Units -------------------------------------------------------------------------------------------

// One rayleigh is 1e10 photons s^-1 m^-2 into 4 pi sr (1e6 cm^-2 column): the radiance of a source of
// I rayleighs at wavelength lambda is I 1e10 / (4 pi) photons s^-1 m^-2 sr^-1 times h c / lambda.
const Real kPhotonsPerRayleighPerSteradian = 1.0e10 / (4.0 * 3.14159265358979323846);
const Real kPlanckTimesLightSpeedJouleNm = 1.98644586e-16;  // h c in J nm (CODATA 2018)

SHARED_INLINE Real rayleighToRadiance(Real rayleigh, Real wavelengthNm) {
  return rayleigh * kPhotonsPerRayleighPerSteradian * kPlanckTimesLightSpeedJouleNm / wavelengthNm;
}

// Luminance of one S10 (one star of V = 10 per square degree): 2.54e-6 lx · 1e-4 / (pi/180)^2 sr, with
// the V = 0 illuminance of astro/star_catalogue.h (Allen 1973). The same zero point gives
// L = 1.0807e5 cd/m^2 · 10^(-0.4 m) for a surface brightness of m V mag/arcsec^2 (1 arcsec^2 =
// 2.3504e-11 sr): 21.6 / 21.9 / 22.0 mag/arcsec^2 = 2.47e-4 / 1.87e-4 / 1.71e-4 cd/m^2.
const Real kS10Luminance = 8.3383e-7;
// The tabulated solar spectrum at 1 au (core/spectrum.h: ASTM G-173 in 10-nm means): its photopic
// illuminance (lux) over 360-830 nm and its value at 500 nm (W m^-2 nm^-1). The zodiacal light and the
// stellar background are given here as multiples of that spectrum (sunlight scattered by dust; the light
// of stars of about solar colour), so a caller multiplies by the solar irradiance at its wavelengths.
const Real kSolarSpectrumIlluminance = 132535.4;
const Real kSolarSpectrumAt500Nm = 1.91686;

// ---- Airglow -------------------------------------------------------------------------------------------

// The van Rhijn factor: the path length through a thin emitting shell of radius layerRadius seen from
// radius observerRadius at zenith-angle cosine cosZenith, relative to the vertical path,
//   V = 1 / sqrt(1 - (r_obs / r_layer)^2 sin^2 z)     (van Rhijn 1921),
// 1 at the zenith, ~ 5.5 at the horizon for a layer 97 km above a sea-level observer. Below the horizon it
// keeps the value of the same zenith distance (the shell is crossed once upward).
SHARED_INLINE Real vanRhijnFactor(Real cosZenith, Real observerRadius, Real layerRadius) {
  Real ratio = min(observerRadius / layerRadius, 1.0);
  Real sin2 = max(1.0 - cosZenith * cosZenith, 0.0);
  return 1.0 / sqrt(max(1.0 - ratio * ratio * sin2, 1.0e-6));
}

// Typical zenith intensities at a dark site near solar minimum (rayleighs) and emission heights (m),
// within the ranges Leinert et al. (1998, section 6, after Roach & Gordon 1973) list: OI 557.7 nm
// 250 R at 97 km; Na D (589.0 + 589.6 nm) 50 R at 92 km (seasonal, 20-150 R); OI 630.0 nm 60 R and
// OI 636.4 nm 20 R (a third of 630.0) at 250 km (F region); a pseudo-continuum (O2, NO2, ...) of
// 0.30 R per angstrom = 3.0 R/nm from 360 to 830 nm at 90 km. With these the zenith airglow in V is
// 145 S10, the 65 % of the 220 S10 dark sky that Leinert's summary gives (tests/night).
const Real kAirglowOI5577Rayleigh = 250.0;
const Real kAirglowNaDRayleigh = 50.0;
const Real kAirglowOI6300Rayleigh = 60.0;
const Real kAirglowOI6364Rayleigh = 20.0;
const Real kAirglowContinuumRayleighPerNm = 3.0;
const Real kAirglowOI5577HeightM = 97000.0;
const Real kAirglowNaDHeightM = 92000.0;
const Real kAirglowOI6300HeightM = 250000.0;
const Real kAirglowContinuumHeightM = 90000.0;

// A line of `rayleigh` at lineNm seen through a band of width binWidthNm centred at wavelengthNm: its
// radiance spread evenly over the band [lambda - w/2, lambda + w/2). Summing over bands that tile the
// spectrum counts each line exactly once; a narrower band than the sampling misses it.
SHARED_INLINE Real airglowLineInBand(Real rayleigh, Real lineNm, Real wavelengthNm, Real binWidthNm) {
  Real w = max(binWidthNm, 1.0e-6);
  Real inside = step(wavelengthNm - 0.5 * w, lineNm) * (1.0 - step(wavelengthNm + 0.5 * w, lineNm));
  return inside * rayleighToRadiance(rayleigh, lineNm) / w;
}

// Airglow spectral radiance (W m^-2 sr^-1 nm^-1) toward a direction of zenith-angle cosine cosZenith from
// an observer at radius observerRadius (m) on a planet of radius planetRadius (m), averaged over the
// band of width binWidthNm around wavelengthNm (the sampling step of the caller), times `intensityScale`
// (1 typical; airglow varies by ~2x with the solar cycle and through a night). Above the air: the caller
// applies the extinction and scattering of the air below.
SHARED_INLINE Real airglowSpectralRadiance(Real wavelengthNm, Real binWidthNm, Real cosZenith, Real observerRadius,
                                           Real planetRadius, Real intensityScale) {
  Real green = airglowLineInBand(kAirglowOI5577Rayleigh, 557.7, wavelengthNm, binWidthNm) *
               vanRhijnFactor(cosZenith, observerRadius, planetRadius + kAirglowOI5577HeightM);
  Real sodium = airglowLineInBand(kAirglowNaDRayleigh, 589.3, wavelengthNm, binWidthNm) *
                vanRhijnFactor(cosZenith, observerRadius, planetRadius + kAirglowNaDHeightM);
  Real red = (airglowLineInBand(kAirglowOI6300Rayleigh, 630.0, wavelengthNm, binWidthNm) +
              airglowLineInBand(kAirglowOI6364Rayleigh, 636.4, wavelengthNm, binWidthNm)) *
             vanRhijnFactor(cosZenith, observerRadius, planetRadius + kAirglowOI6300HeightM);
  Real inRange = step(360.0, wavelengthNm) * step(wavelengthNm, 830.0);
  Real continuum = inRange * rayleighToRadiance(kAirglowContinuumRayleighPerNm, wavelengthNm) *
                   vanRhijnFactor(cosZenith, observerRadius, planetRadius + kAirglowContinuumHeightM);
  return intensityScale * (green + sodium + red + continuum);
}

// ---- Zodiacal light ------------------------------------------------------------------------------------

// Leinert et al. (1998), table 17: the zodiacal light at 500 nm seen from the Earth, in
// 1e-8 W m^-2 sr^-1 um^-1 (77 at the ecliptic pole = 60 S10), by helioecliptic longitude difference
// lambda - lambda_sun (rows: 0, 5, ..., 45, 60, 75, ..., 180 degrees) and ecliptic latitude beta (columns:
// 0, 5, ..., 30, 45, 60, 75, 90 degrees). The paper leaves the cells closest to the Sun empty; they are 0
// here and the lookup takes the row's first tabulated latitude instead.
const int kZodiacalRows = 19;
const int kZodiacalColumns = 11;
const Real kZodiacalTable17[209] = NIGHT_SKY_ARRAY(Real, 209)
    0.0, 0.0, 0.0, 3140.0, 1610.0, 985.0, 640.0, 275.0, 150.0, 100.0, 77.0,
    0.0, 0.0, 0.0, 2940.0, 1540.0, 945.0, 625.0, 271.0, 150.0, 100.0, 77.0,
    0.0, 0.0, 4740.0, 2470.0, 1370.0, 865.0, 590.0, 264.0, 148.0, 100.0, 77.0,
    11500.0, 6780.0, 3440.0, 1860.0, 1110.0, 755.0, 525.0, 251.0, 146.0, 100.0, 77.0,
    6400.0, 4480.0, 2410.0, 1410.0, 910.0, 635.0, 454.0, 237.0, 141.0, 99.0, 77.0,
    3840.0, 2830.0, 1730.0, 1100.0, 749.0, 545.0, 410.0, 223.0, 136.0, 97.0, 77.0,
    2480.0, 1870.0, 1220.0, 845.0, 615.0, 467.0, 365.0, 207.0, 131.0, 95.0, 77.0,
    1650.0, 1270.0, 910.0, 680.0, 510.0, 397.0, 320.0, 193.0, 125.0, 93.0, 77.0,
    1180.0, 940.0, 700.0, 530.0, 416.0, 338.0, 282.0, 179.0, 120.0, 92.0, 77.0,
    910.0, 730.0, 555.0, 442.0, 356.0, 292.0, 250.0, 166.0, 116.0, 90.0, 77.0,
    505.0, 442.0, 352.0, 292.0, 243.0, 209.0, 183.0, 134.0, 104.0, 86.0, 77.0,
    338.0, 317.0, 269.0, 227.0, 196.0, 172.0, 151.0, 116.0, 93.0, 82.0, 77.0,
    259.0, 251.0, 225.0, 193.0, 166.0, 147.0, 132.0, 104.0, 86.0, 79.0, 77.0,
    212.0, 210.0, 197.0, 170.0, 150.0, 133.0, 119.0, 96.0, 82.0, 77.0, 77.0,
    188.0, 186.0, 177.0, 154.0, 138.0, 125.0, 113.0, 90.0, 77.0, 74.0, 77.0,
    179.0, 178.0, 166.0, 147.0, 134.0, 122.0, 110.0, 90.0, 77.0, 73.0, 77.0,
    179.0, 178.0, 165.0, 148.0, 137.0, 127.0, 116.0, 96.0, 79.0, 72.0, 77.0,
    196.0, 192.0, 179.0, 165.0, 151.0, 141.0, 131.0, 104.0, 82.0, 72.0, 77.0,
    230.0, 212.0, 195.0, 178.0, 163.0, 148.0, 134.0, 105.0, 83.0, 72.0, 77.0
NIGHT_SKY_ARRAY_END;

// Fractional row and column of table 17 for |lambda - lambda_sun| and |beta| in degrees.
SHARED_INLINE Real zodiacalRowCoordinate(Real longitudeDifferenceDeg) {
  Real d = clamp(longitudeDifferenceDeg, 0.0, 180.0);
  return d < 45.0 ? d / 5.0 : 9.0 + (d - 45.0) / 15.0;
}
SHARED_INLINE Real zodiacalColumnCoordinate(Real latitudeDeg) {
  Real b = clamp(latitudeDeg, 0.0, 90.0);
  return b < 30.0 ? b / 5.0 : 6.0 + (b - 30.0) / 15.0;
}

// ln of one row of table 17, linear in the column coordinate, the row's empty cells replaced by its first
// tabulated latitude.
SHARED_INLINE Real zodiacalRowLog(int row, Real column) {
  int firstColumn = row < 2 ? 3 : (row == 2 ? 2 : 0);
  Real c = max(column, Real(firstColumn));
  int c0 = min(int(floor(c)), kZodiacalColumns - 2);
  Real f = c - Real(c0);
  Real a = log(kZodiacalTable17[row * kZodiacalColumns + c0]);
  Real b = log(kZodiacalTable17[row * kZodiacalColumns + c0 + 1]);
  return mix(a, b, f);
}

// Table 17 at (|lambda - lambda_sun|, |beta|) in degrees, bilinear in ln(brightness) (the brightness falls
// off exponentially toward the poles and away from the Sun), in 1e-8 W m^-2 sr^-1 um^-1 at 500 nm.
SHARED_INLINE Real zodiacalTable17At(Real longitudeDifferenceDeg, Real latitudeDeg) {
  Real r = zodiacalRowCoordinate(abs(longitudeDifferenceDeg));
  Real c = zodiacalColumnCoordinate(abs(latitudeDeg));
  int r0 = min(int(floor(r)), kZodiacalRows - 2);
  Real f = r - Real(r0);
  return exp(mix(zodiacalRowLog(r0, c), zodiacalRowLog(r0 + 1, c), f));
}

// The zodiacal light toward a unit direction given in the Sun's ecliptic frame (x toward the Sun's
// ecliptic longitude, z the ecliptic north pole; astro/night_sky.h builds it), as a multiple of the
// tabulated solar spectrum (sr^-1): its spectral radiance at wavelength lambda is this times the solar
// spectral irradiance at lambda (at 1 au). Leinert's table is at 500 nm; the zodiacal light is a little
// redder than the Sun (a few per cent per 100 nm, their section 8.4), left out here.
SHARED_INLINE Real zodiacalSolarSpectrumFactor(vec3 sunEclipticDirection) {
  // atan of z over the horizontal length: well conditioned at the poles, where asin(z) is not.
  Real horizontal = sqrt(sunEclipticDirection.x * sunEclipticDirection.x + sunEclipticDirection.y * sunEclipticDirection.y);
  Real latitudeDeg = abs(atan(sunEclipticDirection.z, horizontal)) * (180.0 / kPi);
  Real longitudeDeg = abs(atan(sunEclipticDirection.y, sunEclipticDirection.x)) * (180.0 / kPi);
  // 1e-8 W m^-2 sr^-1 um^-1 = 1e-11 W m^-2 sr^-1 nm^-1.
  return zodiacalTable17At(longitudeDeg, latitudeDeg) * 1.0e-11 / kSolarSpectrumAt500Nm;
}

// ---- The stars too faint to draw one by one --------------------------------------------------------------

// Integrated light of the stars below the catalogue's limit and the diffuse galactic light, by galactic
// latitude b: 15 S10 at the galactic poles (the 7 % "scattered starlight" share of Leinert's 220 S10
// dark sky), rising as a thin plane-parallel disc of stars does, 1 / |sin b|, up to |b| = 6 degrees
// (9.6 times the pole, 144 S10 along the Milky Way's band). A model of the shape, not a star-count map.
const Real kStellarBackgroundPoleS10 = 15.0;
const Real kStellarBackgroundMinSinLatitude = 0.104528;  // sin 6°

// As a multiple of the tabulated solar spectrum (sr^-1), like zodiacalSolarSpectrumFactor, for the sine
// of the galactic latitude (the z of a unit direction in galactic coordinates).
SHARED_INLINE Real stellarBackgroundSolarSpectrumFactor(Real sinGalacticLatitude) {
  Real s = max(abs(sinGalacticLatitude), kStellarBackgroundMinSinLatitude);
  return kStellarBackgroundPoleS10 / s * kS10Luminance / kSolarSpectrumIlluminance;
}

SHARED_END

#endif  // FIRMAMENT_NIGHT_SKY_GLSL
