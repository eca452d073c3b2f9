#version 450
#extension GL_GOOGLE_include_directive : require
// Psi_ms, orders 2 and up: each reads the order before (see atmosphere/multiple_scattering_lut.glsl).
#define FIRST_ORDER 0
#include "atmosphere/multiple_scattering_lut.glsl"
