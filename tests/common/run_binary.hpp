// Running the matforge binary from tests, one way for every test folder (tests/cli,
// tests/hostile, tests/corpus): a fork with a deadline (a hang is a failure, never a stuck CI
// job), the output captured, peak memory measured. Every manifest and validate report a test
// leaves in its temporary folders is also copied to the schema spool, which the suite's last
// test (schema_check) validates against docs/*.schema.json.
#pragma once
#include <gtest/gtest.h>

#include <array>
#include <atomic>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include <signal.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include "test_dirs.hpp"
#include "test_env.hpp"

namespace mf::testbin {
namespace fs = std::filesystem;

struct Proc {
    int code = -1;       // exit status when it exited
    int signal = 0;      // the signal that ended it, 0 when it exited
    bool hung = false;   // killed at the deadline
    std::string output;  // stdout + stderr
    long maxrss_kb = 0;  // peak resident memory of the process
};

// Runs argv[0] with argv (no shell: names with quotes or invalid UTF-8 pass through untouched).
// `kill_after_s`: SIGKILL it after that many seconds (interrupt tests). `deadline_s`: a run still
// going then is a hang: killed and reported as hung.
inline Proc spawn(const std::vector<std::string>& argv, double deadline_s = 300,
                  std::optional<double> kill_after_s = std::nullopt) {
    Proc p;
    char log_name[] = "/tmp/matforge-test-log-XXXXXX";
    const int log_fd = ::mkstemp(log_name);
    if (log_fd < 0) return p;
    ::unlink(log_name);
    std::vector<char*> args;
    for (const auto& a : argv) args.push_back(const_cast<char*>(a.c_str()));
    args.push_back(nullptr);
    const pid_t pid = ::fork();
    if (pid == 0) {
        ::dup2(log_fd, STDOUT_FILENO);
        ::dup2(log_fd, STDERR_FILENO);
        ::execvp(args[0], args.data());
        ::_exit(127);
    }
    const auto start = std::chrono::steady_clock::now();
    int status = 0;
    rusage ru{};
    bool killed_on_purpose = false;
    for (;;) {
        const pid_t r = ::wait4(pid, &status, WNOHANG, &ru);
        if (r == pid) break;
        const double t = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        if (kill_after_s && t >= *kill_after_s && !killed_on_purpose) {
            ::kill(pid, SIGKILL);
            killed_on_purpose = true;
        } else if (t >= deadline_s && !p.hung) {
            ::kill(pid, SIGKILL);
            p.hung = true;
        }
        std::this_thread::sleep_for(std::chrono::milliseconds(kill_after_s ? 1 : 5));
    }
    if (WIFEXITED(status)) p.code = WEXITSTATUS(status);
    if (WIFSIGNALED(status)) p.signal = WTERMSIG(status);
    p.maxrss_kb = ru.ru_maxrss;
    ::lseek(log_fd, 0, SEEK_SET);
    std::array<char, 4096> buf{};
    for (ssize_t n; (n = ::read(log_fd, buf.data(), buf.size())) > 0;)
        p.output.append(buf.data(), static_cast<size_t>(n));
    ::close(log_fd);
    return p;
}

// ---- the schema spool

// A temporary folder of the running test: spooled at the test's end, removed at the program's
// (test_dirs.hpp).
inline void register_test_dir(const fs::path& d) { mf::testdirs::own(d); }

// Copies `text` (a JSON document matforge wrote) into the spool when it is a manifest, a
// validate report or a plan.
inline void spool_text(const std::string& text, const std::string& label) {
    const std::optional<fs::path> spool = mf::testenv::schema_spool();
    if (!spool || text.find("\"generator\": \"matforge ") == std::string::npos ||
        (text.find("\"manifest_version\"") == std::string::npos &&
         text.find("\"report_version\"") == std::string::npos && text.find("\"plan_version\"") == std::string::npos))
        return;
    static std::atomic<int> n{0};
    std::error_code ec;
    fs::create_directories(*spool, ec);
    std::string name = label + "-" + std::to_string(::getpid()) + "-" + std::to_string(n++) + ".json";
    for (char& c : name)
        if (c == '/' || c == ' ') c = '_';
    std::ofstream(*spool / name, std::ios::binary) << text;
}

// Every manifest.json, JSON report and plan under `dir` (symlinks not followed) into the spool.
inline void spool_folder(const fs::path& dir, const std::string& label) {
    std::error_code ec;
    for (fs::recursive_directory_iterator it(dir, fs::directory_options::skip_permission_denied, ec), end;
         !ec && it != end; it.increment(ec)) {
        if (it->is_symlink(ec) || !it->is_regular_file(ec) || it->path().extension() != ".json") continue;
        if (it->file_size(ec) > (64u << 20)) continue;
        std::ifstream f(it->path(), std::ios::binary);
        std::string head(64, '\0');
        f.read(head.data(), 64);
        head.resize(static_cast<size_t>(f.gcount()));
        // Only what matforge wrote (json_text, sorted keys: "failures" comes first in manifests and
        // reports, "changed_since" or "context" in plans), never a document a test made up as input.
        if (head.rfind("{\n  \"failures\": ", 0) != 0 && head.rfind("{\n  \"context\": ", 0) != 0 &&
            head.rfind("{\n  \"changed_since\": ", 0) != 0)
            continue;
        f.seekg(0);
        const std::string text((std::istreambuf_iterator<char>(f)), {});
        spool_text(text, label);
    }
}

// At the end of every test, the test's folders go to the spool.
class SpoolListener : public ::testing::EmptyTestEventListener {
    void OnTestEnd(const ::testing::TestInfo& info) override {
        std::vector<fs::path> dirs;
        {
            std::lock_guard lock(mf::testdirs::mutex());
            dirs.swap(mf::testdirs::of_current_test());
        }
        for (const auto& d : dirs) spool_folder(d, std::string(info.test_suite_name()) + "." + info.name());
    }
};
inline const bool kSpoolListenerInstalled = [] {
    ::testing::UnitTest::GetInstance()->listeners().Append(new SpoolListener);
    return true;
}();

}  // namespace mf::testbin
