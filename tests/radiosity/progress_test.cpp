// ProgressMeter (radiosity/progress.h): what a long loop tells the terminal.
#include <gtest/gtest.h>

#include <mutex>
#include <string>
#include <vector>

#include "radiosity/parallel.h"
#include "radiosity/progress.h"

using namespace radiosity;

TEST(ProgressMeter, CountsEveryItemFromEveryThreadAndReportsNoMoreThanOnceAPeriod) {
    // Items added from parallelFor's workers are all counted: a report made after the loop
    // (a period of 0 lets every add report; add(0) adds nothing) says 1000 of 1000. With the
    // default period of 10 s, a loop of a few milliseconds reports nothing: a short phase stays
    // quiet.
    std::mutex m;
    std::vector<std::string> lines;
    const auto hear = [&](const std::string& s) {
        const std::lock_guard<std::mutex> lock(m);
        lines.push_back(s);
    };
    {
        ProgressMeter meter(hear, "items", 1000, 0.0);
        parallelFor(1000, 1, [&](size_t) { meter.add(1); });
        meter.add(0);
    }
    ASSERT_FALSE(lines.empty());
    EXPECT_NE(lines.back().find("100 % (1000 of 1000)"), std::string::npos) << lines.back();
    lines.clear();
    ProgressMeter quiet(hear, "items", 1000);
    for (int i = 0; i < 1000; ++i) quiet.add(1);
    EXPECT_TRUE(lines.empty());
}

TEST(ProgressMeter, NothingToDoAndNobodyListeningAreFine) {
    // A total of 0 is reported as done, not divided by; an empty reporter is never called.
    std::vector<std::string> lines;
    ProgressMeter none([&](const std::string& s) { lines.push_back(s); }, "nothing", 0, 0.0);
    none.add(0);
    ASSERT_EQ(lines.size(), 1u);
    EXPECT_NE(lines[0].find("100 % (0 of 0)"), std::string::npos) << lines[0];
    ProgressMeter silent({}, "unheard", 10, 0.0);
    silent.add(10);
}
