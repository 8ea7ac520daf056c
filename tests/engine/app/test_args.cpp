#include "app/args.h"
#include "core/error.h"

#include <gtest/gtest.h>

using namespace meadow;

namespace {
CommandSpec renderSpec() {
    return {"render", {"SCENE"}, {"--out", "--size", "--frames", "--camera"}, {"--validation"}};
}
} // namespace

TEST(Args, ParsesValuesSwitchesAndPositionals) {
    ParsedArgs a = parseArgs(renderSpec(), {"scene.json", "--out", "x.png", "--size=320x200", "--validation"});
    EXPECT_EQ(a.positionals, std::vector<std::string>{"scene.json"});
    EXPECT_EQ(a.value("--out"), "x.png");
    EXPECT_TRUE(a.has("--validation"));
    EXPECT_EQ(a.size("--size", {1, 1}), std::make_pair(320u, 200u));
    EXPECT_EQ(a.u32("--frames", 7, 1, 10), 7u); // absent: the fallback
}

TEST(Args, RejectsUnknownOptionsByName) {
    try {
        parseArgs(renderSpec(), {"scene.json", "--bogus"});
        FAIL();
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("unknown option --bogus"), std::string::npos) << e.what();
    }
    EXPECT_THROW(parseArgs(renderSpec(), {"scene.json", "-x"}), Error);
}

TEST(Args, RejectsMissingAndExtraPositionals) {
    EXPECT_THROW(parseArgs(renderSpec(), {}), Error);
    EXPECT_THROW(parseArgs(renderSpec(), {"a.json", "b.json"}), Error);
    EXPECT_THROW(parseArgs(renderSpec(), {"a.json", "--out"}), Error);          // value missing
    EXPECT_THROW(parseArgs(renderSpec(), {"a.json", "--validation=1"}), Error); // switch with value
    EXPECT_THROW(parseArgs(renderSpec(), {"a.json", "--out", "a", "--out", "b"}), Error);
}

TEST(Args, TypedValuesAreChecked) {
    ParsedArgs a = parseArgs(renderSpec(), {"s", "--size", "0x10", "--frames", "-3", "--camera", "1,2,3,4,5"});
    EXPECT_THROW(a.size("--size", {1, 1}), Error);
    EXPECT_THROW(a.u32("--frames", 1, 1, 10), Error);
    EXPECT_THROW(a.floats("--camera", 6), Error);
    ParsedArgs b = parseArgs(renderSpec(), {"s", "--frames", "11", "--camera", "1,2,3,4,5,6.5", "--size", "12x"});
    EXPECT_THROW(b.u32("--frames", 1, 1, 10), Error);
    EXPECT_EQ((*b.floats("--camera", 6))[5], 6.5f);
    EXPECT_THROW(b.size("--size", {1, 1}), Error);
}
