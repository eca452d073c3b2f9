# cmake -DIN=file -DOUT=file.cpp -DNAME=function -P EmbedText.cmake: embeds a text file as
# `std::string_view firmament::NAME()`.
file(READ ${IN} text)
file(WRITE ${OUT} "// Generated from ${IN}. Do not edit.\n#include <string_view>\nnamespace firmament {\nstd::string_view ${NAME}() {\n  return R\"FIRMAMENT_EMBED(${text})FIRMAMENT_EMBED\";\n}\n}  // namespace firmament\n")
