# matforge_test(name SOURCES... LIBS ...): one GoogleTest program, discovered by ctest.
function(matforge_test name)
  cmake_parse_arguments(T "" "" "SOURCES;LIBS" ${ARGN})
  if(NOT T_SOURCES)
    return()
  endif()
  add_executable(test_${name} ${T_SOURCES})
  matforge_target_defaults(test_${name})
  target_link_libraries(test_${name} PRIVATE ${T_LIBS} GTest::gtest_main GTest::gmock)
  target_include_directories(test_${name} PRIVATE ${PROJECT_SOURCE_DIR}/tests/common)
  target_compile_definitions(test_${name} PRIVATE
    MATFORGE_SOURCE_DIR="${PROJECT_SOURCE_DIR}"
    MATFORGE_BINARY_DIR="${PROJECT_BINARY_DIR}")
  gtest_discover_tests(test_${name} DISCOVERY_TIMEOUT 60
    PROPERTIES ENVIRONMENT "MATFORGE_SOURCE_DIR=${PROJECT_SOURCE_DIR}")
endfunction()
