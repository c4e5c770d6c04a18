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
    // Finite but so large that the normal overflowed to NaN and the polygon passed.
    const PolygonCheck huge = checkPolygon({{0, 0, 0}, {1e154, 0, 0}, {1e154, 1e154, 0}});
    EXPECT_EQ(huge.status, S::nonFinite);
    EXPECT_NE(huge.message.find("1e12"), std::string::npos) << huge.message;
    // A triangle a hundred million kilometres wide is still a polygon.
    const PolygonCheck wide = checkPolygon({{0, 0, 0}, {1e11, 0, 0}, {1e11, 1e11, 0}});
    EXPECT_EQ(wide.status, S::ok);
    EXPECT_NEAR(wide.normal.z, 1.0, 1e-12);
    EXPECT_EQ(checkPolygon({{0, 0, 0}, {1, 0, 0}, {2, 0, 0}}).status, S::degenerate);
    EXPECT_EQ(checkPolygon({{0, 0, 0}, {1, 0, 0}, {1, 1, 0.01}, {0, 1, 0}}).status, S::nonPlanar);
    EXPECT_EQ(checkPolygon({{0, 0, 0}, {1, 0, 0}, {0.2, 0.2, 0}, {0, 1, 0}}).status, S::nonConvex);
}
