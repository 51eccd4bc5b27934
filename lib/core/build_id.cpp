// The identity of a loaded object's code (core/version.hpp): its build-id note, found through
// the dynamic loader's list of objects and their program headers, in memory.
#include <elf.h>
#include <link.h>

#include <cstdint>
#include <cstring>
#include <optional>
#include <string>

#include "core/files.hpp"
#include "core/version.hpp"

namespace mf {
namespace {

struct Found {
    uintptr_t address = 0;
    bool holds = false;
    std::string file;      // as the loader names it: "" for the executable
    std::string build_id;  // lowercase hex, "" when none
};

std::string hex(const unsigned char* p, size_t n) {
    static constexpr char kDigits[] = "0123456789abcdef";
    std::string s;
    s.reserve(2 * n);
    for (size_t i = 0; i < n; ++i) {
        s += kDigits[p[i] >> 4];
        s += kDigits[p[i] & 15];
    }
    return s;
}

size_t align_up(size_t n, size_t align) { return (n + align - 1) / align * align; }

// The build-id of one PT_NOTE segment's notes, "" when it holds none. A note's descriptor and the
// next note start at the segment's alignment (4, or 8 for GNU property notes) from its start, as
// binutils reads them (ELF_NOTE_DESC_OFFSET, ELF_NOTE_NEXT_OFFSET).
std::string build_id_note(const unsigned char* p, size_t size, size_t align) {
    size_t at = 0;
    while (at + sizeof(ElfW(Nhdr)) <= size) {
        ElfW(Nhdr) h{};
        std::memcpy(&h, p + at, sizeof h);
        const size_t name_at = at + sizeof h;
        if (h.n_namesz > size - name_at) break;
        const size_t desc_at = at + align_up(sizeof h + h.n_namesz, align);
        if (desc_at > size || h.n_descsz > size - desc_at) break;
        if (h.n_type == NT_GNU_BUILD_ID && h.n_namesz == 4 && std::memcmp(p + name_at, "GNU", 4) == 0 && h.n_descsz > 0)
            return hex(p + desc_at, h.n_descsz);
        at = align_up(desc_at + h.n_descsz, align);
    }
    return {};
}

int visit(dl_phdr_info* info, size_t /*size*/, void* data) {
    auto& f = *static_cast<Found*>(data);
    // Whether [a, a + n) lies in one of the object's loaded segments (mapped memory).
    auto loaded = [info](uintptr_t a, size_t n) {
        for (ElfW(Half) i = 0; i < info->dlpi_phnum; ++i) {
            const ElfW(Phdr)& ph = info->dlpi_phdr[i];
            const uintptr_t start = info->dlpi_addr + ph.p_vaddr;
            if (ph.p_type == PT_LOAD && a >= start && n <= ph.p_memsz && a - start <= ph.p_memsz - n) return true;
        }
        return false;
    };
    if (!loaded(f.address, 1)) return 0;
    f.holds = true;
    f.file = info->dlpi_name ? info->dlpi_name : "";
    for (ElfW(Half) i = 0; i < info->dlpi_phnum && f.build_id.empty(); ++i) {
        const ElfW(Phdr)& ph = info->dlpi_phdr[i];
        const uintptr_t at = info->dlpi_addr + ph.p_vaddr;
        if (ph.p_type != PT_NOTE || !loaded(at, ph.p_memsz)) continue;
        // NOLINTNEXTLINE(performance-no-int-to-ptr): the loader states where a segment lies as a number
        const auto* notes = reinterpret_cast<const unsigned char*>(at);
        f.build_id = build_id_note(notes, ph.p_memsz, ph.p_align == 8 ? 8 : 4);
    }
    return 1;  // found: stop
}

Found find(const void* address) {
    Found f;
    f.address = reinterpret_cast<uintptr_t>(address);
    ::dl_iterate_phdr(visit, &f);
    return f;
}

// An object of matforge_core, so in whatever object links the library.
const void* library_code() {
    static const char kAnchor = 0;
    return &kAnchor;
}

}  // namespace

std::string loaded_build_id(const void* address) { return find(address).build_id; }

std::optional<std::string> code_identity_of(const void* address, std::string& error) {
    const Found f = find(address);
    if (!f.holds) {
        error = "no loaded object holds matforge's code";
        return std::nullopt;
    }
    if (!f.build_id.empty()) return "build-id " + f.build_id;
    // Linked without a build-id (another toolchain, or removed): the bytes of its file, once.
    // The executable through /proc: the file it was started from, even when replaced since.
    const std::string file = f.file.empty() ? "/proc/self/exe" : f.file;
    std::string why;
    const auto sha = sha256_of_file(file, why);
    if (!sha) {
        error = file + " has no build-id and cannot be read (" + why + ")";
        return std::nullopt;
    }
    return "sha256 " + *sha;
}

std::optional<std::string> code_identity(std::string& error) {
    struct Once {
        std::optional<std::string> id;
        std::string error;
    };
    static const Once once = [] {
        Once o;
        o.id = code_identity_of(library_code(), o.error);
        return o;
    }();
    if (!once.id) error = once.error;
    return once.id;
}

}  // namespace mf
