#pragma once
// Subcommands of the `firmament` tool. Each cmd_*.cpp registers one with a static Command object;
// main.cpp dispatches by name, maps exceptions to exit codes and prints help.
#include <cstdint>
#include <filesystem>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace firmament::cli {

// Parsed arguments: options ("--name value" or "--name=value"; repeatable ones keep every value),
// switches ("--name") and positionals, checked against what the subcommand declares.
struct OptionSpec {
  std::string name;   // without dashes, e.g. "width"
  std::string value;  // metavariable, e.g. "W"; empty for a switch
  std::string help;
  bool repeatable = false;
  char shortName = 0;  // e.g. 'o' for -o
};

class Args {
 public:
  std::vector<std::string> positionals;
  bool has(const std::string& name) const { return values_.count(name) != 0; }
  std::optional<std::string> get(const std::string& name) const;
  std::vector<std::string> all(const std::string& name) const;
  std::string getOr(const std::string& name, const std::string& fallback) const;
  // Number parsing that names the option in its error (InputError, exit 2).
  double number(const std::string& name, double fallback) const;
  int integer(const std::string& name, int fallback, int minimum, int maximum) const;
  void add(const std::string& name, const std::string& value) { values_[name].push_back(value); }

 private:
  std::map<std::string, std::vector<std::string>> values_;
};

struct Command {
  std::string name;
  std::string summary;
  std::string usage;  // e.g. "render [SCENE] [-o OUT.exr] ..."
  std::vector<OptionSpec> options;
  int minPositionals = 0;
  int maxPositionals = 0;
  std::function<int(const Args&)> run;
};

// Registers a subcommand at static-initialisation time.
struct CommandRegistration {
  explicit CommandRegistration(Command command);
};

const std::map<std::string, Command>& commands();

// One number through a printf pattern ("%g", "%.9g", ...) for messages and metadata.
std::string formatNumber(const char* pattern, double value);

// Options every scene-taking command shares.
OptionSpec setOption();     // --set /json/pointer=value (repeatable)
OptionSpec deviceOption();  // --device NAME|INDEX

// InputError when `output` (OUT.exr) or a file written beside it (OUT.png, OUT.json) is the input file
// `input`: a render's stats JSON must not overwrite SCENE.json when -o names SCENE.exr beside it.
void refuseOverwritingInput(const std::filesystem::path& output, const std::filesystem::path& input);

// The tool's messages on stderr (--quiet hides info, never warnings) and its progress bar (drawn only on a
// terminal and past one second), for the commands that reach the renderer through the public API only.
void info(const std::string& message);
void warn(const std::string& message);
class ProgressBar {
 public:
  ProgressBar(const std::string& label, uint64_t total);
  ~ProgressBar();
  ProgressBar(const ProgressBar&) = delete;
  ProgressBar& operator=(const ProgressBar&) = delete;
  void advance();

 private:
  struct Bar;
  std::unique_ptr<Bar> bar_;
};
bool quietOutput();  // --quiet given
// Writes a text file atomically (a temporary beside it, then a rename): a kill never leaves half a file.
void writeTextAtomically(const std::filesystem::path& path, const std::string& text);

}  // namespace firmament::cli
