// firmament: the command-line tool. `firmament --help` lists the subcommands; each has --help.
#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <string>

#include "core/atomic_file.h"
#include "core/error.h"
#include "core/log.h"
#include "samples/firmament/command.h"

namespace firmament::cli {
namespace {

std::map<std::string, Command>& registry() {
  static std::map<std::string, Command> map;
  return map;
}

void printCommandHelp(const Command& c) {
  std::printf("usage: firmament %s\n\n%s\n", c.usage.c_str(), c.summary.c_str());
  if (!c.options.empty()) std::printf("\noptions:\n");
  for (const auto& o : c.options) {
    std::string left = o.shortName ? std::string("-") + o.shortName + ", --" + o.name : "    --" + o.name;
    if (!o.value.empty()) left += " " + o.value;
    std::printf("  %-28s %s%s\n", left.c_str(), o.help.c_str(), o.repeatable ? " (repeatable)" : "");
  }
  std::printf("  %-28s %s\n", "    --help", "show this help");
}

void printMainHelp() {
  std::printf(
      "usage: firmament [--version] [--quiet|--verbose] <command> [args]\n\n"
      "Firmament: a physically based sky on Vulkan compute (lavapipe when there is no GPU).\n\n"
      "commands:\n");
  for (const auto& [name, c] : registry()) std::printf("  %-12s %s\n", name.c_str(), c.summary.c_str());
  std::printf(
      "\n'firmament <command> --help' describes a command. Exit codes: 0 ok, 2 bad input, 3 runtime "
      "or device failure.\n");
}

const OptionSpec* findOption(const Command& c, const std::string& name, char shortName) {
  for (const auto& o : c.options)
    if ((!name.empty() && o.name == name) || (shortName && o.shortName == shortName)) return &o;
  return nullptr;
}

Args parse(const Command& c, int argc, char** argv, int first) {
  Args args;
  for (int i = first; i < argc; ++i) {
    std::string a = argv[i];
    if (a.size() > 1 && a[0] == '-' &&
        !(a.size() > 1 && (std::isdigit(static_cast<unsigned char>(a[1])) || a[1] == '.'))) {
      std::string name, value;
      bool hasValue = false;
      const OptionSpec* spec = nullptr;
      if (a.rfind("--", 0) == 0) {
        name = a.substr(2);
        if (auto eq = name.find('='); eq != std::string::npos) {
          value = name.substr(eq + 1);
          name = name.substr(0, eq);
          hasValue = true;
        }
        spec = findOption(c, name, 0);
      } else if (a.size() == 2) {
        spec = findOption(c, "", a[1]);
      }
      if (!spec)
        throw InputError("firmament " + c.name + ": unknown option '" + a + "' (see 'firmament " + c.name +
                         " --help')");
      if (spec->value.empty()) {
        if (hasValue) throw InputError("firmament " + c.name + ": option --" + spec->name + " takes no value");
        args.add(spec->name, "");
        continue;
      }
      if (!hasValue) {
        if (i + 1 >= argc)
          throw InputError("firmament " + c.name + ": option --" + spec->name + " needs a value " + spec->value);
        value = argv[++i];
      }
      if (args.has(spec->name) && !spec->repeatable)
        throw InputError("firmament " + c.name + ": option --" + spec->name + " given twice");
      args.add(spec->name, value);
    } else {
      args.positionals.push_back(a);
    }
  }
  int n = int(args.positionals.size());
  if (n < c.minPositionals || n > c.maxPositionals)
    throw InputError("firmament " + c.name + ": expected " +
                     (c.minPositionals == c.maxPositionals
                          ? std::to_string(c.minPositionals)
                          : std::to_string(c.minPositionals) + " to " + std::to_string(c.maxPositionals)) +
                     " argument(s), got " + std::to_string(n) + "; usage: firmament " + c.usage);
  return args;
}

}  // namespace

CommandRegistration::CommandRegistration(Command command) {
  std::string name = command.name;
  registry().emplace(std::move(name), std::move(command));
}

const std::map<std::string, Command>& commands() { return registry(); }

OptionSpec setOption() {
  return {"set", "/PATH=VALUE", "override a scene field by JSON pointer, e.g. --set /camera/fov_deg=60", true};
}
void refuseOverwritingInput(const std::filesystem::path& output, const std::filesystem::path& input) {
  for (const char* extension : {".exr", ".png", ".json"}) {
    const std::filesystem::path written = std::filesystem::path(output).replace_extension(extension);
    std::error_code error;  // equivalent() fails (false) where either does not exist yet
    if (written.filename() == input.filename() && std::filesystem::equivalent(written, input, error))
      throw InputError("-o " + output.string() + ": would overwrite the input " + input.string() + " with " +
                       written.string() + " (written are OUT.exr, OUT.png and OUT.json); name another output");
  }
}

OptionSpec deviceOption() {
  return {"device", "NAME|INDEX", "Vulkan device by index or part of its name (default: a GPU if any, else lavapipe)"};
}

std::optional<std::string> Args::get(const std::string& name) const {
  auto it = values_.find(name);
  if (it == values_.end() || it->second.empty()) return std::nullopt;
  return it->second.back();
}
std::vector<std::string> Args::all(const std::string& name) const {
  auto it = values_.find(name);
  return it == values_.end() ? std::vector<std::string>{} : it->second;
}
std::string Args::getOr(const std::string& name, const std::string& fallback) const {
  auto v = get(name);
  return v ? *v : fallback;
}
std::string formatNumber(const char* pattern, double value) {
  char buffer[64];
  std::snprintf(buffer, sizeof(buffer), pattern, value);
  return buffer;
}

double Args::number(const std::string& name, double fallback) const {
  auto v = get(name);
  if (!v) return fallback;
  char* end = nullptr;
  double d = std::strtod(v->c_str(), &end);
  if (end == v->c_str() || *end != '\0' || !std::isfinite(d))
    throw InputError("option --" + name + ": '" + *v + "' is not a number");
  return d;
}
int Args::integer(const std::string& name, int fallback, int minimum, int maximum) const {
  auto v = get(name);
  if (!v) return fallback;
  char* end = nullptr;
  long d = std::strtol(v->c_str(), &end, 10);
  if (end == v->c_str() || *end != '\0' || d < minimum || d > maximum)
    throw InputError("option --" + name + ": '" + *v + "' is not an integer in [" + std::to_string(minimum) + ", " +
                     std::to_string(maximum) + "]");
  return int(d);
}

void info(const std::string& message) { ::firmament::logInfo(message); }
void warn(const std::string& message) { ::firmament::logWarning(message); }
bool quietOutput() { return ::firmament::logLevel() == LogLevel::Quiet; }
struct ProgressBar::Bar {
  Bar(const std::string& label, uint64_t total) : progress(label, total) {}
  Progress progress;
};
ProgressBar::ProgressBar(const std::string& label, uint64_t total) : bar_(std::make_unique<Bar>(label, total)) {}
ProgressBar::~ProgressBar() = default;
void ProgressBar::advance() { bar_->progress.advance(); }
void writeTextAtomically(const std::filesystem::path& path, const std::string& text) {
  writeTextFileAtomically(path, text);
}

}  // namespace firmament::cli

int main(int argc, char** argv) {
  using namespace firmament;
  using namespace firmament::cli;
  int i = 1;
  for (; i < argc && argv[i][0] == '-'; ++i) {
    std::string a = argv[i];
    if (a == "--version") {
      std::printf("firmament %s\n", FIRMAMENT_VERSION);
      return kExitOk;
    } else if (a == "--help" || a == "-h") {
      printMainHelp();
      return kExitOk;
    } else if (a == "--quiet" || a == "-q") {
      setLogLevel(LogLevel::Quiet);
    } else if (a == "--verbose" || a == "-v") {
      setLogLevel(LogLevel::Verbose);
    } else {
      std::fprintf(stderr, "firmament: unknown option '%s' (see 'firmament --help')\n", argv[i]);
      return kExitBadInput;
    }
  }
  if (i >= argc) {
    printMainHelp();
    return kExitBadInput;
  }
  auto it = commands().find(argv[i]);
  if (it == commands().end()) {
    std::fprintf(stderr, "firmament: unknown command '%s' (see 'firmament --help')\n", argv[i]);
    return kExitBadInput;
  }
  const Command& command = it->second;
  for (int j = i + 1; j < argc; ++j)
    if (std::strcmp(argv[j], "--help") == 0 || std::strcmp(argv[j], "-h") == 0) {
      printCommandHelp(command);
      return kExitOk;
    }
  return runReportingErrors([&] { return command.run(parse(command, argc, argv, i + 1)); });
}
