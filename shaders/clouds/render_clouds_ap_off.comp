#version 450
#extension GL_GOOGLE_include_directive : require
// The clouds without aerial perspective.
#define CLOUD_AERIAL_PERSPECTIVE 0
#include "clouds/render_clouds.glsl"
