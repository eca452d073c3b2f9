#version 450
#extension GL_GOOGLE_include_directive : require
// The embedded mode's composite (sky/embed_composite.glsl) for a host colour image of format rgba16f.
#define EMBED_COLOUR_FORMAT rgba16f
#include "sky/embed_composite.glsl"
