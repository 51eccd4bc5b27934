# cmake -DIN=file -DOUT=file.inc -DNAME=symbol -P EmbedText.cmake : a C++ raw string constant.
file(READ ${IN} _text)
file(WRITE ${OUT} "constexpr const char* ${NAME} = R\"matforge_embed(${_text})matforge_embed\";\n")
