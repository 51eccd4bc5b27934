# matforge_test(name [RUNS_BINARY] [LOCK name] [SLOW regex...] [ENGINE_PROOF regex...] SOURCES...
# LIBS ...): one
# GoogleTest program, discovered by ctest. Every test gets a ctest label: `unit` (in-process) or
# `integration` (RUNS_BINARY), and `slow` when its name matches one of the SLOW regular
# expressions (anchored; each with its reason in the caller's CMakeLists.txt): the sanitizer
# stage of scripts/test.sh runs `ctest -LE slow`, and the release stage before it only `-L slow`
# (scripts/test.sh alone runs everything in release). LOCK: its tests never run at the same time
# as another test holding that ctest RESOURCE_LOCK (tests that share costly results through the
# test cache: the first computes, the others restore, instead of all computing at once under
# ctest -j). ENGINE_PROOF: the tests (anchored regular expressions) in which a real engine or DCC
# opens what matforge wrote (OpenUSD, Blender, Godot, MaterialX, libktx, three.js): label
# `engine-proof`, so `ctest -L engine-proof` runs exactly the proof.
# RUNS_BINARY: the tests run the matforge binary (MATFORGE_BIN) and can generate synthetic
# sets (MATFORGE_GEN_SAMPLES, tests/common/synthetic_sets.hpp), and every manifest and
# validate report they leave behind is copied to the schema spool (tests/common/run_binary.hpp),
# which the schema_check test validates after them (tests/CMakeLists.txt).
set(MATFORGE_SCHEMA_SPOOL ${PROJECT_BINARY_DIR}/schema-spool)
# The ingest cache every test's matforge runs share (never the user's ~/.cache/matforge): the
# tests run in parallel, so the cache sees concurrent writers and restores in every run.
# Emptied with the spool at the start of a ctest run.
set(MATFORGE_TEST_CACHE ${PROJECT_BINARY_DIR}/test-cache)
function(matforge_test name)
  cmake_parse_arguments(T "RUNS_BINARY" "LOCK" "SLOW;ENGINE_PROOF;SOURCES;LIBS" ${ARGN})
  add_executable(test_${name} ${T_SOURCES})
  matforge_target_defaults(test_${name})
  # OpenImageIO directly too: tests write and read files with it as an independent check.
  target_link_libraries(test_${name} PRIVATE ${T_LIBS} OpenImageIO::OpenImageIO GTest::gtest_main GTest::gmock)
  target_include_directories(test_${name} PRIVATE ${PROJECT_SOURCE_DIR}/tests/common)
  # Paths reach the tests through the environment (tests/common/test_env.hpp), never compiled
  # in: a test object must not depend on where the clone lives (ccache hits across clones).
  set(_env "MATFORGE_SOURCE_DIR=${PROJECT_SOURCE_DIR};MATFORGE_CACHE=${MATFORGE_TEST_CACHE}")
  string(APPEND _env ";MATFORGE_BIN=$<TARGET_FILE:matforge>;MATFORGE_GEN_SAMPLES=$<TARGET_FILE:gen_samples>")
  string(APPEND _env ";MATFORGE_CORPUS_DIR=${MATFORGE_CORPUS_DIR};MATFORGE_NPM_DIR=${PROJECT_BINARY_DIR}/npm")
  string(APPEND _env ";MATFORGE_PY_DIR=${PROJECT_BINARY_DIR}/py;MATFORGE_KTX_DIR=${PROJECT_BINARY_DIR}/ktx")
  if(MATFORGE_SANITIZE)
    # Third-party leaks only (scripts/lsan.supp says which and why), for the test and every
    # matforge it runs, also when ctest is run by hand in the sanitizer build.
    string(APPEND _env ";LSAN_OPTIONS=suppressions=${PROJECT_SOURCE_DIR}/scripts/lsan.supp:print_suppressions=0")
  endif()
  if(T_RUNS_BINARY)
    add_dependencies(test_${name} matforge gen_samples)
    string(APPEND _env ";MATFORGE_SCHEMA_SPOOL=${MATFORGE_SCHEMA_SPOOL}")
  endif()
  set(_props "ENVIRONMENT \"${_env}\"")
  if(T_RUNS_BINARY)
    string(APPEND _props " FIXTURES_REQUIRED schema_spool")
    set(_label integration)
  else()
    set(_label unit)
  endif()
  if(T_LOCK)
    string(APPEND _props " RESOURCE_LOCK ${T_LOCK}")
  endif()
  list(JOIN T_SLOW "|" _slow)
  list(JOIN T_ENGINE_PROOF "|" _proof)
  gtest_discover_tests(test_${name} DISCOVERY_TIMEOUT 60)
  # The properties go on the discovered tests from a file ctest reads after their list
  # (test_<name>_TESTS), not through gtest_discover_tests(PROPERTIES): CMake 3.25 splits a
  # property value at ';' there, so of an ENVIRONMENT of two variables only the first reached
  # the tests, and every property after it was lost (checked with ctest --show-only=json-v1).
  # file(GENERATE): the environment names the binaries by $<TARGET_FILE:...>.
  set(_file ${CMAKE_CURRENT_BINARY_DIR}/test_${name}_properties.cmake)
  # Labels: unit or integration; `slow` (left to the release build when sanitizing);
  # `engine-proof` (a real engine or DCC opens the files: ctest -L engine-proof).
  set(_body "foreach(_t IN LISTS test_${name}_TESTS)\n  set(_labels ${_label})\n")
  if(_slow)
    string(APPEND _body "  if(_t MATCHES \"^(${_slow})$\")\n    list(APPEND _labels slow)\n  endif()\n")
  endif()
  if(_proof)
    string(APPEND _body "  if(_t MATCHES \"^(${_proof})$\")\n    list(APPEND _labels engine-proof)\n  endif()\n")
  endif()
  string(APPEND _body "  set_tests_properties(\"\${_t}\" PROPERTIES ${_props} LABELS \"\${_labels}\")\nendforeach()\n")
  file(GENERATE OUTPUT ${_file} CONTENT "${_body}")
  set_property(DIRECTORY APPEND PROPERTY TEST_INCLUDE_FILES ${_file})
endfunction()
