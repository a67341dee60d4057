// The demo's statistics JSON (cpp/src/app/StatsJson.cpp): strings escaped as RFC 8259 asks,
// control characters included (the hand-written writer dropped them), invalid UTF-8 replaced,
// unmeasured times null, and frames as an array.
#include <gtest/gtest.h>

#include <string>

#include "app/StatsJson.h"

namespace {

weft::FrameStats sample() {
    weft::FrameStats s;
    s.frameIndex = 7;
    s.cpuMs = 1.5;
    s.gpuMs = -1.0; // not measured
    s.passes.push_back({std::string("say \"hi\"\\\x01\n\x1f"), 0.25, -1.0});
    s.culled = {"tab\there"};
    s.reused = {std::string("bad \xff byte")};
    return s;
}

TEST(StatsJson, EscapesEveryControlCharacterAndQuote) {
    const std::string json = weft::statsToJson(sample(), "dev");
    EXPECT_NE(json.find(R"("name":"say \"hi\"\\\u0001\n\u001f")"), std::string::npos) << json;
    EXPECT_NE(json.find(R"("culled":["tab\there"])"), std::string::npos) << json;
    // U+FFFD (EF BF BD in UTF-8) stands for the byte that is not UTF-8
    EXPECT_NE(json.find("\"bad \xEF\xBF\xBD byte\""), std::string::npos) << json;
    for (char c : json) EXPECT_GE(static_cast<unsigned char>(c), 0x20u) << json;
}

TEST(StatsJson, FieldsInOrderAndUnmeasuredTimesAreNull) {
    const std::string json = weft::statsToJson(sample(), "dev");
    EXPECT_EQ(
        json.rfind(R"({"device":"dev","frame_index":7,"cpu_ms":1.5,"gpu_ms":null,"passes":[)", 0),
        0u)
        << json;
    EXPECT_NE(json.find(R"("cpu_ms":0.25,"gpu_ms":null})"), std::string::npos) << json;
}

TEST(StatsJson, FramesAreAnArray) {
    const std::string json =
        weft::statsToJson(std::vector<weft::FrameStats>{sample(), sample()}, "d");
    EXPECT_EQ(json.front(), '[');
    EXPECT_EQ(json.substr(json.size() - 3), "\n]\n");
    EXPECT_NE(json.find("},\n{\"device\""), std::string::npos) << json;
    EXPECT_EQ(weft::statsToJson(std::vector<weft::FrameStats>{}, "d"), "[\n]\n");
}

} // namespace
