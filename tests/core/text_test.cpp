#include <gtest/gtest.h>

#include <initializer_list>
#include <string>
#include <vector>

#include "core/text.hpp"

namespace {

const std::string R = "\xEF\xBF\xBD";  // U+FFFD

TEST(Utf8OrReplacement, ValidTextIsUnchanged) {
    for (const std::string& s :
         std::initializer_list<std::string>{"", "plain ascii", "Caf\xC3\xA9", "\xE2\x82\xAC 20", "\xF0\x9F\x98\x80",
                                            "\xEF\xBF\xBD", "\xF4\x8F\xBF\xBF" /* U+10FFFF */, std::string("a\0b", 3)})
        EXPECT_EQ(mf::utf8_or_replacement(s), s);
}

TEST(Utf8OrReplacement, Latin1ByteBecomesOneReplacement) {
    EXPECT_EQ(mf::utf8_or_replacement("Caf\xE9_Color.png"), "Caf" + R + "_Color.png");
    EXPECT_EQ(mf::utf8_or_replacement("\xFF\xFE"), R + R);
}

TEST(Utf8OrReplacement, RejectsOverlongsSurrogatesAndBeyondUnicode) {
    EXPECT_EQ(mf::utf8_or_replacement("\xC0\xAF"), R + R);                  // overlong '/': C0 is never a lead
    EXPECT_EQ(mf::utf8_or_replacement("\xE0\x80\xAF"), R + R + R);          // overlong 3-byte form
    EXPECT_EQ(mf::utf8_or_replacement("\xED\xA0\x80"), R + R + R);          // surrogate U+D800
    EXPECT_EQ(mf::utf8_or_replacement("\xF4\x90\x80\x80"), R + R + R + R);  // U+110000
}

TEST(Utf8OrReplacement, MaximalSubpartsAsInTheUnicodeStandard) {
    // Unicode 15 §3.9, Table 3-11: "61 F1 80 80 E1 80 C2 62 80 63 80 BF 64" gives
    // a, FFFD (F1 80 80), FFFD (E1 80), FFFD (C2), b, FFFD, c, FFFD, FFFD, d.
    EXPECT_EQ(mf::utf8_or_replacement("\x61\xF1\x80\x80\xE1\x80\xC2\x62\x80\x63\x80\xBF\x64"),
              "a" + R + R + R + "b" + R + "c" + R + R + "d");
    EXPECT_EQ(mf::utf8_or_replacement("ok\xE2\x82"), "ok" + R);  // truncated at the end
}

}  // namespace

namespace {

TEST(Nearest, TyposFindTheirWordOthersNothing) {
    const std::vector<std::string> commands{"ingest", "validate", "preview", "report", "plan", "merge", "cache"};
    EXPECT_EQ(mf::nearest("injest", commands), "ingest");
    EXPECT_EQ(mf::nearest("INGEST", commands), "ingest");
    EXPECT_EQ(mf::nearest("valdate", commands), "validate");
    EXPECT_EQ(mf::nearest("prevew", commands), "preview");
    EXPECT_EQ(mf::nearest("frobnicate", commands), "");
    EXPECT_EQ(mf::nearest("x", commands), "");
    EXPECT_EQ(mf::nearest("--presett", {"--preset", "--jobs", "--out"}), "--preset");
}

TEST(TerminalSafe, ControlCharactersAreWrittenAsEscapes) {
    EXPECT_EQ(mf::terminal_safe("plain Caf\xC3\xA9 \t tab"), "plain Caf\xC3\xA9 \t tab");
    EXPECT_EQ(mf::terminal_safe("a\x1b]0;title\x07z"), "a\\x1b]0;title\\x07z");
    EXPECT_EQ(mf::terminal_safe("del\x7f c1\xC2\x9b"), "del\\x7f c1\\x9b");
    EXPECT_EQ(mf::terminal_safe("two\nlines"), "two\\x0alines");
    EXPECT_EQ(mf::terminal_safe("two\nlines", true), "two\nlines");
    EXPECT_EQ(mf::terminal_safe(std::string("nul\0!", 5)), "nul\\x00!");
}

TEST(Numbers, FixedAndPercent) {
    EXPECT_EQ(mf::fixed(2.0 / 3.0, 3), "0.667");
    EXPECT_EQ(mf::fixed(-0.5, 0), "-0");
    EXPECT_EQ(mf::percent(0.1234), "12.3 %");
    EXPECT_EQ(mf::ascii_lower("Net004A_Color.JPG \xC3\x89"), "net004a_color.jpg \xC3\x89");
}

// Names as people write them: non-ASCII capitals fold too, one to one, invalid bytes kept.
TEST(Text, FoldCase) {
    EXPECT_EQ(mf::fold_case("BR\xC3\x8F"
                            "CK Wall"),
              "br\xC3\xaf"
              "ck wall");                                                // Ï -> ï
    EXPECT_EQ(mf::fold_case("\xC3\x89T\xC3\x89"), "\xC3\xa9t\xC3\xa9");  // É -> é
    EXPECT_EQ(mf::fold_case("\xC3\x97\xC3\x9F"), "\xC3\x97\xC3\x9F") << "× and ß stay";
    EXPECT_EQ(mf::fold_case("\xC5\x81\xC3\xB3"
                            "d\xC5\xBA"),
              "\xC5\x82\xC3\xB3"
              "d\xC5\xBA");                                                            // Łódź
    EXPECT_EQ(mf::fold_case("\xC5\xB9"), "\xC5\xBA");                                  // Ź -> ź (odd run)
    EXPECT_EQ(mf::fold_case("\xC5\xB8"), "\xC3\xBF");                                  // Ÿ -> ÿ
    EXPECT_EQ(mf::fold_case("\xCE\xA9\xD0\x96\xD0\x81"), "\xCF\x89\xD0\xB6\xD1\x91");  // Ω Ж Ё
    EXPECT_EQ(mf::fold_case("a\xC3(\xFF\xC0\x80"), "a\xC3(\xFF\xC0\x80") << "invalid and overlong kept";
    EXPECT_EQ(mf::fold_case("\xE2\x80\x93"), "\xE2\x80\x93") << "three-byte code points kept";
}

}  // namespace

// One escaper for the report page and JUnit: every reference both HTML and XML read, ill-formed
// bytes and forbidden controls as U+FFFD, tab/LF/CR and valid UTF-8 kept.
TEST(Text, MarkupEscape) {
    EXPECT_EQ(mf::markup_escape("a<b>&\"'c"), "a&lt;b&gt;&amp;&quot;&#39;c");
    EXPECT_EQ(mf::markup_escape(std::string("x\x01y\x1fz", 5)), "x\xEF\xBF\xBDy\xEF\xBF\xBDz");
    EXPECT_EQ(mf::markup_escape("t\tn\nr\r"), "t\tn\nr\r");
    EXPECT_EQ(mf::markup_escape("caf\xC3\xA9 \xFF"), "caf\xC3\xA9 \xEF\xBF\xBD");
    EXPECT_EQ(mf::markup_escape(""), "");
}
