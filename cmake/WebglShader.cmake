# cmake -DSPIRV_CROSS=exe -DIN=shader.spv -DOUT=file.inc -DNAME=symbol -P WebglShader.cmake
# A shader compiled by glslc (with -g: names kept, so WebGL binds by them) translated by
# spirv-cross to ESSL 3.00 for WebGL 2, as a C++ raw string constant (lib/report/viewer.cpp).
# Specialization constants stay `#ifndef SPIRV_CROSS_CONSTANT_ID_<id>` macros: a page defines
# a material's variant before compiling. Two fixes make it valid ESSL 3.00 under any variant:
#  - precision highp float: the renderer computes in fp32 (spirv-cross declares mediump by default);
#  - an index into a sampler array must be a constant expression in ESSL 3.00 (spirv-cross
#    writes `int i = max(SLOT, 0); textures[i]`, i from specialization constants only): such an
#    index variable is declared const. Any other index fails the build here.
execute_process(COMMAND ${SPIRV_CROSS} ${IN} --es --version 300 --output ${OUT}.essl
                RESULT_VARIABLE _rc ERROR_VARIABLE _err)
if(NOT _rc EQUAL 0)
  message(FATAL_ERROR "spirv-cross ${IN}: ${_err}")
endif()
file(READ ${OUT}.essl _text)
string(REPLACE "precision mediump float;" "precision highp float;" _text "${_text}")

string(REGEX MATCHALL "uniform highp sampler[A-Za-z0-9]+ [A-Za-z0-9_]+\\[[0-9]+\\];" _arrays "${_text}")
foreach(_decl IN LISTS _arrays)
  string(REGEX REPLACE "^uniform highp sampler[A-Za-z0-9]+ ([A-Za-z0-9_]+)\\[.*$" "\\1" _array "${_decl}")
  string(REGEX MATCHALL "[^A-Za-z0-9_]${_array}\\[[^]]*\\]" _uses "${_text}")
  foreach(_use IN LISTS _uses)
    string(REGEX REPLACE "^.${_array}\\[(.*)\\]$" "\\1" _index "${_use}")
    if(_index MATCHES "^[0-9]+$")
      continue()
    endif()
    if(NOT _index MATCHES "^[A-Za-z_][A-Za-z0-9_]*$")
      message(FATAL_ERROR "${IN}: ${_array}[${_index}]: a sampler array indexed by an expression (ESSL 3.00 takes constants only)")
    endif()
    string(REGEX MATCH "\n[ ]*(const )?int ${_index} = max\\([A-Z_]+, 0\\);" _def "${_text}")
    if(_def STREQUAL "")
      message(FATAL_ERROR "${IN}: ${_array}[${_index}]: ${_index} is not max(a specialization constant, 0); teach cmake/WebglShader.cmake its form")
    endif()
    string(REPLACE "int ${_index} = " "const int ${_index} = " _fixed "${_def}")
    string(REPLACE "const const" "const" _fixed "${_fixed}")
    string(REPLACE "${_def}" "${_fixed}" _text "${_text}")
  endforeach()
endforeach()
# The specialization constants are named where they are declared: the page's #defines follow
# the #version line, which must stay first.
if(NOT _text MATCHES "^#version 300 es\n")
  message(FATAL_ERROR "${IN}: spirv-cross wrote no '#version 300 es' first line")
endif()
file(WRITE ${OUT} "constexpr const char* ${NAME} = R\"matforge_essl(${_text})matforge_essl\";\n")
file(REMOVE ${OUT}.essl)
