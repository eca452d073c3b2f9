#version 450
#extension GL_GOOGLE_include_directive : require
// The clear-sky frame from the per-frame sky-view table (cameras inside the atmosphere).
#define SKY_FROM_LUT 1
#include "sky/render_sky.glsl"
