#version 450
#extension GL_GOOGLE_include_directive : require
// Psi_ms, first order: light from the sun (see atmosphere/multiple_scattering_lut.glsl).
#define FIRST_ORDER 1
#include "atmosphere/multiple_scattering_lut.glsl"
