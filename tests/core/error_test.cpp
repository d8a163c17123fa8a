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
