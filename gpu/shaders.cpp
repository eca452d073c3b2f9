#include "gpu/shaders.h"

#include "core/error.h"

namespace firmament::gpu {

std::span<const uint32_t> shaderCode(const std::string& name) {
  const auto& registry = shaderRegistry();
  auto found = registry.find(name);
  if (found != registry.end()) return found->second;
  std::string known;
  for (const auto& [key, code] : registry) known += (known.empty() ? "" : ", ") + key;
  throw RuntimeError("no compiled shader named \"" + name + "\" (a shaders/" + name +
                     ".comp file); known: " + known);
}

}  // namespace firmament::gpu
