// Loading the matforge_oiio module (image/oiio_module.hpp): where a build or an install puts it,
// once, on first use, never closed. image.cpp asks it for the table only when a file is one the
// direct readers (image/direct.hpp) decline.
#include <dlfcn.h>

#include <filesystem>
#include <string>
#include <vector>

#include "image/oiio_module.hpp"

namespace mf::oiio_module {
namespace {

namespace fs = std::filesystem;

// The matforge_oiio module, loaded once, on first use, in the places a build or an install
// puts it: beside the file holding this code when that is not the executable (the Python
// extension, whose package carries the module), beside the executable (a copied tree), the
// install's library folder relative to the executable's (MATFORGE_OIIO_MODULE_RELDIR:
// bin/../lib/<arch>/matforge), then the build tree (MATFORGE_OIIO_MODULE_BUILT: tests and
// benchmarks run from their own folders). Never closed.
struct Module {
    const Table* table = nullptr;
    std::string error;
};

Module load_module() {
    std::vector<fs::path> places;
    std::error_code ec, here_ec;
    const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
    Dl_info self{};
    if (::dladdr(reinterpret_cast<void*>(&load_module), &self) != 0 && self.dli_fname) {
        const fs::path here = fs::weakly_canonical(self.dli_fname, here_ec);
        if (!here_ec && (ec || here != exe)) places.push_back(here.parent_path() / kFileName);
    }
    if (!ec) {
        places.push_back(exe.parent_path() / kFileName);
        places.push_back(exe.parent_path() / MATFORGE_OIIO_MODULE_RELDIR / kFileName);
    }
    places.emplace_back(MATFORGE_OIIO_MODULE_BUILT);
    Module m;
    std::string tried;
    for (const fs::path& p : places) {
        if (!fs::exists(p, ec)) {
            tried += (tried.empty() ? "" : ", ") + p.lexically_normal().string() + " (absent)";
            continue;
        }
        void* handle = ::dlopen(p.c_str(), RTLD_NOW | RTLD_LOCAL);
        if (!handle) {
            const char* why = ::dlerror();
            tried += (tried.empty() ? "" : ", ") + p.lexically_normal().string() + " (" + (why ? why : "?") + ")";
            continue;
        }
        using Entry = const Table* (*)();
        auto* entry = reinterpret_cast<Entry>(::dlsym(handle, kEntry));
        const Table* t = entry ? entry() : nullptr;
        if (!t || t->abi != kAbi || t->size != sizeof(Table)) {
            tried += (tried.empty() ? "" : ", ") + p.lexically_normal().string() + " (of another matforge build)";
            continue;  // the handle stays open: closing a module that ran no code gains nothing
        }
        m.table = t;
        return m;
    }
    m.error = "matforge's image decoders and encoders (" + std::string(kFileName) +
              ", OpenImageIO) could not be loaded; tried " + tried + "; reinstall matforge";
    return m;
}

const Module& module() {
    static const Module m = load_module();
    return m;
}

}  // namespace

const Table* table(std::string& error, const std::string& prefix) {
    const Module& m = module();
    if (!m.table) error = prefix + m.error;
    return m.table;
}

}  // namespace mf::oiio_module
