#version 450
#extension GL_GOOGLE_include_directive : require
// The clear-sky frame marched per pixel (any camera; the only way from above the atmosphere).
#define SKY_FROM_LUT 0
#include "sky/render_sky.glsl"
