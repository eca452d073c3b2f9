#pragma once
// The SPIR-V of every shaders/**/*.comp, compiled at build time (cmake/FirmamentShaders.cmake) and
// keyed by path relative to shaders/ without extension: "gpu/fill_test", "sky/render_sky".
#include <cstdint>
#include <map>
#include <span>
#include <string>

namespace firmament::gpu {

const std::map<std::string, std::span<const uint32_t>>& shaderRegistry();

// The words of a registered shader; RuntimeError naming the known shaders if there is none.
std::span<const uint32_t> shaderCode(const std::string& name);

}  // namespace firmament::gpu
