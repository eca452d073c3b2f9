# cmake -DROOT=dir -DOUT=file.cpp -DNAME=function -DFILES="a|b" -P EmbedFiles.cmake: embeds text files as
# `std::span<const firmament::EmbeddedFile> firmament::NAME()`, each named by its path relative to ROOT.
set(body "")
string(REPLACE "|" ";" FILES "${FILES}")
foreach(file IN LISTS FILES)
  file(RELATIVE_PATH rel ${ROOT} ${file})
  file(READ ${file} text)
  string(APPEND body "    {\"${rel}\", R\"FIRMAMENT_EMBED(${text})FIRMAMENT_EMBED\"},\n")
endforeach()
file(WRITE ${OUT}.tmp "// Generated from the files under ${ROOT}. Do not edit.\n#include \"core/embedded_file.h\"\nnamespace firmament {\nstd::span<const EmbeddedFile> ${NAME}() {\n  static const EmbeddedFile files[] = {\n${body}  };\n  return files;\n}\n}  // namespace firmament\n")
file(COPY_FILE ${OUT}.tmp ${OUT} ONLY_IF_DIFFERENT)
file(REMOVE ${OUT}.tmp)
