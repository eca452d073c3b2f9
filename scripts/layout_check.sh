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
#   4. The tool's rendering commands reach Firmament through the public API only: render, timelapse and
#      view (samples/firmament/cmd_render.cpp, cmd_timelapse.cpp, cmd_view.cpp, render_outputs.*,
#      sequence_scene.*) include no Firmament header but include/firmament/ ("firmament/...") and the
#      tool's own (samples/firmament/, samples/viewer/); docs/decisions/0502 says why the evaluation
#      commands may still link eval/.
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

# 4. The rendering commands use the public API only.
public_only=(samples/firmament/cmd_render.cpp samples/firmament/cmd_timelapse.cpp samples/firmament/cmd_view.cpp
  samples/firmament/render_outputs.h samples/firmament/render_outputs.cpp samples/firmament/sequence_scene.h
  samples/firmament/sequence_scene.cpp)
report "a rendering command includes an internal header (use include/firmament/, docs/api.md)" \
  "$(git grep --untracked -n -E '#include "' -- "${public_only[@]}" 2>/dev/null |
    grep -v -E '#include "(firmament|samples/firmament|samples/viewer)/')"

if [ $failed = 0 ]; then
  echo "layout_check: the renderer is apart from eval/, sky/ writes no files, no \"$period\" anywhere, the rendering commands include only the public API"
fi
exit $failed
