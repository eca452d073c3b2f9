#include "samples/viewer/script.h"

#include <cmath>
#include <fstream>
#include <sstream>

#include "core/error.h"
#include "samples/viewer/fly_camera.h"

namespace firmament::viewer {

std::vector<ScriptCommand> loadScript(const std::filesystem::path& file) {
  std::ifstream in(file);
  if (!in) throw InputError(file.string() + ": cannot read the script");
  std::stringstream buffer;
  buffer << in.rdbuf();
  return parseScript(buffer.str(), file.string());
}

std::vector<ScriptCommand> parseScript(const std::string& text, const std::string& source) {
  std::vector<ScriptCommand> commands;
  std::istringstream lines(text);
  std::string line;
  int number = 0;
  while (std::getline(lines, line)) {
    ++number;
    std::istringstream words(line);
    std::string name;
    if (!(words >> name) || name[0] == '#') continue;
    const std::string where = source + ":" + std::to_string(number) + ": " + name;
    auto number_ = [&](const char* what) {
      std::string word;
      if (!(words >> word)) throw InputError(where + ": needs " + what);
      char* end = nullptr;
      const double v = std::strtod(word.c_str(), &end);
      if (end == word.c_str() || *end != '\0' || !std::isfinite(v))
        throw InputError(where + ": '" + word + "' is not a number (" + what + ")");
      return v;
    };
    auto word_ = [&](const char* what) {
      std::string word;
      if (!(words >> word)) throw InputError(where + ": needs " + what);
      return word;
    };
    ScriptCommand c;
    c.line = number;
    using K = ScriptCommand::Kind;
    if (name == "key") {
      c.kind = K::Key;
      c.text = word_("KEYS (W A S D Q E)");
      try {
        parseKeys(c.text);
      } catch (const InputError& e) {
        throw InputError(where + ": " + e.what());
      }
      c.a = number_("SECONDS");
      if (c.a < 0.0 || c.a > 3600.0) throw InputError(where + ": SECONDS: allowed: 0 to 3600");
    } else if (name == "drag") {
      c.kind = K::Drag;
      c.a = number_("DX (pixels)");
      c.b = number_("DY (pixels)");
    } else if (name == "speed") {
      c.kind = K::Speed;
      c.a = number_("M_PER_S");
      if (c.a < kMinSpeed_m_s || c.a > kMaxSpeed_m_s)
        throw InputError(where + ": allowed: " + std::to_string(int(kMinSpeed_m_s)) + " to " +
                         std::to_string(int(kMaxSpeed_m_s)) + " m/s");
    } else if (name == "advance") {
      c.kind = K::Advance;
      c.a = number_("HOURS");
      if (std::abs(c.a) > 24.0 * 366.0) throw InputError(where + ": HOURS: allowed: -8784 to 8784");
    } else if (name == "set") {
      c.kind = K::Set;
      c.text = word_("/POINTER=VALUE");
    } else if (name == "wait") {
      c.kind = K::Wait;
      c.a = number_("FRAMES");
      if (c.a < 1.0 || c.a > 100000.0 || c.a != std::floor(c.a))
        throw InputError(where + ": FRAMES: allowed: an integer from 1 to 100000");
    } else if (name == "screenshot") {
      c.kind = K::Screenshot;
      c.text = word_("OUT.exr");
      if (std::filesystem::path(c.text).extension() != ".exr")
        throw InputError(where + ": " + c.text + ": the screenshot must end in .exr (the .png goes beside it)");
    } else if (name == "save") {
      c.kind = K::Save;
      c.text = word_("OUT.json");
      if (std::filesystem::path(c.text).extension() != ".json")
        throw InputError(where + ": " + c.text + ": a scene file must end in .json");
    } else if (name == "quit") {
      c.kind = K::Quit;
    } else {
      throw InputError(where +
                       ": unknown command; allowed: key, drag, speed, advance, set, wait, screenshot, save, quit");
    }
    std::string extra;
    if (words >> extra) throw InputError(where + ": unexpected '" + extra + "' after the command");
    commands.push_back(c);
  }
  return commands;
}

}  // namespace firmament::viewer
