# cmake -DIN=file -DOUT=file.cpp -P EmbedText.cmake: embeds a text file as firmament::sceneSchemaText().
file(READ ${IN} text)
file(WRITE ${OUT} "// Generated from ${IN}. Do not edit.\n#include <string_view>\nnamespace firmament {\nstd::string_view sceneSchemaText() {\n  return R\"FIRMAMENT_EMBED(${text})FIRMAMENT_EMBED\";\n}\n}  // namespace firmament\n")
