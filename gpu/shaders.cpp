#include "gpu/shaders.h"

#include "core/error.h"
#include "core/hash.h"

namespace firmament::gpu {

std::span<const uint32_t> shaderCode(const std::string& name) {
  const auto& registry = shaderRegistry();
  auto found = registry.find(name);
  if (found != registry.end()) return found->second;
  std::string known;
  for (const auto& [key, code] : registry) known += (known.empty() ? "" : ", ") + key;
  throw RuntimeError("no compiled shader named \"" + name + "\" (a shaders/" + name + ".comp file); known: " + known);
}

std::string shaderCodeHash(std::initializer_list<const char*> names) {
  uint64_t hash = fnv1a("");
  for (const char* name : names) {
    std::span<const uint32_t> code = shaderCode(name);
    hash = fnv1a(std::string_view(reinterpret_cast<const char*>(code.data()), code.size_bytes()), hash);
  }
  return hex16(hash);
}

}  // namespace firmament::gpu
