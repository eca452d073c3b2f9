#include "atmosphere/table_file.h"

#include <cstring>
#include <fstream>

#include "core/atomic_file.h"
#include "core/log.h"

namespace firmament {
namespace {

constexpr char kMagic[8] = {'F', 'M', 'T', 'A', 'B', 'L', 'E', '2'};

template <class T>
bool readValue(std::ifstream& in, T& value) {
  return bool(in.read(reinterpret_cast<char*>(&value), sizeof(T)));
}

template <class T>
void writeValue(std::ofstream& out, const T& value) {
  out.write(reinterpret_cast<const char*>(&value), sizeof(T));
}

}  // namespace

std::optional<std::vector<TableData>> readTableFile(const std::filesystem::path& file, const std::string& key) {
  std::ifstream in(file, std::ios::binary);
  if (!in) return std::nullopt;
  char magic[8];
  uint32_t keyLength = 0, count = 0;
  if (!in.read(magic, 8) || std::memcmp(magic, kMagic, 8) != 0 || !readValue(in, keyLength) || keyLength > 4096)
    return std::nullopt;
  std::string storedKey(keyLength, '\0');
  if (!in.read(storedKey.data(), keyLength) || storedKey != key || !readValue(in, count) || count > 64)
    return std::nullopt;
  std::vector<TableData> tables(count);
  for (auto& t : tables) {
    uint32_t bytesPerValue = 0;
    if (!readValue(in, t.width) || !readValue(in, t.height) || !readValue(in, t.depth) || !readValue(in, t.channels) ||
        !readValue(in, bytesPerValue) || (bytesPerValue != 4 && bytesPerValue != 1))
      return std::nullopt;
    uint64_t n = uint64_t(t.width) * t.height * t.depth * t.channels;
    if (n == 0 || n > (uint64_t(1) << 28)) return std::nullopt;
    char* data = nullptr;
    if (bytesPerValue == 4) {
      t.values.resize(size_t(n));
      data = reinterpret_cast<char*>(t.values.data());
    } else {
      t.bytes.resize(size_t(n));
      data = reinterpret_cast<char*>(t.bytes.data());
    }
    if (!in.read(data, std::streamsize(n * bytesPerValue))) return std::nullopt;
  }
  return tables;
}

void writeTableFile(const std::filesystem::path& file, const std::string& key, const std::vector<TableData>& tables) {
  try {
    std::filesystem::create_directories(file.parent_path());
    writeFileAtomically(file, [&](const std::filesystem::path& tmp) {
      std::ofstream out(tmp, std::ios::binary);
      out.write(kMagic, 8);
      writeValue(out, uint32_t(key.size()));
      out.write(key.data(), std::streamsize(key.size()));
      writeValue(out, uint32_t(tables.size()));
      for (const auto& t : tables) {
        writeValue(out, t.width);
        writeValue(out, t.height);
        writeValue(out, t.depth);
        writeValue(out, t.channels);
        const bool floats = !t.values.empty();
        writeValue(out, uint32_t(floats ? sizeof(float) : 1));
        if (floats)
          out.write(reinterpret_cast<const char*>(t.values.data()), std::streamsize(t.values.size() * sizeof(float)));
        else
          out.write(reinterpret_cast<const char*>(t.bytes.data()), std::streamsize(t.bytes.size()));
      }
      if (!out) throw std::runtime_error("write failed");
    });
  } catch (const std::exception& e) {
    logWarning("could not cache tables in " + file.string() + ": " + e.what());
  }
}

}  // namespace firmament
