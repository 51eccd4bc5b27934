// Where a test finds what the build made and what the repository holds. ctest sets these
// variables on every test (cmake/MatforgeTesting.cmake); they are read at run time rather than
// compiled in, so no test object names the folder the clone lives in: a compiler cache shared by
// two clones (CI's, .ci/run) hits for every test file.
#pragma once
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <optional>
#include <string>

namespace mf::testenv {

// The variable's value; a test program started without ctest stops here, saying what to do.
inline std::string required(const char* name) {
    const char* v = std::getenv(name);
    if (v == nullptr || *v == '\0') {
        std::fprintf(stderr,
                     "%s is not set: run the tests through ctest (ctest --test-dir build -R NAME), which sets it\n",
                     name);
        std::abort();
    }
    return v;
}

inline std::filesystem::path source_dir() { return required("MATFORGE_SOURCE_DIR"); }
inline std::string bin() { return required("MATFORGE_BIN"); }                    // the matforge binary
inline std::string gen_samples() { return required("MATFORGE_GEN_SAMPLES"); }    // tools/gen_samples
inline std::filesystem::path npm_dir() { return required("MATFORGE_NPM_DIR"); }  // scripts/npm-checkers.sh
inline std::filesystem::path py_dir() { return required("MATFORGE_PY_DIR"); }    // scripts/py-checkers.sh
inline std::filesystem::path ktx_dir() { return required("MATFORGE_KTX_DIR"); }  // scripts/ktx-checker.sh
// The real-material corpus (tests/data/corpus: truth.json and real/<set>/).
inline std::filesystem::path corpus_dir() { return required("MATFORGE_CORPUS_DIR"); }
// Where manifests and reports go for schema_check; unset for tests that run no binary.
inline std::optional<std::filesystem::path> schema_spool() {
    const char* v = std::getenv("MATFORGE_SCHEMA_SPOOL");
    if (v == nullptr || *v == '\0') return std::nullopt;
    return std::filesystem::path(v);
}

}  // namespace mf::testenv
