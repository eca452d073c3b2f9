// `firmament timelapse SCENE --from UTC --to UTC --fps F --speed X --out DIR`: hours of simulated time to
// EXR + PNG frames, a CSV of per-frame metadata and an MP4 (ffmpeg). Resumable (every file is written
// atomically; a frame is done when its record frame_NNNNNN.json exists) and shardable (--frames A-B,
// --shard I/N, Slurm array variables); `--assemble DIR` makes the PNGs left to do, the CSV and the video.
// docs/timelapse.md describes the folder, the exposure and the determinism.
#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <memory>
#include <optional>
#include <sstream>

#include <nlohmann/json.hpp>

#include "firmament/image.h"
#include "firmament/sky.h"
#include "samples/firmament/command.h"
#include "samples/firmament/sequence_scene.h"

extern char** environ;

namespace firmament::cli {
namespace {

namespace fs = std::filesystem;
constexpr const char* kManifestName = "timelapse.json";
constexpr int kManifestFormat = 1;
constexpr int kMaxFrames = 10000000;

std::string frameStem(int i) {
  char name[32];
  std::snprintf(name, sizeof(name), "frame_%06d", i);
  return name;
}

// The options that decide the frames (the resume manifest holds them).
struct Plan {
  fs::path dir;
  std::string scenePath;  // as given; empty: the built-in scene
  std::string from, to;   // normalised (formatUtc)
  double fps = 30.0;
  double speed = 60.0;     // simulated seconds per video second
  double duration_s = 0;   // to - from
  int frames = 0;          // frame i at from + i * speed / fps, up to and including `to`
  std::string cameraPath;  // hash of the camera path's keys; empty: the scene's camera
  nlohmann::json scene;    // the base scene (time = from), resolved, for --assemble
  std::string sceneHash;
  double elapsed(int i) const { return double(i) * speed / fps; }
};

nlohmann::json manifestOf(const Plan& p) {
  return {{"format", kManifestFormat},
          {"scene_file", p.scenePath},
          {"scene_hash", p.sceneHash},
          {"from", p.from},
          {"to", p.to},
          {"fps", p.fps},
          {"speed", p.speed},
          {"frames", p.frames},
          {"camera_path", p.cameraPath},
          {"scene", p.scene}};
}

nlohmann::json readJson(const fs::path& file) {
  std::ifstream in(file);
  if (!in) throw InputError(file.string() + ": cannot read it");
  try {
    return nlohmann::json::parse(in);
  } catch (const std::exception& e) {
    throw InputError(file.string() + ": not valid JSON: " + e.what());
  }
}

// The canonical form of a time option (InputError naming the option).
std::string parseTime(const std::string& option, const std::string& text) {
  try {
    return canonicalUtc(text);
  } catch (const InputError& e) {
    throw InputError("--" + option + " " + text + ": " + e.what());
  }
}

// --frames A-B (inclusive, 0-based) or --shard I/N (I in 0..N-1, contiguous blocks), else the Slurm
// array's task (SLURM_ARRAY_TASK_ID - SLURM_ARRAY_TASK_MIN of SLURM_ARRAY_TASK_COUNT), else all frames.
struct Range {
  int first = 0, last = -1;  // inclusive; last < first: empty
  bool part = false;         // a part of the run: no CSV, no video (the assemble step makes them)
  std::string why;
};

Range shardRange(int index, int count, int frames) {
  Range r;
  r.first = int(int64_t(index) * frames / count);
  r.last = int(int64_t(index + 1) * frames / count) - 1;
  r.part = true;
  return r;
}

int parseCount(const std::string& text, const std::string& what) {
  char* end = nullptr;
  errno = 0;
  long v = std::strtol(text.c_str(), &end, 10);
  if (text.empty() || end == text.c_str() || *end != '\0' || errno != 0 || v < 0 || v > kMaxFrames)
    throw InputError(what);
  return int(v);
}

Range frameRange(const Args& args, int frames) {
  if (args.has("frames") && args.has("shard")) throw InputError("--frames and --shard: give one of them");
  if (auto f = args.get("frames")) {
    const std::string msg = "--frames " + *f + ": allowed: A-B, frame numbers from 0 to " + std::to_string(frames - 1) +
                            " with A <= B (this run has " + std::to_string(frames) + " frames)";
    const size_t dash = f->find('-');
    if (dash == std::string::npos) throw InputError(msg);
    Range r;
    r.first = parseCount(f->substr(0, dash), msg);
    r.last = parseCount(f->substr(dash + 1), msg);
    if (r.first > r.last || r.last >= frames) throw InputError(msg);
    r.part = !(r.first == 0 && r.last == frames - 1);
    r.why = "--frames " + *f;
    return r;
  }
  auto shard = [&](const std::string& text, const std::string& source) {
    const std::string msg =
        source + " " + text + ": allowed: I/N with N from 1 to " + std::to_string(kMaxFrames) + " and I from 0 to N-1";
    const size_t slash = text.find('/');
    if (slash == std::string::npos) throw InputError(msg);
    const int i = parseCount(text.substr(0, slash), msg), n = parseCount(text.substr(slash + 1), msg);
    if (n < 1 || i >= n) throw InputError(msg);
    Range r = shardRange(i, n, frames);
    r.part = n > 1;
    r.why = source + " " + text;
    return r;
  };
  if (auto s = args.get("shard")) return shard(*s, "--shard");
  const char* id = std::getenv("SLURM_ARRAY_TASK_ID");
  const char* count = std::getenv("SLURM_ARRAY_TASK_COUNT");
  if (id && count && *id && *count) {
    const char* min = std::getenv("SLURM_ARRAY_TASK_MIN");
    const std::string msg = std::string("SLURM_ARRAY_TASK_ID ") + id + ", SLURM_ARRAY_TASK_MIN " +
                            (min ? min : "(unset)") + ", SLURM_ARRAY_TASK_COUNT " + count +
                            ": allowed: an array of consecutive task ids (e.g. --array=0-3)";
    const int task = parseCount(id, msg), first = min && *min ? parseCount(min, msg) : 0;
    if (task < first) throw InputError(msg);
    return shard(std::to_string(task - first) + "/" + count, "Slurm array task");
  }
  return {0, frames - 1, false, ""};
}

// What one frame's record (frame_NNNNNN.json) keeps: what the CSV and the exposure need.
struct FrameRecord {
  double logAverage = 0.0;  // cd/m², of the EXR (the exposure's input)
  nlohmann::json json;
};

// ---- progress ----

class FrameProgress {
 public:
  FrameProgress(int total, int done) : total_(total), done_(done) {
    const char* forced = std::getenv("FIRMAMENT_PROGRESS");
    tty_ = forced ? std::strcmp(forced, "1") == 0 : ::isatty(2) != 0;
    if (quietOutput()) tty_ = false;
  }
  ~FrameProgress() {
    if (drawn_) std::fprintf(stderr, "\n");
  }
  void frameDone(int frame, const std::string& utc, double seconds) {
    ++done_;
    ++rendered_;
    sum_ += seconds;
    const double eta = sum_ / rendered_ * (total_ - done_);
    char etaText[32];
    const long e = long(std::lround(eta));
    std::snprintf(etaText, sizeof(etaText), "%ld:%02ld:%02ld", e / 3600, e / 60 % 60, e % 60);
    if (tty_) {
      const int width = 30, filled = total_ ? int(double(done_) / total_ * width) : width;
      std::string bar(size_t(filled), '=');
      if (filled < width) bar += '>' + std::string(size_t(width - filled - 1), ' ');
      std::fprintf(stderr, "\rtimelapse [%s] %d/%d frames  %.2f s/frame  ETA %s ", bar.c_str(), done_, total_, seconds,
                   etaText);
      std::fflush(stderr);
      drawn_ = true;
    } else {
      char line[200];
      std::snprintf(line, sizeof(line), "frame %d (%d/%d) %s  %.2f s  ETA %s", frame, done_, total_, utc.c_str(),
                    seconds, etaText);
      info(line);
    }
  }

 private:
  int total_, done_, rendered_ = 0;
  double sum_ = 0.0;
  bool tty_ = false, drawn_ = false;
};

// ---- the video ----

std::optional<std::string> findFfmpeg() {
  if (const char* forced = std::getenv("FIRMAMENT_FFMPEG"))
    return ::access(forced, X_OK) == 0 ? std::optional<std::string>(forced) : std::nullopt;
  const char* path = std::getenv("PATH");
  std::stringstream dirs(path ? path : "/usr/bin:/bin");
  std::string d;
  while (std::getline(dirs, d, ':')) {
    const fs::path candidate = fs::path(d.empty() ? "." : d) / "ffmpeg";
    if (::access(candidate.c_str(), X_OK) == 0) return candidate.string();
  }
  return std::nullopt;
}

int runProgram(const std::vector<std::string>& argv) {
  std::vector<char*> cargs;
  for (const auto& a : argv) cargs.push_back(const_cast<char*>(a.c_str()));
  cargs.push_back(nullptr);
  pid_t pid = 0;
  if (posix_spawn(&pid, cargs[0], nullptr, nullptr, cargs.data(), environ) != 0) return -1;
  int status = 0;
  while (waitpid(pid, &status, 0) < 0)
    if (errno != EINTR) return -1;
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

// ---- assemble: PNGs left to do, frames.csv, the video ----

struct AssembleOptions {
  std::string codec = "h264";
  bool video = true;
};

int assemble(const fs::path& dir, const AssembleOptions& options) {
  const fs::path manifestPath = dir / kManifestName;
  if (!fs::exists(manifestPath))
    throw InputError("--assemble " + dir.string() + ": no " + kManifestName + " there (not a time-lapse folder)");
  const nlohmann::json m = readJson(manifestPath);
  if (m.value("format", 0) != kManifestFormat || !m.contains("frames") || !m.contains("scene"))
    throw InputError(manifestPath.string() + ": not a time-lapse manifest of this version (format " +
                     std::to_string(kManifestFormat) + ")");
  const int frames = m["frames"].get<int>();
  const double fps = m["fps"].get<double>();
  std::vector<int> missing;
  for (int i = 0; i < frames; ++i)
    if (!fs::exists(dir / (frameStem(i) + ".json")) || !fs::exists(dir / (frameStem(i) + ".exr"))) missing.push_back(i);
  if (!missing.empty())
    throw InputError("--assemble " + dir.string() + ": " + std::to_string(missing.size()) + " of " +
                     std::to_string(frames) + " frames are missing (the first: " + std::to_string(missing.front()) +
                     "); render them first (the remaining shards, or the run again with --resume)");
  const Exposure exposure = Exposure::fromSceneJson(m["scene"].dump(), manifestPath.string() + "#/scene");

  // The exposure: the eye adaptation (core/tonemap.h) over video time, replayed from the records, so that
  // a frame's PNG is the same whichever process renders it.
  EyeAdaptation adaptation;
  std::ostringstream csv;
  csv << "frame,utc,elapsed_s,sun_altitude_deg,sun_azimuth_deg,moon_altitude_deg,moon_illuminated_fraction,"
         "log_average_cd_m2,adapted_cd_m2,ev100,weather_mean_coverage,weather_cloudy_fraction,"
         "weather_mean_precipitation_mm_h,weather_max_top_m,frame_wall_s\n";
  int written = 0;
  for (int i = 0; i < frames; ++i) {
    const nlohmann::json r = readJson(dir / (frameStem(i) + ".json"));
    const double adapted = adaptation.update(r.at("log_average_cd_m2").get<double>(), 1.0 / fps, exposure);
    const fs::path png = dir / (frameStem(i) + ".png");
    double ev100 = exposure.ev100For(adapted);
    if (!fs::exists(png)) {
      ev100 = exposure.savePng(loadExr((dir / (frameStem(i) + ".exr")).string()), png.string(), &adapted);
      ++written;
    }
    char line[512];
    const nlohmann::json w = r.value("weather", nlohmann::json::object());
    auto num = [](const nlohmann::json& j, const char* key) {
      return j.contains(key) ? j[key].get<double>() : std::nan("");
    };
    std::snprintf(line, sizeof(line), "%d,%s,%.3f,%.4f,%.4f,%.4f,%.4f,%.6g,%.6g,%.4f,%.4f,%.4f,%.4f,%.1f,%.3f\n", i,
                  r.at("utc").get<std::string>().c_str(), r.at("elapsed_s").get<double>(),
                  r.at("sun_altitude_deg").get<double>(), r.at("sun_azimuth_deg").get<double>(),
                  r.at("moon_altitude_deg").get<double>(), r.at("moon_illuminated_fraction").get<double>(),
                  r.at("log_average_cd_m2").get<double>(), adapted, ev100, num(w, "mean_coverage"),
                  num(w, "cloudy_fraction"), num(w, "mean_precipitation_mm_h"), num(w, "max_top_m"),
                  r.at("wall_s").get<double>());
    csv << line;
  }
  writeTextAtomically(dir / "frames.csv", csv.str());
  info("wrote " + (dir / "frames.csv").string() + " (" + std::to_string(frames) + " frames; " +
       std::to_string(written) + " PNGs made now)");
  if (!options.video) return kExitOk;

  const std::optional<std::string> ffmpeg = findFfmpeg();
  if (!ffmpeg) {
    std::fprintf(stderr,
                 "error: ffmpeg not found (on PATH, or FIRMAMENT_FFMPEG): no video made. The frames are complete in "
                 "%s; install ffmpeg (Debian: apt-get install ffmpeg) and run 'firmament timelapse --assemble %s'\n",
                 dir.c_str(), dir.c_str());
    return kExitRuntime;
  }
  // Written as timelapse.partial.mp4, renamed when ffmpeg succeeds: a kill during the encode never
  // leaves a half-written video under the final name.
  const fs::path video = dir / "timelapse.mp4", partial = dir / "timelapse.partial.mp4";
  char rate[32];
  std::snprintf(rate, sizeof(rate), "%.17g", fps);
  std::vector<std::string> argv = {
      *ffmpeg,      "-hide_banner", "-loglevel",     "error", "-nostdin", "-y",
      "-framerate", rate,           "-start_number", "0",     "-i",       (dir / "frame_%06d.png").string()};
  if (options.codec == "h264") {
    argv.insert(argv.end(), {"-c:v", "libx264", "-preset", "medium", "-crf", "18", "-pix_fmt", "yuv420p"});
  } else {
    argv.insert(argv.end(), {"-c:v", "libx265", "-preset", "medium", "-crf", "20", "-pix_fmt", "yuv420p10le", "-tag:v",
                             "hvc1", "-x265-params", "log-level=error"});
  }
  argv.insert(argv.end(), {"-movflags", "+faststart", partial.string()});
  const auto started = std::chrono::steady_clock::now();
  const int rc = runProgram(argv);
  if (rc != 0) {
    std::error_code ec;
    fs::remove(partial, ec);
    throw RuntimeError("ffmpeg (" + *ffmpeg + ") failed with exit status " + std::to_string(rc) + "; the frames in " +
                       dir.string() + " are complete");
  }
  std::error_code ec;
  fs::rename(partial, video, ec);
  if (ec) throw RuntimeError("cannot rename " + partial.string() + " to " + video.string() + ": " + ec.message());
  char summary[256];
  std::snprintf(summary, sizeof(summary), "wrote %s (%s, %d frames at %g fps, %.1f s to encode)", video.c_str(),
                options.codec == "h264" ? "H.264 yuv420p" : "H.265 10-bit", frames, fps,
                std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count());
  info(summary);
  return kExitOk;
}

AssembleOptions assembleOptions(const Args& args) {
  AssembleOptions a;
  a.codec = args.getOr("codec", "h264");
  if (a.codec != "h264" && a.codec != "h265")
    throw InputError("--codec " + a.codec + ": allowed: h264 (yuv420p, the default), h265 (10-bit)");
  a.video = !args.has("no-video");
  return a;
}

// Weather statistics of a frame's map (coverage, cloudy fraction, precipitation, highest top) and the
// simulation's start and length (one run for the whole sequence: Sky::setSequenceFrame).
nlohmann::json weatherStatistics(const Sky& sky) {
  const WeatherSummary w = sky.weather();
  if (!w.present) return nullptr;
  return {{"mean_coverage", w.meanCoverage},
          {"cloudy_fraction", w.cloudyFraction},
          {"mean_precipitation_mm_h", w.meanPrecipitation_mm_h},
          {"max_top_m", w.maxTop_m},
          {"start_utc", w.startUtc},
          {"run_h", w.run_h}};
}

// Removes what a killed writer of this range's frames left (".frame_NNNNNN.tmp-PID-N.EXT", core/atomic_file.h).
// Only this range's: another shard may be writing its own frames into the folder now.
void removeStaleTemporaries(const fs::path& dir, const Range& range) {
  std::error_code ec;
  for (const auto& entry : fs::directory_iterator(dir, ec)) {
    const std::string name = entry.path().filename().string();
    int frame = -1;
    if (name.rfind(".frame_", 0) == 0 && name.find(".tmp-") == 13 &&
        std::sscanf(name.c_str(), ".frame_%d", &frame) == 1 && frame >= range.first && frame <= range.last)
      fs::remove(entry.path(), ec);
  }
}

int runTimelapse(const Args& args) {
  if (auto dir = args.get("assemble")) {
    if (!args.positionals.empty())
      throw InputError("--assemble DIR reads the scene from DIR/" + std::string(kManifestName) +
                       ": give no SCENE with it");
    for (const char* o :
         {"from", "to", "fps", "speed", "out", "frames", "shard", "resume", "camera-path", "width", "height", "set"})
      if (args.has(o)) throw InputError(std::string("--assemble DIR takes only --codec and --no-video, not --") + o);
    return assemble(*dir, assembleOptions(args));
  }
  if (args.positionals.empty()) throw InputError("timelapse: give a SCENE (or --assemble DIR)");
  for (const char* required : {"from", "to", "out"})
    if (!args.has(required)) throw InputError(std::string("timelapse: --") + required + " is required");
  const AssembleOptions video = assembleOptions(args);

  Plan plan;
  plan.scenePath = args.positionals[0];
  plan.dir = *args.get("out");
  plan.from = parseTime("from", *args.get("from"));
  plan.to = parseTime("to", *args.get("to"));
  plan.duration_s = utcSecondsBetween(plan.from, plan.to);
  if (!(plan.duration_s > 0.0))
    throw InputError("--to " + plan.to + " is not after --from " + plan.from + ": allowed: a later time");
  if (plan.duration_s > 366.0 * 86400.0)
    throw InputError("--from " + plan.from + " --to " + plan.to + ": allowed: at most 366 days");
  plan.fps = args.number("fps", 30.0);
  if (!(plan.fps >= 1.0 && plan.fps <= 240.0)) throw InputError("--fps: allowed: 1 to 240 frames per second");
  plan.speed = args.number("speed", 60.0);
  if (!(plan.speed > 0.0 && plan.speed <= 86400.0 * 30.0))
    throw InputError("--speed: allowed: more than 0 and up to 2592000 simulated seconds per video second");
  const double count = std::floor(plan.duration_s * plan.fps / plan.speed + 1e-9) + 1.0;
  if (count > kMaxFrames)
    throw InputError("--from/--to/--fps/--speed give " + std::to_string(int64_t(count)) + " frames; allowed: up to " +
                     std::to_string(kMaxFrames) + " (raise --speed or lower --fps)");
  plan.frames = int(count);

  std::vector<std::string> overrides = args.all("set");
  if (auto w = args.get("width")) overrides.push_back("/camera/width=" + *w);
  if (auto h = args.get("height")) overrides.push_back("/camera/height=" + *h);
  overrides.push_back("/time/utc=" + plan.from);
  // Every frame is a still (no temporal reprojection across a time-lapse's steps, docs/decisions/0401): its
  // pixels depend on its own scene only, so a resumed or sharded run gives the same frames as one
  // uninterrupted run.
  Sky::Builder builder;
  builder.sceneFile(plan.scenePath).device(args.getOr("device", "")).temporalReprojection(false);
  for (const std::string& o : overrides) builder.set(o);
  const std::unique_ptr<Sky> sky = builder.build();  // the base scene: time = from
  auto number = [&](const std::string& pointer) { return nlohmann::json::parse(sky->get(pointer)).get<double>(); };
  if (!sky->get("/sun").empty())
    warn(plan.scenePath +
         ": has a sun section: the sun stays where it says (remove it to let the sun, moon "
         "and stars follow the clock)");
  const int width = int(number("/camera/width")), height = int(number("/camera/height"));
  if (video.video && (width % 2 || height % 2))
    throw InputError("image size " + std::to_string(width) + "x" + std::to_string(height) +
                     ": the video (4:2:0 chroma) needs an even width and height; allowed: even sizes, or --no-video");
  std::optional<CameraPath> cameraPath;
  if (auto file = args.get("camera-path")) {
    cameraPath = CameraPath::load(*file, cameraPoseOf(*sky));
    plan.cameraPath = cameraPath->hash();
  }
  plan.scene = nlohmann::json::parse(sky->sceneJson());
  plan.sceneHash = sky->sceneHash();
  const SkyCamera baseCamera = sky->camera();
  // Frame i's scene: the base plan.elapsed(i) later, on the camera path when there is one.
  auto frameScene = [&](int i, bool check) {
    const double t = plan.elapsed(i);
    if (cameraPath) {
      const SkyCamera camera = skyCameraOf(cameraPath->at(t), baseCamera);
      check ? sky->checkSequenceFrame(t, camera) : sky->setSequenceFrame(t, camera);
    } else {
      check ? sky->checkSequenceFrame(t) : sky->setSequenceFrame(t);
    }
  };
  frameScene(plan.frames - 1, true);  // a bad scene at the end fails before anything is written
  const Range range = frameRange(args, plan.frames);

  // The folder and the resume manifest: a folder of another scene or other options is refused.
  const fs::path manifestPath = plan.dir / kManifestName;
  if (args.has("resume") && !fs::exists(manifestPath))
    throw InputError("--resume: " + plan.dir.string() + " holds no time-lapse (no " + kManifestName + ")");
  std::error_code ec;
  fs::create_directories(plan.dir, ec);
  if (ec || !fs::is_directory(plan.dir))
    throw InputError("--out " + plan.dir.string() + ": cannot create the folder" + (ec ? ": " + ec.message() : ""));
  if (::access(plan.dir.c_str(), W_OK) != 0)
    throw InputError("--out " + plan.dir.string() + ": the folder is not writable");
  const nlohmann::json manifest = manifestOf(plan);
  if (fs::exists(manifestPath)) {
    const nlohmann::json old = readJson(manifestPath);
    for (const char* key : {"format", "scene_hash", "from", "to", "fps", "speed", "frames", "camera_path"})
      if (!old.contains(key) || old[key] != manifest[key])
        throw InputError("--out " + plan.dir.string() + " holds a time-lapse of " +
                         (std::string(key) == "scene_hash" ? "another scene" : "other options") + " (" + key + ": " +
                         (old.contains(key) ? old[key].dump() : "none") + " there, " + manifest[key].dump() +
                         " here): cannot resume it; name another --out folder or delete this one");
    info("resuming the time-lapse in " + plan.dir.string());
  } else {
    try {
      writeTextAtomically(manifestPath, manifest.dump(2) + "\n");
    } catch (const std::exception& e) {
      throw InputError("--out " + plan.dir.string() + ": cannot write " + kManifestName + ": " + e.what());
    }
  }
  removeStaleTemporaries(plan.dir, range);

  auto done = [&](int i) {
    return fs::exists(plan.dir / (frameStem(i) + ".json")) && fs::exists(plan.dir / (frameStem(i) + ".exr"));
  };
  std::vector<int> todo;
  for (int i = range.first; i <= range.last; ++i)
    if (!done(i)) todo.push_back(i);
  {
    char line[256];
    std::snprintf(line, sizeof(line), "%s: %d frames (%s to %s, %g fps, %gx)%s%s; frames %d-%d: %d to render",
                  plan.dir.c_str(), plan.frames, plan.from.c_str(), plan.to.c_str(), plan.fps, plan.speed,
                  range.why.empty() ? "" : ", ", range.why.c_str(), range.first, range.last, int(todo.size()));
    info(line);
  }

  const Exposure exposure(*sky);
  if (!todo.empty()) {
    info("device: " + sky->deviceDescription());

    // The exposure's state before the first frame to render, replayed from the records of the frames before
    // it; when one is missing (another shard's), the PNGs wait for --assemble.
    EyeAdaptation adaptation;
    bool adaptationKnown = true;
    for (int i = 0; i < todo.front() && adaptationKnown; ++i) {
      if (!done(i)) {
        adaptationKnown = false;
        break;
      }
      adaptation.update(readJson(plan.dir / (frameStem(i) + ".json")).at("log_average_cd_m2").get<double>(),
                        1.0 / plan.fps, exposure);
    }
    FrameProgress progress(range.last - range.first + 1, range.last - range.first + 1 - int(todo.size()));
    int previous = todo.front() - 1;
    for (int i : todo) {
      const auto started = std::chrono::steady_clock::now();
      if (i != previous + 1 && adaptationKnown) {  // a gap of frames already done: replay their records
        for (int j = previous + 1; j < i; ++j)
          adaptation.update(readJson(plan.dir / (frameStem(j) + ".json")).at("log_average_cd_m2").get<double>(),
                            1.0 / plan.fps, exposure);
      }
      previous = i;
      frameScene(i, false);
      SkyFrame frame = sky->render(width, height);
      // The EXR keeps the scene's metadata but not the per-pass timings: a frame's file is the same whichever
      // process renders it (the timings go to the record).
      for (auto it = frame.metadata.begin(); it != frame.metadata.end();)
        it = it->first.rfind("firmament.timing", 0) == 0 ? frame.metadata.erase(it) : std::next(it);
      const std::string stem = frameStem(i);
      saveExr(frame, (plan.dir / (stem + ".exr")).string());
      const double logAverage = logAverageLuminance(frame);
      double ev100 = std::nan("");
      if (adaptationKnown) {
        const double adapted = adaptation.update(logAverage, 1.0 / plan.fps, exposure);
        ev100 = exposure.savePng(frame, (plan.dir / (stem + ".png")).string(), &adapted);
      }
      const std::string utc = nlohmann::json::parse(sky->get("/time/utc")).get<std::string>();
      const CameraPose pose = cameraPoseOf(*sky);
      nlohmann::json record = {{"frame", i},
                               {"utc", utc},
                               {"elapsed_s", plan.elapsed(i)},
                               {"sun_altitude_deg", 90.0 - frame.sunZenith_deg},
                               {"sun_azimuth_deg", frame.sunAzimuth_deg},
                               {"moon_altitude_deg", frame.moonAltitude_deg},
                               {"moon_illuminated_fraction", frame.moonIlluminatedFraction},
                               {"log_average_cd_m2", logAverage},
                               {"camera",
                                {{"yaw_deg", pose.yaw_deg},
                                 {"pitch_deg", pose.pitch_deg},
                                 {"height_above_ground_m", pose.height_above_ground_m},
                                 {"fov_deg", pose.fov_deg}}},
                               {"weather", weatherStatistics(*sky)},
                               {"scene_hash", frame.sceneHash},
                               {"device", sky->deviceDescription()},
                               {"gpu_frame_ms", frame.gpuMilliseconds}};
      if (std::isfinite(ev100)) record["preview_ev100"] = ev100;
      const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
      record["wall_s"] = seconds;
      // The record last: a frame is done when its record exists (its EXR and PNG are there by then).
      writeTextAtomically(plan.dir / (stem + ".json"), record.dump(2) + "\n");
      progress.frameDone(i, utc, seconds);
    }
  }
  if (range.part) {
    info("frames " + std::to_string(range.first) + "-" + std::to_string(range.last) +
         " done; once every part is: firmament timelapse --assemble " + plan.dir.string());
    return kExitOk;
  }
  return assemble(plan.dir, video);
}

const CommandRegistration reg{
    {"timelapse",
     "hours of simulated time to EXR/PNG frames, a CSV and an MP4; resumable; shardable (Slurm)",
     "timelapse SCENE --from UTC --to UTC --out DIR [--fps F] [--speed X] [--camera-path FILE] "
     "[--frames A-B | --shard I/N] [--resume] [--codec h264|h265] [--no-video] [--width W --height H] "
     "[--set /PATH=VALUE]... [--device D]  |  timelapse --assemble DIR [--codec h264|h265] [--no-video]",
     {{"from", "UTC", "start time, ISO 8601 (e.g. 2026-06-21T12:00:00Z); the scene's /time/utc is replaced"},
      {"to", "UTC", "end time (after --from; at most 366 days later); the last frame is at or before it"},
      {"fps", "F", "video frames per second (1-240, default 30)"},
      {"speed", "X", "simulated seconds per video second (default 60); a frame every X/F simulated seconds"},
      {"out", "DIR",
       "output folder: frame_NNNNNN.exr/.png/.json, frames.csv, timelapse.mp4, timelapse.json (the resume "
       "manifest)"},
      {"camera-path", "FILE",
       "camera keyframes, JSON {\"keys\": [{\"time_s\", \"yaw_deg\", \"pitch_deg\"[, \"height_above_ground_m\"]"
       "[, \"fov_deg\"]}...]}, time_s after --from; a smooth (Catmull-Rom) path between them"},
      {"frames", "A-B", "render only frames A to B (0-based, inclusive); no CSV or video (see --assemble)"},
      {"shard", "I/N",
       "render only part I of N (I from 0; contiguous blocks); default from SLURM_ARRAY_TASK_ID - "
       "SLURM_ARRAY_TASK_MIN and SLURM_ARRAY_TASK_COUNT"},
      {"resume", "",
       "continue the run in DIR (also the default when DIR holds one of the same scene and options); fails "
       "when DIR holds none"},
      {"assemble", "DIR", "once every frame exists: the PNGs not yet made, frames.csv and the video"},
      {"codec", "h264|h265", "h264: H.264 yuv420p (default); h265: H.265 10-bit (yuv420p10le); both +faststart"},
      {"no-video", "", "write the frames and the CSV, no MP4"},
      {"width", "W", "image width (same as --set /camera/width=W); even for the video"},
      {"height", "H", "image height; even for the video"},
      setOption(),
      deviceOption()},
     0,
     1,
     runTimelapse}};

}  // namespace
}  // namespace firmament::cli
