#include "gpu/pipeline_cache.h"

#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iterator>
#include <system_error>

#include "core/log.h"
#include "gpu/check.h"

namespace firmament::gpu {
namespace {

std::string hex(const uint8_t* bytes, size_t count) {
  static const char* digits = "0123456789abcdef";
  std::string out;
  for (size_t i = 0; i < count; ++i) {
    out += digits[bytes[i] >> 4];
    out += digits[bytes[i] & 15];
  }
  return out;
}

std::filesystem::path environmentPath(const char* name) {
  const char* value = std::getenv(name);
  return value && *value ? std::filesystem::path(value) : std::filesystem::path();
}

}  // namespace

std::filesystem::path defaultCacheDir() {
  if (auto dir = environmentPath("FIRMAMENT_CACHE_DIR"); !dir.empty()) return dir;
  if (auto dir = environmentPath("XDG_CACHE_HOME"); !dir.empty()) return dir / "firmament";
  if (auto dir = environmentPath("HOME"); !dir.empty()) return dir / ".cache" / "firmament";
  return {};
}

PipelineCache::PipelineCache(VkDevice device, const VkPhysicalDeviceProperties& properties, std::filesystem::path dir)
    : device_(device), properties_(properties) {
  std::vector<char> data;
  if (!dir.empty()) {
    file_ = dir / ("pipelines-" + hex(properties.pipelineCacheUUID, VK_UUID_SIZE) + "-" +
                   std::to_string(properties.driverVersion) + ".vkcache");
    std::ifstream in(file_, std::ios::binary);
    if (in) data.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
    if (!in.good() && !in.eof()) data.clear();
    // Drivers check the header too, but not all survive garbage after a valid-looking one; a file
    // from another device or a truncated write is dropped here.
    if (!data.empty() && !headerMatches(data)) {
      logVerbose("ignoring pipeline cache " + file_.string() + " (not from this device and driver)");
      data.clear();
    }
  }
  VkPipelineCacheCreateInfo info{VK_STRUCTURE_TYPE_PIPELINE_CACHE_CREATE_INFO};
  info.initialDataSize = data.size();
  info.pInitialData = data.empty() ? nullptr : data.data();
  if (vkCreatePipelineCache(device_, &info, nullptr, &cache_) != VK_SUCCESS) {
    // A driver that rejects the data: start empty rather than fail.
    info.initialDataSize = 0;
    info.pInitialData = nullptr;
    data.clear();
    FIRMAMENT_VK(vkCreatePipelineCache(device_, &info, nullptr, &cache_));
  }
  loaded_ = !data.empty();
}

PipelineCache::~PipelineCache() {
  save();
  vkDestroyPipelineCache(device_, cache_, nullptr);
}

bool PipelineCache::headerMatches(const std::vector<char>& data) const {
  // VkPipelineCacheHeaderVersionOne: length, version, vendor, device, UUID (32 bytes in all).
  VkPipelineCacheHeaderVersionOne header;
  if (data.size() < sizeof(header)) return false;
  std::memcpy(&header, data.data(), sizeof(header));
  return header.headerSize >= sizeof(header) && header.headerSize <= data.size() &&
         header.headerVersion == VK_PIPELINE_CACHE_HEADER_VERSION_ONE && header.vendorID == properties_.vendorID &&
         header.deviceID == properties_.deviceID &&
         std::memcmp(header.pipelineCacheUUID, properties_.pipelineCacheUUID, VK_UUID_SIZE) == 0;
}

void PipelineCache::save() {
  if (!dirty_ || file_.empty()) return;
  dirty_ = false;
  size_t size = 0;
  if (vkGetPipelineCacheData(device_, cache_, &size, nullptr) != VK_SUCCESS || size == 0) return;
  std::vector<char> data(size);
  if (vkGetPipelineCacheData(device_, cache_, &size, data.data()) != VK_SUCCESS) return;
  data.resize(size);

  std::error_code error;
  std::filesystem::create_directories(file_.parent_path(), error);
  // Unique temporary name so two processes saving at once never interleave bytes in one file.
  auto temp = file_;
  temp += ".tmp" + std::to_string(::getpid());
  {
    std::ofstream out(temp, std::ios::binary | std::ios::trunc);
    out.write(data.data(), std::streamsize(data.size()));
    out.close();
    if (!out) {
      std::filesystem::remove(temp, error);
      logWarning("could not write the pipeline cache " + temp.string());
      return;
    }
  }
  std::filesystem::rename(temp, file_, error);
  if (error) {
    std::filesystem::remove(temp, error);
    logWarning("could not replace the pipeline cache " + file_.string());
  }
}

}  // namespace firmament::gpu
