#version 450
#extension GL_GOOGLE_include_directive : require
// The clouds with aerial perspective from the per-frame volume (default).
#define CLOUD_AERIAL_PERSPECTIVE 2
#include "clouds/render_clouds.glsl"
