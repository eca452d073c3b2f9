#pragma once
// The SPIR-V of every shaders/**/*.comp, compiled at build time (cmake/FirmamentShaders.cmake) and
// keyed by path relative to shaders/ without extension: "gpu/fill_test", "sky/render_sky".
#include <cstdint>
#include <initializer_list>
#include <map>
#include <span>
#include <string>

namespace firmament::gpu {

const std::map<std::string, std::span<const uint32_t>>& shaderRegistry();

// The words of a registered shader; RuntimeError naming the known shaders if there is none.
std::span<const uint32_t> shaderCode(const std::string& name);

// FNV-1a of the named shaders' SPIR-V, as 16 hex digits: part of every disk-cache key of tables those
// shaders compute, so a changed shader never reads tables an older build wrote.
std::string shaderCodeHash(std::initializer_list<const char*> names);

}  // namespace firmament::gpu
