# matforge_test(name [RUNS_BINARY] SOURCES... LIBS ...): one GoogleTest program, discovered by
# ctest. RUNS_BINARY: the tests run the matforge binary (MATFORGE_BIN) and can generate synthetic
# sets (MATFORGE_GEN_SAMPLES, tests/common/synthetic_sets.hpp), and every manifest and
# validate report they leave behind is copied to the schema spool (tests/common/run_binary.hpp),
# which the schema_check test validates after them (tests/CMakeLists.txt).
set(MATFORGE_SCHEMA_SPOOL ${PROJECT_BINARY_DIR}/schema-spool)
# The ingest cache every test's matforge runs share (never the user's ~/.cache/matforge): the
# tests run in parallel, so the cache sees concurrent writers and restores in every run.
# Emptied with the spool at the start of a ctest run.
set(MATFORGE_TEST_CACHE ${PROJECT_BINARY_DIR}/test-cache)
function(matforge_test name)
  cmake_parse_arguments(T "RUNS_BINARY" "" "SOURCES;LIBS" ${ARGN})
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
  set(_props ENVIRONMENT "${_env}")
  if(T_RUNS_BINARY)
    target_compile_definitions(test_${name} PRIVATE MATFORGE_BIN="$<TARGET_FILE:matforge>"
      MATFORGE_GEN_SAMPLES="$<TARGET_FILE:gen_samples>" MATFORGE_SCHEMA_SPOOL="${MATFORGE_SCHEMA_SPOOL}")
    add_dependencies(test_${name} matforge gen_samples)
    list(APPEND _props FIXTURES_REQUIRED schema_spool)
  endif()
  gtest_discover_tests(test_${name} DISCOVERY_TIMEOUT 60 PROPERTIES ${_props})
endfunction()
