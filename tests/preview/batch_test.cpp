// The preview batch's memory bound (issue 49: "cap memory by the number in flight, a budget, not a
// count"): the workers read ahead as far as BatchOptions::memory_budget allows, counting the
// bytes of prepared textures and rendered images held, so 1K materials run far ahead and large
// ones one by one; a material larger than the whole budget is still rendered. Materials here are
// made in memory (one 256² RGBA albedo each) so that every one prepares to the same bytes, and
// the renderer's start on lavapipe (a quarter of a second) leaves the workers time to read ahead.
#include <gtest/gtest.h>

#include <cstdint>
#include <string>
#include <vector>

#include "preview/batch.hpp"
#include "test_dirs.hpp"
#include "test_files.hpp"
#include "vulkan_fixture.hpp"

namespace mf::preview::batch_test {
namespace fs = std::filesystem;

constexpr uint32_t kTexture = 256, kImage = 32;

render::Material material(int n) {
    render::Material m;
    m.name = "m" + std::to_string(n);
    render::Texture t;
    t.width = t.height = kTexture;
    t.channels = 4;
    t.srgb = true;
    t.data.resize(size_t{kTexture} * kTexture * 4);
    for (size_t i = 0; i < t.data.size(); ++i)
        t.data[i] = static_cast<uint8_t>((i * 7 + static_cast<size_t>(n)) & 0xFF);
    m.textures.push_back(std::move(t));
    m.albedo.texture = 0;
    return m;
}

class BatchBudget : public ::testing::Test {
protected:
    void SetUp() override {
        test::use_lavapipe_only();
        log_ = std::make_shared<render::MessageLog>();
        sf_.scene.width = sf_.scene.height = kImage;
        opt_.context.device = render::DeviceKind::cpu;
        opt_.context.validation = true;
        opt_.context.log = log_;
        opt_.out = testdirs::fresh_for_test("matforge-batch-test-", "out");
        opt_.lanes = 1;
        for (int n = 0; n < 16; ++n)
            jobs_.push_back({"m" + std::to_string(n), "m" + std::to_string(n),
                             [n](const BlockSupport&, std::vector<std::string>&, std::string&) {
                                 return std::optional<render::Material>(material(n));
                             }});
        // What one material holds once prepared, on the device the batch will make: its textures
        // (render::PreparedMaterial::bytes), then its image until the image is said.
        render::Context context(opt_.context);
        prepared_ = render::prepare(context, sf_.scene, material(0)).bytes();
        ASSERT_GT(prepared_, uint64_t{kTexture} * kTexture * 4 - 1);
    }

    void TearDown() override {
        std::string all;
        for (const std::string& m : log_->messages()) all += m + "\n";
        EXPECT_EQ(log_->count(), 0u) << all;
    }

    BatchResult run() {
        std::vector<std::string> said;
        BatchResult r = render_batch(sf_, jobs_, opt_, [&](const std::string& line) { said.push_back(line); });
        std::string all;
        for (const std::string& line : said) all += line + "\n";
        EXPECT_EQ(r.rendered, jobs_.size()) << all;
        EXPECT_EQ(r.failed, 0u) << all;
        for (const Job& j : jobs_) EXPECT_TRUE(fs::is_regular_file(opt_.out / (j.stem + ".png"))) << j.stem;
        return r;
    }

    const uint64_t image_ = uint64_t{kImage} * kImage * 4;  // a rendered image's 8-bit RGBA
    std::shared_ptr<render::MessageLog> log_;
    SceneFile sf_;
    BatchOptions opt_;
    std::vector<Job> jobs_;
    uint64_t prepared_ = 0;
};

// A budget of two and a half materials: the workers fill it and stop there.
TEST_F(BatchBudget, WorkersReadAheadUpToTheBudgetAndNoFurther) {
    opt_.jobs = 4;
    opt_.memory_budget = prepared_ * 5 / 2;
    const BatchResult r = run();
    EXPECT_LE(r.held_most, opt_.memory_budget);
    // Read ahead while the renderer was made: two prepared at once (a count of one would hold one).
    EXPECT_GE(r.held_most, 2 * prepared_);
}

// A budget of gigabytes: not a count of materials, so every one is read ahead while the renderer
// is made, whatever the number of workers (the same test with a budget of 2.5 holds two).
TEST_F(BatchBudget, ALargeBudgetLetsTheWorkersRunFarAhead) {
    opt_.jobs = 4;
    opt_.memory_budget = uint64_t{1} << 30;
    const BatchResult r = run();
    EXPECT_GE(r.held_most, 8 * prepared_) << "held at most " << r.held_most << " bytes, " << prepared_ << " a material";
}

// A budget smaller than one material: each is still rendered, one after another once a size is
// known (before that, two start at once: the first two reads know no size).
TEST_F(BatchBudget, MaterialsLargerThanTheBudgetAreRenderedOneAtATime) {
    opt_.jobs = 4;
    opt_.memory_budget = 1;
    const BatchResult r = run();
    EXPECT_LE(r.held_most, 2 * (prepared_ + image_));
    EXPECT_GE(r.held_most, prepared_);
}

// A device made ahead (start_device, while `matforge preview` reads its manifest) is the one the
// batch renders with: it takes it (the future is used up) and the pictures are the bytes a batch
// that made its own device writes.
using BatchDevice = BatchBudget;

TEST_F(BatchDevice, ADeviceMadeAheadIsTakenAndRendersTheSamePictures) {
    opt_.jobs = 4;
    run();
    std::vector<std::vector<unsigned char>> own;
    for (const Job& j : jobs_) own.push_back(testfiles::file_bytes(opt_.out / (j.stem + ".png")));
    opt_.out = opt_.out.parent_path() / "ahead";
    opt_.device_ahead = start_device(opt_.context);
    run();
    EXPECT_FALSE(opt_.device_ahead->made.valid()) << "the batch made a device of its own";
    for (size_t i = 0; i < jobs_.size(); ++i) {
        EXPECT_FALSE(own[i].empty());
        EXPECT_EQ(testfiles::file_bytes(opt_.out / (jobs_[i].stem + ".png")), own[i]) << jobs_[i].stem;
    }
}

// A device that cannot be made (a GPU where the loader sees only lavapipe) fails the batch as it
// did when the batch made it: render::NoDeviceError, from render_batch.
TEST_F(BatchDevice, ADeviceThatCannotBeMadeAheadFailsTheBatch) {
    opt_.context.device = render::DeviceKind::gpu;
    opt_.device_ahead = start_device(opt_.context);
    EXPECT_THROW(render_batch(sf_, jobs_, opt_, [](const std::string&) {}), render::NoDeviceError);
    opt_.device_ahead.reset();
    EXPECT_THROW(render_batch(sf_, jobs_, opt_, [](const std::string&) {}), render::NoDeviceError);
}

}  // namespace mf::preview::batch_test
