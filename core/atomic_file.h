#pragma once
// Every output file is written to a temporary file in the target's folder and then renamed over the
// target. rename(2) within one file system is atomic, so a reader sees either the old file or the
// complete new one: an interrupted or failed write never leaves a half-written target and never
// destroys an existing one (DESIGN.md, "Errors").
#include <filesystem>
#include <functional>
#include <string_view>

namespace firmament {

// Calls writer(tmp) with a fresh temporary path beside `target` (same folder, same extension, so
// libraries that look at the extension still work), flushes it to disk, then renames it to `target`.
// If the writer throws, or writes nothing, the temporary file is removed, `target` is left as it was
// and the exception propagates (a writer that creates no file gives RuntimeError).
// A missing target folder is an InputError naming it; a failed rename is a RuntimeError.
void writeFileAtomically(const std::filesystem::path& target,
                         const std::function<void(const std::filesystem::path& tmp)>& writer);

// Convenience: atomically replaces `target` with exactly `contents` (e.g. a stats JSON).
void writeTextFileAtomically(const std::filesystem::path& target, std::string_view contents);

}  // namespace firmament
