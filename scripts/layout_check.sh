#!/usr/bin/env bash
# Checks the house rules that a build cannot: run from anywhere, exit 0 when all hold, 1 otherwise
# (each broken rule printed with the files that break it). CTest runs it (tests/CMakeLists.txt).
#
#   1. The renderer does not link or include the evaluation code: nothing under sky/ (nor the layers
#      below it) includes "eval/...", and no CMakeLists.txt of those layers links firmament_eval.
#   2. The renderer writes no files: no file under sky/ opens a file for writing (ofstream, fopen,
#      writeExr/writePng, the atomic writers). Writing outputs belongs to the tool (samples/).
#   3. Code, docs and test names say what and why, never when: no work-period number (the word in
#      $period below, followed by a count) appears in the tracked sources, scripts, scenes or docs.
#      Scratch folders (/tmp/...) are not named
#      outside tests and scripts.
set -uo pipefail
cd "$(dirname "$0")/.."
failed=0

report() {  # report RULE OUTPUT
  if [ -n "$2" ]; then
    echo "layout_check: $1" >&2
    echo "$2" | sed 's/^/  /' >&2
    failed=1
  fi
}

renderer_layers=(core gpu astro weather atmosphere clouds sky shaders)

# 1. One-way dependencies: the renderer's layers never reach eval/.
report "the renderer includes the evaluation code (eval/ sits above sky/)" \
  "$(git grep --untracked -n -E '#include "eval/' -- "${renderer_layers[@]/%//}" 2>/dev/null)"
report "a renderer layer links firmament_eval" \
  "$(git grep --untracked -n 'firmament_eval' -- $(printf '%s/CMakeLists.txt ' "${renderer_layers[@]}") 2>/dev/null)"

# 2. sky/ writes no files.
report "a file under sky/ writes files (the tool writes outputs: samples/firmament/)" \
  "$(git grep --untracked -n -E 'std::ofstream|ofstream\b|fopen\(|writeExr|writePng|writePngPreview|writeTextFileAtomically|writeFileAtomically|std::filesystem::(rename|create_directories|copy)' -- sky/ 2>/dev/null)"

# 3. No history in the tree: the work-period word in any tracked text file, and no scratch paths outside
# tests/scripts. The word is spelt in two parts so that this file passes its own check.
period="sess""ion"
report "\"$period\" names a time, not a reason: say what and why" \
  "$(git grep --untracked -n -i -E "\\b${period}s?\\b" -- . 2>/dev/null)"
report "a scratch folder (/tmp/...) is named outside tests/ and scripts/" \
  "$(git grep --untracked -n '/tmp/' -- . ':!tests/' ':!scripts/' ':!.ci/' 2>/dev/null)"

if [ $failed = 0 ]; then
  echo "layout_check: the renderer is apart from eval/, sky/ writes no files, no \"$period\" anywhere"
fi
exit $failed
