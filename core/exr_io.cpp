#include "core/exr_io.h"

#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfInputFile.h>
#include <ImfOutputFile.h>
#include <ImfStandardAttributes.h>
#include <ImfStringAttribute.h>
#include <ImfTestFile.h>

#include <cstdio>
#include <limits>
#include <string>
#include <vector>

#include "core/atomic_file.h"
#include "core/error.h"

namespace firmament {
namespace fs = std::filesystem;

namespace {

const char* const kChannelNames[4] = {"R", "G", "B", "A"};

void checkImageShape(const fs::path& path, const Image& image) {
  if (image.width <= 0 || image.height <= 0 || (image.channels != 3 && image.channels != 4) ||
      image.pixels.size() != image.pixelCount() * size_t(image.channels))
    throw RuntimeError("cannot write '" + path.string() + "': image is " + std::to_string(image.width) + "x" +
                       std::to_string(image.height) + "x" + std::to_string(image.channels) + " with " +
                       std::to_string(image.pixels.size()) + " values");
}

Imf::Header makeHeader(const fs::path& path, const Image& image, ExrCompression compression) {
  Imf::Header header(image.width, image.height);
  header.compression() = compression == ExrCompression::Piz ? Imf::PIZ_COMPRESSION : Imf::ZIP_COMPRESSION;
  for (int c = 0; c < image.channels; ++c) header.channels().insert(kChannelNames[c], Imf::Channel(Imf::FLOAT));
  // The pixels are absolute, linear Rec.709: say so in the standard attributes, so that other tools
  // interpret them correctly (OpenEXR "whiteLuminance": cd/m² of RGB (1,1,1)).
  Imf::addChromaticities(header, Imf::Chromaticities());  // the default is Rec.709 / D65
  Imf::addWhiteLuminance(header, 1.0f);
  for (const auto& [key, value] : image.metadata) {
    if (key.empty() || header.find(key) != header.end())
      throw RuntimeError("cannot write '" + path.string() + "': metadata key '" + key +
                         "' is empty or reserved by OpenEXR");
    header.insert(key, Imf::StringAttribute(value));
  }
  return header;
}

}  // namespace

void writeExr(const fs::path& path, const Image& image, ExrCompression compression) {
  checkImageShape(path, image);
  Imf::Header header = makeHeader(path, image, compression);
  writeFileAtomically(path, [&](const fs::path& tmp) {
    const size_t xStride = sizeof(float) * size_t(image.channels);
    const size_t yStride = xStride * size_t(image.width);
    Imf::FrameBuffer frame;
    for (int c = 0; c < image.channels; ++c)
      frame.insert(kChannelNames[c],
                   Imf::Slice(Imf::FLOAT, reinterpret_cast<char*>(const_cast<float*>(image.pixels.data() + c)), xStride,
                              yStride));
    try {
      Imf::OutputFile file(tmp.c_str(), header);
      file.setFrameBuffer(frame);
      file.writePixels(image.height);
    } catch (const std::exception& e) {
      throw RuntimeError("cannot write '" + path.string() + "': " + e.what());
    }
  });
}

namespace {
// The checks before OpenEXR opens a file: it exists, is readable, is a flat OpenEXR file.
void checkReadable(const fs::path& path) {
  const std::string name = path.string();
  std::error_code ec;
  if (!fs::exists(path, ec)) throw InputError("cannot read '" + name + "': no such file");
  if (!fs::is_regular_file(path, ec)) throw InputError("cannot read '" + name + "': not a regular file");
  if (std::FILE* f = std::fopen(path.c_str(), "rb")) {
    std::fclose(f);
  } else {
    throw InputError("cannot read '" + name + "': permission denied or unreadable");
  }
  bool tiled = false, deep = false, multiPart = false;
  if (!Imf::isOpenExrFile(path.c_str(), tiled, deep, multiPart))
    throw InputError("cannot read '" + name + "': not an OpenEXR file");
  if (deep) throw InputError("cannot read '" + name + "': deep OpenEXR images are not supported");
}
}  // namespace

Image readExr(const fs::path& path) {
  const std::string name = path.string();
  checkReadable(path);
  try {
    Imf::InputFile file(path.c_str());  // a multi-part file: its first part
    const Imf::Header& header = file.header();
    const Imath::Box2i window = header.dataWindow();
    const int64_t width = int64_t(window.max.x) - window.min.x + 1;
    const int64_t height = int64_t(window.max.y) - window.min.y + 1;
    if (width <= 0 || height <= 0 || width * height > int64_t(1) << 31)
      throw InputError("cannot read '" + name + "': data window of " + std::to_string(width) + "x" +
                       std::to_string(height) + " pixels is empty or too large");

    // Which channels to read. A luminance-only file (Y) is read as grey.
    const Imf::ChannelList& list = header.channels();
    std::vector<std::string> sources;
    if (list.findChannel("R") && list.findChannel("G") && list.findChannel("B")) {
      sources = {"R", "G", "B"};
    } else if (list.findChannel("Y") && !list.findChannel("RY") && !list.findChannel("BY")) {
      sources = {"Y", "Y", "Y"};
    } else {
      std::string found;
      for (auto it = list.begin(); it != list.end(); ++it) found += std::string(found.empty() ? "" : ", ") + it.name();
      throw InputError("cannot read '" + name + "': needs channels R, G, B; the file has " +
                       (found.empty() ? std::string("none") : found));
    }
    if (list.findChannel("A")) sources.push_back("A");
    for (const auto& s : sources) {
      const Imf::Channel* ch = list.findChannel(s);
      if (ch->xSampling != 1 || ch->ySampling != 1)
        throw InputError("cannot read '" + name + "': channel " + s + " is subsampled");
    }

    Image image(int(width), int(height), int(sources.size()));
    const size_t xStride = sizeof(float) * size_t(image.channels);
    const size_t yStride = xStride * size_t(image.width);
    Imf::FrameBuffer frame;
    std::vector<float> grey;  // "Y" can only be bound once; copied to R, G, B afterwards
    bool luminanceOnly = sources[0] == "Y";
    for (int c = 0; c < image.channels; ++c) {
      if (luminanceOnly && c > 0 && c < 3) continue;
      frame.insert(sources[c], Imf::Slice::Make(Imf::FLOAT, image.pixels.data() + c, window, xStride, yStride));
    }
    file.setFrameBuffer(frame);
    file.readPixels(window.min.y, window.max.y);
    if (luminanceOnly)
      for (size_t i = 0; i < image.pixelCount(); ++i) {
        float* p = image.pixels.data() + i * size_t(image.channels);
        p[1] = p[2] = p[0];
      }

    for (auto it = header.begin(); it != header.end(); ++it)
      if (const auto* s = dynamic_cast<const Imf::StringAttribute*>(&it.attribute()))
        image.metadata[it.name()] = s->value();
    return image;
  } catch (const InputError&) {
    throw;
  } catch (const std::exception& e) {
    // OpenEXR's Iex exceptions: truncated or corrupt files, unsupported layouts.
    throw InputError("cannot read '" + name + "': " + e.what());
  }
}

ExrChannel readExrChannel(const fs::path& path, const std::vector<std::string>& names) {
  const std::string name = path.string();
  checkReadable(path);
  try {
    Imf::InputFile file(path.c_str());
    const Imf::Header& header = file.header();
    const Imath::Box2i window = header.dataWindow();
    const int64_t width = int64_t(window.max.x) - window.min.x + 1;
    const int64_t height = int64_t(window.max.y) - window.min.y + 1;
    if (width <= 0 || height <= 0 || width * height > int64_t(1) << 28)
      throw InputError("cannot read '" + name + "': data window of " + std::to_string(width) + "x" +
                       std::to_string(height) + " pixels is empty or too large");
    const Imf::ChannelList& list = header.channels();
    std::string chosen, found;
    int count = 0;
    for (auto it = list.begin(); it != list.end(); ++it) {
      found += std::string(found.empty() ? "" : ", ") + it.name();
      ++count;
    }
    for (const auto& n : names)
      if (list.findChannel(n)) {
        chosen = n;
        break;
      }
    if (chosen.empty() && count == 1) chosen = list.begin().name();
    if (chosen.empty()) {
      std::string wanted;
      for (const auto& n : names) wanted += std::string(wanted.empty() ? "" : ", ") + n;
      throw InputError("cannot read '" + name + "': needs one of the channels " + wanted +
                       " (or a single channel); the file has " + (found.empty() ? std::string("none") : found));
    }
    const Imf::Channel* ch = list.findChannel(chosen);
    if (ch->xSampling != 1 || ch->ySampling != 1)
      throw InputError("cannot read '" + name + "': channel " + chosen + " is subsampled");
    ExrChannel result;
    result.width = int(width);
    result.height = int(height);
    result.name = chosen;
    result.values.assign(size_t(width) * size_t(height), 0.0f);
    Imf::FrameBuffer frame;
    frame.insert(chosen, Imf::Slice::Make(Imf::FLOAT, result.values.data(), window, sizeof(float),
                                          sizeof(float) * size_t(width)));
    file.setFrameBuffer(frame);
    file.readPixels(window.min.y, window.max.y);
    for (auto it = header.begin(); it != header.end(); ++it)
      if (const auto* s = dynamic_cast<const Imf::StringAttribute*>(&it.attribute()))
        result.metadata[it.name()] = s->value();
    return result;
  } catch (const InputError&) {
    throw;
  } catch (const std::exception& e) {
    throw InputError("cannot read '" + name + "': " + e.what());
  }
}

void writeExrChannel(const fs::path& path, const ExrChannel& channel) {
  if (channel.width <= 0 || channel.height <= 0 || channel.name.empty() ||
      channel.values.size() != size_t(channel.width) * size_t(channel.height))
    throw RuntimeError("cannot write '" + path.string() + "': channel '" + channel.name + "' of " +
                       std::to_string(channel.width) + "x" + std::to_string(channel.height) + " with " +
                       std::to_string(channel.values.size()) + " values");
  Imf::Header header(channel.width, channel.height);
  header.compression() = Imf::ZIP_COMPRESSION;
  header.channels().insert(channel.name, Imf::Channel(Imf::FLOAT));
  for (const auto& [key, value] : channel.metadata) {
    if (key.empty() || header.find(key) != header.end())
      throw RuntimeError("cannot write '" + path.string() + "': metadata key '" + key +
                         "' is empty or reserved by OpenEXR");
    header.insert(key, Imf::StringAttribute(value));
  }
  writeFileAtomically(path, [&](const fs::path& tmp) {
    Imf::FrameBuffer frame;
    frame.insert(channel.name,
                 Imf::Slice(Imf::FLOAT, reinterpret_cast<char*>(const_cast<float*>(channel.values.data())),
                            sizeof(float), sizeof(float) * size_t(channel.width)));
    try {
      Imf::OutputFile file(tmp.c_str(), header);
      file.setFrameBuffer(frame);
      file.writePixels(channel.height);
    } catch (const std::exception& e) {
      throw RuntimeError("cannot write '" + path.string() + "': " + e.what());
    }
  });
}

}  // namespace firmament
