#pragma once
// A text file built into the program (cmake/EmbedFiles.cmake): its path relative to the folder it was
// embedded from, and its contents.
#include <span>
#include <string_view>

namespace firmament {

struct EmbeddedFile {
  std::string_view path;
  std::string_view text;
};

}  // namespace firmament
