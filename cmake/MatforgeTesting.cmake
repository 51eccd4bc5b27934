# matforge_test(name [RUNS_BINARY] [LOCK name] SOURCES... LIBS ...): one GoogleTest program,
# discovered by ctest. LOCK: its tests never run at the same time as another test holding that
# ctest RESOURCE_LOCK (tests that share costly results through the test cache: the first
# computes, the others restore, instead of all computing at once under ctest -j).
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
  cmake_parse_arguments(T "RUNS_BINARY" "LOCK" "SOURCES;LIBS" ${ARGN})
  add_executable(test_${name} ${T_SOURCES})
  matforge_target_defaults(test_${name})
  target_link_libraries(test_${name} PRIVATE ${T_LIBS} GTest::gtest_main GTest::gmock)
  target_include_directories(test_${name} PRIVATE ${PROJECT_SOURCE_DIR}/tests/common)
  target_compile_definitions(test_${name} PRIVATE
    MATFORGE_SOURCE_DIR="${PROJECT_SOURCE_DIR}"
    MATFORGE_BINARY_DIR="${PROJECT_BINARY_DIR}")
  set(_env "MATFORGE_SOURCE_DIR=${PROJECT_SOURCE_DIR};MATFORGE_CACHE=${MATFORGE_TEST_CACHE}")
  if(MATFORGE_SANITIZE)
    # Third-party leaks only (scripts/lsan.supp says which and why), for the test and every
    # matforge it runs, also when ctest is run by hand in the sanitizer build.
    string(APPEND _env ";LSAN_OPTIONS=suppressions=${PROJECT_SOURCE_DIR}/scripts/lsan.supp:print_suppressions=0")
  endif()
  set(_props "ENVIRONMENT \"${_env}\"")
  if(T_RUNS_BINARY)
    target_compile_definitions(test_${name} PRIVATE MATFORGE_BIN="$<TARGET_FILE:matforge>"
      MATFORGE_GEN_SAMPLES="$<TARGET_FILE:gen_samples>" MATFORGE_SCHEMA_SPOOL="${MATFORGE_SCHEMA_SPOOL}")
    add_dependencies(test_${name} matforge gen_samples)
    string(APPEND _props " FIXTURES_REQUIRED schema_spool")
  endif()
  if(T_LOCK)
    string(APPEND _props " RESOURCE_LOCK ${T_LOCK}")
  endif()
  gtest_discover_tests(test_${name} DISCOVERY_TIMEOUT 60)
  # The properties go on the discovered tests from a file ctest reads after their list
  # (test_<name>_TESTS), not through gtest_discover_tests(PROPERTIES): CMake 3.25 splits a
  # property value at ';' there, so of an ENVIRONMENT of two variables only the first reached
  # the tests, and every property after it was lost (checked with ctest --show-only=json-v1).
  set(_file ${CMAKE_CURRENT_BINARY_DIR}/test_${name}_properties.cmake)
  file(WRITE ${_file} "foreach(_t IN LISTS test_${name}_TESTS)\n  set_tests_properties(\"\${_t}\" PROPERTIES ${_props})\nendforeach()\n")
  set_property(DIRECTORY APPEND PROPERTY TEST_INCLUDE_FILES ${_file})
endfunction()
