#pragma once
// Scripted input for `firmament view --script FILE`: one command a line, each run at the start of one
// frame, so a test can fly the viewer with no person at it (docs/viewer.md, "Scripts").
//   key KEYS SECONDS     fly as if KEYS (W A S D Q E) were held for SECONDS at the current speed
//   drag DX DY           a mouse drag of DX, DY pixels (turns the camera)
//   speed M_PER_S        flying speed
//   advance HOURS        moves /time/utc by HOURS (may be negative)
//   set /POINTER=VALUE   any scene field, as --set
//   wait FRAMES          renders FRAMES frames with no input
//   screenshot OUT.exr   a still of the view: OUT.exr, OUT.png and the view as OUT.view.json
//   save OUT.json        the view as a scene file
//   quit                 ends the viewer (so does the end of the script)
// Blank lines and lines starting with '#' are skipped.
#include <filesystem>
#include <string>
#include <vector>

namespace firmament::viewer {

struct ScriptCommand {
  enum class Kind { Key, Drag, Speed, Advance, Set, Wait, Screenshot, Save, Quit };
  Kind kind = Kind::Quit;
  std::string text;  // keys, the override, or the output path
  double a = 0.0, b = 0.0;
  int line = 0;
};

// InputError naming FILE:LINE, the command and the allowed ones, for any malformed line.
std::vector<ScriptCommand> loadScript(const std::filesystem::path& file);
std::vector<ScriptCommand> parseScript(const std::string& text, const std::string& source);

}  // namespace firmament::viewer
