// What the presets of one pass share of a set's validation (plan/plan.hpp PlanShare): validate_set
// runs once per distinct (rules config, maps), the configs compared by value. Observed through a
// file changed between two calls: a shared result still shows the first pixels, a fresh one the new.
#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>

#include "cli_util.hpp"
#include "findings/findings.hpp"
#include "image/image.hpp"
#include "plan/plan.hpp"

namespace {

namespace fs = std::filesystem;

void write_grey_png(const fs::path& file, float value) {
    std::vector<unsigned char> bytes;
    std::string error;
    ASSERT_TRUE(mf::encode_image(mf::Image(16, 16, 3, value), {mf::FileFormat::png, 8}, bytes, error)) << error;
    std::ofstream(file, std::ios::binary | std::ios::trunc)
        .write(reinterpret_cast<const char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
}

bool too_dark(const mf::validate::SetValidation& v) {
    return std::any_of(v.findings.begin(), v.findings.end(),
                       [](const mf::Finding& f) { return f.code == mf::code::albedo_too_dark; });
}

TEST(PlanShare, ValidatesOnceForEqualRulesAndAgainForOthers) {
    const fs::path dir = mft::temp_dir("share");
    const fs::path file = dir / "Rock_Color.png";
    write_grey_png(file, 0.5f);
    auto maps = [&] {
        mf::InputFile in;
        in.path = file;
        in.display = "Rock_Color.png";
        std::string error;
        auto m = mf::validate::make_map_input(mf::Role::albedo, in, "Rock_Color.png", mf::NormalConvention::unknown,
                                              error);
        EXPECT_TRUE(m) << error;
        return std::vector<mf::validate::MapInput>{*m};
    };
    mf::PlanShare share(3);
    const mf::rules::RuleConfig a;
    EXPECT_FALSE(too_dark(share.validate(maps(), a, {})));
    write_grey_png(file, 0.0f);           // black now: too dark for any config that looks again
    const mf::rules::RuleConfig a_again;  // another object, equal by value
    EXPECT_FALSE(too_dark(share.validate(maps(), a_again, {}))) << "equal configs share the first result";
    mf::rules::RuleConfig b;
    b.thresholds.albedo_min_srgb = 31.0;
    EXPECT_TRUE(too_dark(share.validate(maps(), b, {}))) << "another config is validated on its own";
}

}  // namespace
