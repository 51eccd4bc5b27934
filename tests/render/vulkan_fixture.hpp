// Every renderer test runs on lavapipe with the Khronos validation layer; a validation message
// of any kind (objects left undestroyed at vkDestroyDevice included) fails the test.
#pragma once
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <memory>

#include "render/render.hpp"

namespace mf::test {

// The tests run on lavapipe alone: the loader is pointed at its manifest (unless the caller set
// VK_ICD_FILENAMES), so other drivers of mesa-vulkan-drivers are neither loaded nor unloaded.
// (Sanitizer builds pin lavapipe and the validation layer in render::Context itself, so
// LeakSanitizer sees real leaks only; see lib/render/context.cpp.)
inline void use_lavapipe_only() {
    static const bool once = [] {
        for (const char* dir : {"/usr/share/vulkan/icd.d", "/etc/vulkan/icd.d", "/usr/local/share/vulkan/icd.d"}) {
            std::error_code ec;
            for (const auto& e : std::filesystem::directory_iterator(dir, ec))
                if (e.path().filename().string().rfind("lvp_icd", 0) == 0) {
                    setenv("VK_ICD_FILENAMES", e.path().c_str(), 0);
                    return true;
                }
        }
        return false;
    }();
    (void)once;
}

class VulkanTest : public ::testing::Test {
protected:
    void SetUp() override {
        use_lavapipe_only();
        log_ = std::make_shared<render::MessageLog>();
        render::ContextOptions opt;
        opt.device = render::DeviceKind::cpu;  // CI has no GPU; results must not depend on one
        opt.validation = true;
        opt.log = log_;
        configure(opt);
        context_ = std::make_unique<render::Context>(opt);
    }

    void TearDown() override {
        context_.reset();  // leaks are reported here
        std::string all;
        for (const std::string& m : log_->messages()) all += m + "\n";
        EXPECT_EQ(log_->count(), 0u) << all;
    }

    render::Context& context() { return *context_; }
    virtual void configure(render::ContextOptions&) {}

private:
    std::shared_ptr<render::MessageLog> log_;
    std::unique_ptr<render::Context> context_;
};

}  // namespace mf::test
