// The OpenColorIO context of the tests: one for the whole program (building processors is the
// slow part); a config that cannot load fails the calling test.
#pragma once
#include <gtest/gtest.h>

#include <memory>
#include <string>

#include "color/color.hpp"

namespace mf::testcolor {

inline std::shared_ptr<const ColorContext> color_context() {
    static const std::shared_ptr<const ColorContext> ctx = [] {
        std::string err;
        auto c = ColorContext::create(err);
        if (!c) ADD_FAILURE() << err;
        return c;
    }();
    return ctx;
}

}  // namespace mf::testcolor
