#include "core/png_io.h"

#include <png.h>

#include <csetjmp>
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

#include "core/atomic_file.h"
#include "core/error.h"

namespace firmament {
namespace fs = std::filesystem;

namespace {

// libpng reports errors by longjmp. The functions that call it hold only trivially destructible
// state between setjmp and the last libpng call, so the jump skips no destructor.
struct PngErrorState {
  char message[256] = "unknown libpng error";
};

[[noreturn]] void onPngError(png_structp png, png_const_charp message) {
  auto* state = static_cast<PngErrorState*>(png_get_error_ptr(png));
  std::snprintf(state->message, sizeof(state->message), "%s", message);
  png_longjmp(png, 1);
}
void onPngWarning(png_structp, png_const_charp) {}

int colorTypeFor(int channels) {
  switch (channels) {
    case 1:
      return PNG_COLOR_TYPE_GRAY;
    case 2:
      return PNG_COLOR_TYPE_GRAY_ALPHA;
    case 3:
      return PNG_COLOR_TYPE_RGB;
    default:
      return PNG_COLOR_TYPE_RGBA;
  }
}

// Returns false and fills `error` on failure. `rows` and `texts` are prepared by the caller.
bool writePngStream(std::FILE* file, int width, int height, int channels, png_bytep* rows, png_text* texts,
                    int textCount, PngErrorState* error) {
  png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, error, onPngError, onPngWarning);
  if (!png) return false;
  png_infop info = png_create_info_struct(png);
  if (!info || setjmp(png_jmpbuf(png))) {
    png_destroy_write_struct(&png, &info);
    return false;
  }
  png_init_io(png, file);
  png_set_IHDR(png, info, png_uint_32(width), png_uint_32(height), 8, colorTypeFor(channels), PNG_INTERLACE_NONE,
               PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
  png_set_sRGB_gAMA_and_cHRM(png, info, PNG_sRGB_INTENT_PERCEPTUAL);
  if (textCount > 0) png_set_text(png, info, texts, textCount);
  png_write_info(png, info);
  png_write_image(png, rows);
  png_write_end(png, info);
  png_destroy_write_struct(&png, &info);
  return true;
}

// The tEXt entries of a PNG file (keyword NUL text), found by walking its chunks; the simplified
// libpng read API does not expose them. Stops quietly at anything malformed.
std::map<std::string, std::string> readTextChunks(std::FILE* file) {
  std::map<std::string, std::string> text;
  if (std::fseek(file, 8, SEEK_SET) != 0) return text;
  for (;;) {
    unsigned char head[8];
    if (std::fread(head, 1, 8, file) != 8) break;
    const uint32_t length = uint32_t(head[0]) << 24 | uint32_t(head[1]) << 16 | uint32_t(head[2]) << 8 | head[3];
    const std::string type(reinterpret_cast<const char*>(head + 4), 4);
    if (length > (1u << 24)) break;
    if (type == "IEND") break;
    if (type == "tEXt") {
      std::string data(length, '\0');
      if (length > 0 && std::fread(data.data(), 1, length, file) != length) break;
      if (auto nul = data.find('\0'); nul != std::string::npos) text[data.substr(0, nul)] = data.substr(nul + 1);
      if (std::fseek(file, 4, SEEK_CUR) != 0) break;  // CRC
    } else if (std::fseek(file, long(length) + 4, SEEK_CUR) != 0) {
      break;
    }
  }
  return text;
}

// Reads a grey PNG with libpng's low-level API into `out`, through the caller's row buffer: the
// objects that own memory belong to the caller, so a longjmp out of libpng skips no destructor.
bool readGreyStream(std::FILE* file, Grey16* out, std::vector<png_byte>* row, int* colorType, PngErrorState* error) {
  png_structp png = png_create_read_struct(PNG_LIBPNG_VER_STRING, error, onPngError, onPngWarning);
  if (!png) return false;
  png_infop info = png_create_info_struct(png);
  if (!info || setjmp(png_jmpbuf(png))) {
    png_destroy_read_struct(&png, &info, nullptr);
    return false;
  }
  png_init_io(png, file);
  png_read_info(png, info);
  *colorType = png_get_color_type(png, info);
  const int depth = png_get_bit_depth(png, info);
  if (*colorType != PNG_COLOR_TYPE_GRAY && *colorType != PNG_COLOR_TYPE_GRAY_ALPHA) {
    png_destroy_read_struct(&png, &info, nullptr);
    return true;  // the caller reports the colour type
  }
  if (depth < 8) png_set_expand_gray_1_2_4_to_8(png);
  if (*colorType == PNG_COLOR_TYPE_GRAY_ALPHA) png_set_strip_alpha(png);
  png_read_update_info(png, info);
  out->width = int(png_get_image_width(png, info));
  out->height = int(png_get_image_height(png, info));
  out->bitDepth = depth;
  if (int64_t(out->width) * out->height > int64_t(1) << 28) {  // the caller reports the size
    png_destroy_read_struct(&png, &info, nullptr);
    return true;
  }
  const size_t rowBytes = png_get_rowbytes(png, info);
  const size_t width = size_t(out->width);
  out->samples.resize(width * size_t(out->height));
  row->resize(rowBytes);
  for (int y = 0; y < out->height; ++y) {
    png_read_row(png, row->data(), nullptr);
    uint16_t* dst = out->samples.data() + size_t(y) * width;
    if (depth == 16) {
      for (size_t x = 0; x < width; ++x) dst[x] = uint16_t((*row)[2 * x] << 8 | (*row)[2 * x + 1]);  // big-endian
    } else {
      for (size_t x = 0; x < width; ++x) dst[x] = (*row)[x];
    }
  }
  png_read_end(png, nullptr);
  png_destroy_read_struct(&png, &info, nullptr);
  return true;
}

bool writeGreyStream(std::FILE* file, int width, int height, png_bytep* rows, PngErrorState* error) {
  png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, error, onPngError, onPngWarning);
  if (!png) return false;
  png_infop info = png_create_info_struct(png);
  if (!info || setjmp(png_jmpbuf(png))) {
    png_destroy_write_struct(&png, &info);
    return false;
  }
  png_init_io(png, file);
  png_set_IHDR(png, info, png_uint_32(width), png_uint_32(height), 16, PNG_COLOR_TYPE_GRAY, PNG_INTERLACE_NONE,
               PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
  png_write_info(png, info);
  png_write_image(png, rows);
  png_write_end(png, info);
  png_destroy_write_struct(&png, &info);
  return true;
}

}  // namespace

Grey16 readPngGrey16(const fs::path& path) {
  const std::string name = path.string();
  std::error_code ec;
  if (!fs::exists(path, ec)) throw InputError("cannot read '" + name + "': no such file");
  std::FILE* file = std::fopen(path.c_str(), "rb");
  if (!file) throw InputError("cannot read '" + name + "': " + std::strerror(errno));
  png_byte signature[8] = {};
  if (std::fread(signature, 1, 8, file) != 8 || png_sig_cmp(signature, 0, 8) != 0) {
    std::fclose(file);
    throw InputError("cannot read '" + name + "': not a PNG file");
  }
  std::rewind(file);
  Grey16 result;
  int colorType = -1;
  PngErrorState error;
  std::vector<png_byte> row;
  const bool ok = readGreyStream(file, &result, &row, &colorType, &error);
  std::fclose(file);
  if (!ok) throw InputError("cannot read '" + name + "': " + error.message);
  if (colorType != PNG_COLOR_TYPE_GRAY && colorType != PNG_COLOR_TYPE_GRAY_ALPHA)
    throw InputError("cannot read '" + name + "' as heights: it is a " +
                     (colorType == PNG_COLOR_TYPE_PALETTE ? std::string("palette") : std::string("colour")) +
                     " PNG; expected a grey PNG (8 or 16 bits)");
  if (result.samples.size() != size_t(result.width) * size_t(result.height))
    throw InputError("cannot read '" + name + "': " + std::to_string(result.width) + "x" +
                     std::to_string(result.height) + " pixels is more than the 2^28 allowed");
  return result;
}

void writePngGrey16(const fs::path& path, int width, int height, const uint16_t* samples) {
  if (width <= 0 || height <= 0 || !samples)
    throw RuntimeError("cannot write '" + path.string() + "': bad image shape " + std::to_string(width) + "x" +
                       std::to_string(height));
  std::vector<uint8_t> bytes(size_t(width) * size_t(height) * 2);
  for (size_t i = 0; i < size_t(width) * size_t(height); ++i) {
    bytes[2 * i] = uint8_t(samples[i] >> 8);
    bytes[2 * i + 1] = uint8_t(samples[i] & 0xff);
  }
  std::vector<png_bytep> rows(static_cast<size_t>(height));
  for (int y = 0; y < height; ++y) rows[size_t(y)] = bytes.data() + size_t(y) * size_t(width) * 2;
  writeFileAtomically(path, [&](const fs::path& tmp) {
    std::FILE* file = std::fopen(tmp.c_str(), "wb");
    if (!file) throw RuntimeError("cannot create '" + tmp.string() + "': " + std::strerror(errno));
    PngErrorState error;
    bool ok = writeGreyStream(file, width, height, rows.data(), &error);
    bool closed = std::fclose(file) == 0;
    if (!ok) throw RuntimeError("cannot write '" + path.string() + "': " + error.message);
    if (!closed) throw RuntimeError("cannot write '" + path.string() + "' (disk full?)");
  });
}

void writePng(const fs::path& path, int width, int height, int channels, const uint8_t* pixels,
              const std::map<std::string, std::string>& text) {
  if (width <= 0 || height <= 0 || channels < 1 || channels > 4 || !pixels)
    throw RuntimeError("cannot write '" + path.string() + "': bad image shape " + std::to_string(width) + "x" +
                       std::to_string(height) + "x" + std::to_string(channels));
  std::vector<png_bytep> rows(static_cast<size_t>(height));
  for (int y = 0; y < height; ++y)
    rows[size_t(y)] = const_cast<png_bytep>(pixels + size_t(y) * size_t(width) * size_t(channels));
  std::vector<png_text> texts;
  for (const auto& [key, value] : text) {
    png_text t{};
    t.compression = PNG_TEXT_COMPRESSION_NONE;
    t.key = const_cast<char*>(key.c_str());
    t.text = const_cast<char*>(value.c_str());
    t.text_length = value.size();
    texts.push_back(t);
  }

  writeFileAtomically(path, [&](const fs::path& tmp) {
    std::FILE* file = std::fopen(tmp.c_str(), "wb");
    if (!file) throw RuntimeError("cannot create '" + tmp.string() + "': " + std::strerror(errno));
    PngErrorState error;
    bool ok = writePngStream(file, width, height, channels, rows.data(), texts.data(), int(texts.size()), &error);
    bool closed = std::fclose(file) == 0;
    if (!ok) throw RuntimeError("cannot write '" + path.string() + "': " + error.message);
    if (!closed) throw RuntimeError("cannot write '" + path.string() + "' (disk full?)");
  });
}

Image8 readPng(const fs::path& path) {
  const std::string name = path.string();
  std::error_code ec;
  if (!fs::exists(path, ec)) throw InputError("cannot read '" + name + "': no such file");
  std::FILE* file = std::fopen(path.c_str(), "rb");
  if (!file) throw InputError("cannot read '" + name + "': " + std::strerror(errno));
  png_byte signature[8] = {};
  if (std::fread(signature, 1, 8, file) != 8 || png_sig_cmp(signature, 0, 8) != 0) {
    std::fclose(file);
    throw InputError("cannot read '" + name + "': not a PNG file");
  }
  std::map<std::string, std::string> text = readTextChunks(file);
  std::fclose(file);
  // The simplified API reads with no longjmp in our frames and converts any layout to 8 bits.
  png_image image{};
  image.version = PNG_IMAGE_VERSION;
  if (!png_image_begin_read_from_file(&image, path.c_str()))
    throw InputError("cannot read '" + name + "': " + image.message);
  Image8 result;
  result.text = std::move(text);
  const bool alpha = (image.format & PNG_FORMAT_FLAG_ALPHA) != 0;
  const bool color = (image.format & PNG_FORMAT_FLAG_COLOR) != 0;
  image.format = color ? (alpha ? PNG_FORMAT_RGBA : PNG_FORMAT_RGB) : (alpha ? PNG_FORMAT_GA : PNG_FORMAT_GRAY);
  result.width = int(image.width);
  result.height = int(image.height);
  result.channels = int(PNG_IMAGE_SAMPLE_CHANNELS(image.format));
  result.pixels.resize(PNG_IMAGE_SIZE(image));
  if (!png_image_finish_read(&image, nullptr, result.pixels.data(), 0, nullptr)) {
    std::string message = image.message;
    png_image_free(&image);
    throw InputError("cannot read '" + name + "': " + message);
  }
  return result;
}

}  // namespace firmament
