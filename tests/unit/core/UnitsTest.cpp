// Units text from data files: cleaned for display, compared by meaning for the spellings data
// sets use (CF/UDUNITS "mm h-1", GDAL unit types "metre", scenario authors' "mm/h").
#include "runtime/core/Units.h"

#include <gtest/gtest.h>

namespace kiosk {
namespace {

TEST(Units, SpellingsOfOneUnitAreTheSame) {
    EXPECT_TRUE(sameUnits("m", "metres"));
    EXPECT_TRUE(sameUnits("meters", " m "));
    EXPECT_TRUE(sameUnits("mm/h", "mm h-1"));
    EXPECT_TRUE(sameUnits("mm/h", "mm hr-1"));
    EXPECT_TRUE(sameUnits("mm/h", "mm h**-1"));
    EXPECT_TRUE(sameUnits("mm/h", "millimetres/hour"));
    EXPECT_TRUE(sameUnits("m/s", "m s-1"));
    EXPECT_TRUE(sameUnits("m/s", "m.s^-1"));
    EXPECT_TRUE(sameUnits("degC", "degrees_Celsius"));
    EXPECT_TRUE(sameUnits("degC", "\u00b0C"));
    EXPECT_EQ(canonicalUnits("kg m-2 s-1"), "kg.m-2/s");
    EXPECT_EQ(canonicalUnits("s-1"), "1/s");
}

TEST(Units, DifferentUnitsAreNot) {
    EXPECT_FALSE(sameUnits("m", "ft"));
    EXPECT_FALSE(sameUnits("mm/h", "mm"));
    EXPECT_FALSE(sameUnits("mm/h", "h/mm"));
    EXPECT_FALSE(sameUnits("mm", "Mm"));  // units are case-sensitive
    EXPECT_FALSE(sameUnits("", ""));      // nothing stated is not agreement
    EXPECT_FALSE(sameUnits("m", ""));
}

TEST(Units, CleaningTrimsAndRefusesWhatCannotBeShown) {
    EXPECT_EQ(cleanUnits("  mm/h\t"), "mm/h");
    EXPECT_EQ(cleanUnits(""), "");
    std::string why;
    EXPECT_FALSE(cleanUnits("mm\x1b[2J", &why));
    EXPECT_EQ(why, "contains control characters");
    EXPECT_FALSE(cleanUnits(std::string(65, 'm'), &why));
    EXPECT_EQ(why, "longer than 64 characters");
    EXPECT_TRUE(cleanUnits(std::string(64, 'm')));
}

}  // namespace
}  // namespace kiosk
