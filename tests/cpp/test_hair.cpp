// .hair serialisation and fur counts through the C++ API (no GPU needed).
#include <gtest/gtest.h>

#include <cstring>

#include <weft/Error.h>
#include <weft/HairGenerator.h>
#include <weft/HairIo.h>

namespace {

weft::HairStrands twoStrands() {
    weft::HairStrands h;
    h.points = {{0, 0, 0}, {0, 1, 0}, {1, 0, 0}, {1, 1, 0}, {1, 2, 0}};
    h.segments = {1, 2};
    h.thickness = {1, 2, 3, 4, 5};
    return h;
}

} // namespace

TEST(HairIo, RoundTripKeepsEveryArrayAndLayout) {
    const weft::HairStrands h = twoStrands();
    const std::vector<uint8_t> bytes = weft::serializeHair(h);
    // header + 2 uint16 segments + 5 xyz + 5 thickness
    ASSERT_EQ(bytes.size(), 128u + 4u + 60u + 20u);
    EXPECT_EQ(std::memcmp(bytes.data(), "HAIR", 4), 0);
    EXPECT_EQ(bytes[12], 1u | 2u | 4u); // flags: segments, points, thickness
    const weft::HairStrands back = weft::parseHair(bytes.data(), bytes.size());
    EXPECT_EQ(back.points, h.points);
    EXPECT_EQ(back.segments, h.segments);
    EXPECT_EQ(back.thickness, h.thickness);
    EXPECT_TRUE(back.warnings.empty());
}

TEST(HairIo, EveryTruncationIsRejected) {
    const std::vector<uint8_t> bytes = weft::serializeHair(twoStrands());
    for (size_t n = 0; n < bytes.size(); ++n)
        EXPECT_THROW(weft::parseHair(bytes.data(), n), weft::IoError) << n;
}

TEST(HairGenerator, FurStrandCountsAndSeedListing) {
    weft::Mesh mesh = weft::Mesh::plane(1.0f, 1.0f, 2, 2); // 8 triangles
    weft::FurParams p;
    p.level = 3;
    const weft::HairStrands fur = weft::generateFur(mesh, p);
    EXPECT_EQ(fur.strandCount(), 8u * 9u);
    EXPECT_EQ(fur.pointCount(), 8u * 9u * 11u);
    // the first step of every strand is the normal (+Y) times the segment length 0.03
    const glm::vec3 step = fur.points[1] - fur.points[0];
    EXPECT_NEAR(step.y, 0.03f, 1e-6f);
    EXPECT_NEAR(step.x, 0.0f, 1e-6f);
    p.level = 0;
    EXPECT_THROW(weft::generateFur(mesh, p), weft::InvalidArgument);
}
