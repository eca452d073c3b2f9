#pragma once
// A VkPipelineCache persisted on disk, so the second run of a program skips shader compilation (the
// first dispatch on lavapipe otherwise JIT-compiles for ~0.2 s per pipeline). One file per device and
// driver: pipelines-<device UUID>-<driver version>.vkcache in the cache folder. A file that is missing,
// unreadable or from another device is ignored; writes go to a temporary file, then rename.
#include <vulkan/vulkan.h>

#include <filesystem>
#include <vector>

namespace firmament::gpu {

// FIRMAMENT_CACHE_DIR, else $XDG_CACHE_HOME/firmament, else ~/.cache/firmament; empty if none is set.
std::filesystem::path defaultCacheDir();

class PipelineCache {
 public:
  // `dir` empty -> in memory only.
  PipelineCache(VkDevice device, const VkPhysicalDeviceProperties& properties, std::filesystem::path dir);
  ~PipelineCache();  // saves if pipelines were added
  PipelineCache(const PipelineCache&) = delete;
  PipelineCache& operator=(const PipelineCache&) = delete;

  VkPipelineCache handle() const { return cache_; }
  const std::filesystem::path& file() const { return file_; }  // empty when in memory only
  bool loadedFromDisk() const { return loaded_; }
  void markDirty() { dirty_ = true; }
  // Writes the cache file now (also done on destruction). Failures are warnings, never errors.
  void save();

 private:
  bool headerMatches(const std::vector<char>& data) const;

  VkDevice device_;
  VkPhysicalDeviceProperties properties_;
  VkPipelineCache cache_ = VK_NULL_HANDLE;
  std::filesystem::path file_;
  bool loaded_ = false;
  bool dirty_ = false;
};

}  // namespace firmament::gpu
