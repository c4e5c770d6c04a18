#include "radiosity/scene.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

using namespace radiosity;

TEST(CheckPolygon, UnitSquareIsOkWithAreaAndNormal) {
    PolygonCheck c = checkPolygon({{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}});
    ASSERT_EQ(c.status, PolygonCheck::Status::ok) << c.message;
    EXPECT_NEAR(c.area, 1.0, 1e-12);
    EXPECT_NEAR(c.normal.z, 1.0, 1e-12);
}

TEST(CheckPolygon, RejectsEachDefectClass) {
    using S = PolygonCheck::Status;
    const double nan = std::numeric_limits<double>::quiet_NaN();
    EXPECT_EQ(checkPolygon({{0, 0, 0}, {1, 0, 0}}).status, S::tooFew);
    EXPECT_EQ(checkPolygon({{0, 0, nan}, {1, 0, 0}, {1, 1, 0}}).status, S::nonFinite);
    EXPECT_EQ(checkPolygon({{0, 0, 0}, {1, 0, 0}, {2, 0, 0}}).status, S::degenerate);
    EXPECT_EQ(checkPolygon({{0, 0, 0}, {1, 0, 0}, {1, 1, 0.01}, {0, 1, 0}}).status, S::nonPlanar);
    EXPECT_EQ(checkPolygon({{0, 0, 0}, {1, 0, 0}, {0.2, 0.2, 0}, {0, 1, 0}}).status, S::nonConvex);
}
