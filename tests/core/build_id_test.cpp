// The build's identity (core/version.hpp): the build-id read from the loaded objects' program
// headers is the one binutils' readelf reads from their files, for the test executable (which
// links lib/core, as matforge and the Python extension do) and for a shared library.
#include <gtest/gtest.h>

#include <dlfcn.h>
#include <openssl/evp.h>

#include <algorithm>
#include <cctype>
#include <cstdint>
#include <filesystem>
#include <string>

#include "core/version.hpp"
#include "test_elf.hpp"

namespace build_id_test {

int local_function(int x) { return x + 1; }

// This executable's file (resolved here: /proc/self in readelf would be readelf's own).
std::string self() { return std::filesystem::read_symlink("/proc/self/exe").string(); }

bool is_hex(const std::string& s) {
    return std::all_of(s.begin(), s.end(), [](char c) { return std::isdigit(c) || (c >= 'a' && c <= 'f'); });
}

}  // namespace build_id_test

TEST(BuildId, TheExecutablesIsTheOneReadelfPrints) {
    const std::string want = mf::testelf::readelf_build_id(build_id_test::self());
    // GNU ld's sha1 style (cmake/MatforgeWarnings.cmake asks for it): 20 bytes.
    ASSERT_EQ(want.size(), 40u) << mf::testelf::output_of("readelf -n " + build_id_test::self());
    EXPECT_TRUE(build_id_test::is_hex(want)) << want;
    EXPECT_EQ(mf::loaded_build_id(reinterpret_cast<const void*>(&build_id_test::local_function)), want);
    static const int data = 7;
    EXPECT_EQ(mf::loaded_build_id(&data), want) << "any address of the object names it";
    // lib/core is linked into this executable: its identity is this executable's build-id.
    std::string error;
    const auto id = mf::code_identity(error);
    ASSERT_TRUE(id) << error;
    EXPECT_EQ(*id, "build-id " + want);
    EXPECT_EQ(mf::code_identity(error), id) << "computed once, the same after";
}

// The object holding the address, not always the executable: the Python extension names itself.
TEST(BuildId, ASharedLibrarysIsItsOwn) {
    const void* fn = reinterpret_cast<const void*>(&EVP_sha256);  // libcrypto, linked by lib/core
    Dl_info where{};
    ASSERT_NE(::dladdr(fn, &where), 0);
    ASSERT_NE(where.dli_fname, nullptr);
    const std::string want = mf::testelf::readelf_build_id(where.dli_fname);
    ASSERT_FALSE(want.empty()) << where.dli_fname << ": Debian's libraries carry a build-id";
    EXPECT_NE(want, mf::testelf::readelf_build_id(build_id_test::self()));
    EXPECT_EQ(mf::loaded_build_id(fn), want) << where.dli_fname;
    std::string error;
    EXPECT_EQ(mf::code_identity_of(fn, error), "build-id " + want) << error;
}

TEST(BuildId, AnAddressNoObjectHoldsHasNone) {
    const void* nowhere = reinterpret_cast<const void*>(uintptr_t{16});
    EXPECT_EQ(mf::loaded_build_id(nowhere), "");
    std::string error;
    EXPECT_EQ(mf::code_identity_of(nowhere, error), std::nullopt);
    EXPECT_NE(error.find("no loaded object"), std::string::npos) << error;
}
