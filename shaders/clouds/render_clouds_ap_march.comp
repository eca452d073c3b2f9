#version 450
#extension GL_GOOGLE_include_directive : require
// The clouds with aerial perspective by a per-pixel march of the air (quality option).
#define CLOUD_AERIAL_PERSPECTIVE 1
#include "clouds/render_clouds.glsl"
