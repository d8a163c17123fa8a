// Message helpers: fail's one-line form, and numbers as messages show them.
#include "obscura/error.h"

#include <gtest/gtest.h>

#include <charconv>
#include <cmath>
#include <limits>
#include <string>

using namespace obscura;

TEST(Error, FailJoinsWhatAndProblem) {
    try {
        fail("--flag", "is wrong");
        FAIL() << "fail returned";
    } catch (const Error& e) {
        EXPECT_STREQ(e.what(), "--flag: is wrong");
    }
}

TEST(Error, NumberTextIsShortAndReadsBack) {
    EXPECT_EQ(numberText(0.05f), "0.05");
    EXPECT_EQ(numberText(0.0f), "0");
    EXPECT_EQ(numberText(-1.0f), "-1");
    EXPECT_EQ(numberText(1e-4f), "1e-04");  // the shorter of the two forms
    EXPECT_EQ(numberText(100000.0f), "1e+05");
    EXPECT_EQ(numberText(std::numeric_limits<float>::infinity()), "inf");
    EXPECT_EQ(numberText(-std::numeric_limits<float>::infinity()), "-inf");
    EXPECT_EQ(numberText(std::nanf("")), "nan");
    EXPECT_EQ(numberText(0.1), "0.1");
    // Every float of a spread of magnitudes parses back to itself.
    for (float v = 1.234567e-20f; v < 1e20f; v *= 7.31f) {
        const std::string text = numberText(v);
        float back = 0.0f;
        const auto r = std::from_chars(text.data(), text.data() + text.size(), back);
        ASSERT_EQ(r.ec, std::errc()) << text;
        EXPECT_EQ(back, v) << text;
    }
}

// A message is one printable line whatever the input quoted in it: control characters and bytes that are not
// UTF-8 become \xNN, well-formed UTF-8 (a file name's) stays as it is.
TEST(Error, MessagesArePrintableAndKeepUtf8) {
    EXPECT_STREQ(Error("caf\xc3\xa9.glb: no such file").what(), "caf\xc3\xa9.glb: no such file");  // é
    EXPECT_STREQ(Error("\xe2\x82\xac \xf0\x9f\x98\x80").what(), "\xe2\x82\xac \xf0\x9f\x98\x80");    // € and U+1F600
    EXPECT_STREQ(Error("line\nbreak\ttab\r\x7f").what(), "line\\x0abreak\\x09tab\\x0d\\x7f");
    EXPECT_STREQ(Error(std::string("nul\0end", 7)).what(), "nul\\x00end");
    // Bytes that only look like UTF-8: a lone continuation, a truncated sequence, an overlong form (C0 80 for
    // NUL), a surrogate (ED A0 80), past U+10FFFF (F4 90 80 80).
    EXPECT_STREQ(Error("\x80 \xc3 \xe2\x82").what(), "\\x80 \\xc3 \\xe2\\x82");
    EXPECT_STREQ(Error("\xc0\x80|\xed\xa0\x80|\xf4\x90\x80\x80").what(),
                 "\\xc0\\x80|\\xed\\xa0\\x80|\\xf4\\x90\\x80\\x80");
    try {
        fail("raw.ply", "element count '\x01\xff\xfe" "3' is not a non-negative integer");
        FAIL() << "fail returned";
    } catch (const Error& e) {
        EXPECT_STREQ(e.what(), "raw.ply: element count '\\x01\\xff\\xfe3' is not a non-negative integer");
    }
}
