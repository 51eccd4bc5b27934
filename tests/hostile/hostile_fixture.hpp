// The Hostile fixture: a good set beside each hostile case, `matforge ingest` run with a deadline,
// and the checks every case shares (the good set finished, a finding names the file). Shared by
// hostile_test.cpp (inputs that break readers) and hardening_test.cpp (issue #16's classes).
#pragma once
#include <OpenImageIO/imageio.h>

#include <zip.h>
#include <cstdlib>
#include <string>

#include <sys/stat.h>

#include "hostile_util.hpp"

namespace mfh {

constexpr long kBombRssLimitKb = 600 * 1024;  // far below what decoding any bomb would need

class Hostile : public ::testing::Test {
protected:
    fs::path in, out;
    nlohmann::json manifest;

    void SetUp() override {
        in = temp_dir("in");
        out = temp_dir("out");
        fs::remove(out);  // ingest creates it
        write_bytes(in / "Good" / "Good_Color.png", encode(gradient(16, 16, 3)));
        write_bytes(in / "Good" / "Good_Roughness.png", encode(gradient(16, 16, 1)));
    }
    void TearDown() override {
        if (HasFailure()) return;  // keep the evidence
        std::error_code ec;
        fs::permissions(in, fs::perms::all, ec);
        fs::remove_all(in, ec);
        fs::remove_all(out, ec);
    }

    Proc ingest(std::vector<std::string> extra = {}, const std::vector<std::string>& prefix = {}) {
        std::vector<std::string> argv = prefix;
        for (const auto& a : std::vector<std::string>{bin(), "ingest", in.string(), "-o", out.string(), "--quiet"})
            argv.push_back(a);
        argv.insert(argv.end(), extra.begin(), extra.end());
        Proc p = spawn(argv, 120);
        EXPECT_FALSE(p.hung) << "ingest hung\n" << p.output;
        EXPECT_EQ(p.signal, 0) << "ingest crashed\n" << p.output;
        if (fs::exists(out / "manifest.json")) manifest = read_json(out / "manifest.json");
        return p;
    }

    const nlohmann::json* mat(const std::string& name) const {
        for (const auto& m : manifest["materials"])
            if (m["name"] == name) return &m;
        return nullptr;
    }

    // The good set finished: listed as ok, its outputs on disk.
    void expect_good_done() const {
        const auto* g = mat("Good");
        ASSERT_TRUE(g) << manifest.dump(1);
        EXPECT_EQ((*g)["status"], "ok");
        EXPECT_TRUE(fs::is_regular_file(out / "Good" / "Good_basecolor.png"));
        EXPECT_TRUE(fs::is_regular_file(out / "Good" / "Good_orm.png"));
        EXPECT_TRUE(temp_files_under(out).empty());
        // A finished run leaves neither its lock nor its journal (store/output_dir.hpp).
        EXPECT_FALSE(fs::exists(fs::symlink_status(out / ".manifest.json.lock")));
        EXPECT_FALSE(fs::exists(fs::symlink_status(out / ".manifest.json.journal")));
    }

    // Material `m` has a finding `code` about `file`, whose message names the file.
    const nlohmann::json* expect_finding(const std::string& m, const std::string& code, const std::string& file,
                                         const std::string& needle = "") const {
        const auto* mm = mat(m);
        EXPECT_TRUE(mm) << manifest.dump(1);
        if (!mm) return nullptr;
        for (const auto& f : (*mm)["findings"]) {
            if (f["code"] != code || f.value("file", "") != file) continue;
            const std::string msg = f["message"];
            EXPECT_NE(msg.find(file), std::string::npos) << "message names the file: " << msg;
            if (!needle.empty()) {
                EXPECT_NE(msg.find(needle), std::string::npos) << msg;
            }
            return &f;
        }
        ADD_FAILURE() << "no " << code << " for " << file << " in " << mm->dump(1);
        return nullptr;
    }

    // manifest.failures has `code` with a message holding `needle` (the file), also on stderr.
    void expect_failure(const Proc& p, const std::string& code, const std::string& needle) const {
        for (const auto& f : manifest["failures"])
            if (f["code"] == code && f["message"].get<std::string>().find(needle) != std::string::npos) {
                EXPECT_NE(p.output.find(code), std::string::npos) << p.output;
                return;
            }
        ADD_FAILURE() << "no failure " << code << " naming " << needle << " in " << manifest["failures"].dump(1);
    }

    // A set whose one bad map is skipped: UNREADABLE_FILE (error) naming it, status partial,
    // the set's good albedo still converted, the good set done, exit 1.
    void bad_map(const std::string& name, const Bytes& bytes, const std::string& needle = "") {
        write_bytes(in / "Hostile" / "Hostile_Color.png", encode(gradient(16, 16, 3)));
        write_bytes(in / "Hostile" / name, bytes);
        const Proc p = ingest();
        expect_bad_map_result(p, name, needle);
    }
    void expect_bad_map_result(const Proc& p, const std::string& name, const std::string& needle = "") {
        EXPECT_EQ(p.code, 1) << p.output;
        expect_good_done();
        const auto* h = mat("Hostile");
        ASSERT_TRUE(h) << manifest.dump(1);
        EXPECT_EQ((*h)["status"], "partial");
        const auto* f = expect_finding("Hostile", "UNREADABLE_FILE", name, needle);
        if (f) {
            EXPECT_EQ((*f)["severity"], "error");
        }
        EXPECT_TRUE(fs::is_regular_file(out / "Hostile" / "Hostile_basecolor.png"));
    }

    // A bomb: refused from its header (the guard's message), with bounded memory.
    void bomb(const std::string& name, const Bytes& bytes, const std::string& needle = "exceeds the limit") {
        write_bytes(in / "Hostile" / "Hostile_Color.png", encode(gradient(16, 16, 3)));
        write_bytes(in / "Hostile" / name, bytes);
        const Proc p = ingest();
        expect_bad_map_result(p, name, needle);
        EXPECT_LT(p.maxrss_kb, kBombRssLimitKb) << "the size guard fires before any pixel buffer is allocated";
    }

    // An odd but valid map: read, converted, no UNREADABLE_FILE. Returns the set's entry.
    const nlohmann::json* odd_ok(const std::string& name, const Bytes& bytes) {
        write_bytes(in / "Odd" / name, bytes);
        return odd_ok_run(name);
    }
    const nlohmann::json* odd_ok_run(const std::string& name) {
        const Proc p = ingest({"--fail-on", "never"});
        EXPECT_EQ(p.code, 0) << p.output;
        expect_good_done();
        const auto* o = mat("Odd");
        EXPECT_TRUE(o) << manifest.dump(1);
        if (!o) return nullptr;
        EXPECT_EQ((*o)["status"], "ok") << o->dump(1);
        for (const auto& f : (*o)["findings"]) EXPECT_NE(f["code"], "UNREADABLE_FILE") << f.dump();
        bool listed = false;
        for (const auto& [role, i] : (*o)["inputs"].items()) listed = listed || i["file"] == name;
        EXPECT_TRUE(listed) << name << " is an input: " << o->dump(1);
        return o;
    }
};

inline Bytes valid_png() { return encode(gradient(16, 16, 1)); }

// OpenImageIO writes what our encoder does not offer (float TIFF, many channels).
inline Bytes oiio_file(const std::string& ext, int w, int h, int c, OIIO::TypeDesc type, const std::vector<float>& px) {
    const fs::path tmp = fs::temp_directory_path() /
                         ("matforge-hostile-oiio-" + std::to_string(::getpid()) + "." + ext);
    auto o = OIIO::ImageOutput::create(tmp.string());
    EXPECT_TRUE(o);
    OIIO::ImageSpec spec(w, h, c, type);
    EXPECT_TRUE(o->open(tmp.string(), spec)) << o->geterror();
    EXPECT_TRUE(o->write_image(OIIO::TypeDesc::FLOAT, px.data())) << o->geterror();
    o->close();
    Bytes b = read_bytes(tmp);
    fs::remove(tmp);
    return b;
}

struct ZipEntry {
    std::string name;
    Bytes data;
};
inline void write_zip(const fs::path& p, const std::vector<ZipEntry>& entries, bool stored = false) {
    fs::create_directories(p.parent_path());
    int err = 0;
    zip_t* z = zip_open(p.c_str(), ZIP_CREATE | ZIP_TRUNCATE, &err);
    ASSERT_TRUE(z);
    for (const auto& e : entries) {
        zip_source_t* s = zip_source_buffer(z, e.data.data(), e.data.size(), 0);
        ASSERT_TRUE(s);
        const zip_int64_t idx = zip_file_add(z, e.name.c_str(), s, ZIP_FL_OVERWRITE);
        ASSERT_GE(idx, 0) << zip_strerror(z);
        if (stored) zip_set_file_compression(z, static_cast<zip_uint64_t>(idx), ZIP_CM_STORE, 0);
    }
    ASSERT_EQ(zip_close(z), 0);
}

inline bool is_root() { return ::geteuid() == 0; }

// A private mount namespace (root, or an unprivileged user namespace) for tmpfs output disks:
// the mount vanishes with the process, whatever happens to the test. Empty when one can be
// made, else why not (a chroot or an unprivileged container: "unshare: cannot change root
// filesystem propagation").
inline std::string tmpfs_unavailable() {
    const Proc p = spawn({"unshare", is_root() ? "-m" : "-rm", "sh", "-c",
                          "d=$(mktemp -d) && mount -t tmpfs -o size=64k tmpfs \"$d\" && umount \"$d\" && rmdir \"$d\""},
                         30);
    if (p.code == 0) return {};
    return "this machine cannot mount a tmpfs in a private mount namespace (needs root or unprivileged user "
           "namespaces, outside a chroot): " +
           p.output;
}

// .ci/run sets MATFORGE_REQUIRE_PRIVILEGED=1 on its machines, which allow it: there a test that
// needs a privilege fails instead of skipping, so CI cannot lose it quietly.
inline bool privileged_tests_required() {
    const char* v = std::getenv("MATFORGE_REQUIRE_PRIVILEGED");
    return v != nullptr && std::string(v) == "1";
}

}  // namespace mfh

// Skips the calling test, with the reason, where no tmpfs can be mounted (fails it under CI).
#define MFH_REQUIRE_TMPFS()                                                   \
    do {                                                                      \
        if (const std::string why = mfh::tmpfs_unavailable(); !why.empty()) { \
            if (mfh::privileged_tests_required()) FAIL() << why;              \
            GTEST_SKIP() << why;                                              \
        }                                                                     \
    } while (false)
