#!/usr/bin/env bash
# Checks that every tracked C++ file (.h, .cpp) is formatted by .clang-format: exit 0 when all are,
# 1 with the list of files that differ (and how to fix them), 2 when clang-format 14 is missing.
# CTest runs it (tests/CMakeLists.txt). Shaders (.glsl, .comp) are not formatted by it.
set -uo pipefail
cd "$(dirname "$0")/.."
# Debian 12's clang-format is 14; another major version formats some constructs differently.
formatter=$(command -v clang-format-14 || command -v clang-format || true)
if [ -z "$formatter" ]; then
  echo "format_check: clang-format is not installed (Debian package clang-format)" >&2
  exit 2
fi
differ=()
while IFS= read -r file; do
  if ! "$formatter" --dry-run --Werror "$file" >/dev/null 2>&1; then differ+=("$file"); fi
done < <(git ls-files --cached --others --exclude-standard -- '*.h' '*.cpp')
if [ ${#differ[@]} -gt 0 ]; then
  echo "format_check: ${#differ[@]} file(s) differ from .clang-format; fix with: $formatter -i FILE" >&2
  printf '  %s\n' "${differ[@]}" >&2
  exit 1
fi
