// The KMS backend's output selection (connector by name / index / first connected, mode by
// size / preferred / largest) and its one-line errors, on plain data: no DRM device needed.
#include "runtime/platform/KmsSelection.h"

#include <gtest/gtest.h>

#include <string>
#include <vector>

namespace kiosk::platform::kms {
namespace {

const ModeInfo k1080p60{1920, 1080, 60, true};
const ModeInfo k1080p50{1920, 1080, 50, false};
const ModeInfo k720p60{1280, 720, 60, false};
const ModeInfo k4k30{3840, 2160, 30, false};

// A Raspberry-Pi-like card: two HDMI ports, only the second with a monitor, plus a DSI panel
// that reports connected but has no modes yet.
const std::vector<ConnectorInfo> kConnectors = {
    {"HDMI-A-1", false, {}},
    {"HDMI-A-2", true, {k720p60, k1080p50, k1080p60}},
    {"DSI-1", true, {}},
};
const std::string kDevice = "/dev/dri/card1";

struct ConnectorCase {
    const char* name;
    const char* wanted;
    int expected;           ///< index, or -1
    const char* code;       ///< when expected == -1
    const char* substring;  ///< in the formatted diagnostic
};

void PrintTo(const ConnectorCase& c, std::ostream* os) {
    *os << c.name;
}

const ConnectorCase kConnectorCases[] = {
    {"EmptyPicksFirstConnected", "", 1, "", ""},
    {"ByName", "HDMI-A-2", 1, "", ""},
    {"ByIndex", "1", 1, "", ""},
    {"UnknownNameListsAvailable", "HDMI-A-3", -1, "PLATFORM_DRM_CONNECTOR",
     "connector 'HDMI-A-3' not found on /dev/dri/card1; available: 0:HDMI-A-1, "
     "1:HDMI-A-2 (connected), 2:DSI-1"},
    {"IndexOutOfRange", "7", -1, "PLATFORM_DRM_CONNECTOR", "connector '7' not found"},
    {"NamesAreCaseSensitive", "hdmi-a-2", -1, "PLATFORM_DRM_CONNECTOR", "not found"},
    {"NamedButDisconnected", "HDMI-A-1", -1, "PLATFORM_DRM_DISCONNECTED",
     "connector HDMI-A-1 on /dev/dri/card1 has no display connected"},
    {"ConnectedWithoutModesIsNotUsable", "DSI-1", -1, "PLATFORM_DRM_DISCONNECTED", "DSI-1"},
    {"IndexOfDisconnected", "0", -1, "PLATFORM_DRM_DISCONNECTED", "HDMI-A-1"},
};

class ChooseConnector : public ::testing::TestWithParam<ConnectorCase> {};

TEST_P(ChooseConnector, Table) {
    const auto& c = GetParam();
    Diagnostics diags;
    EXPECT_EQ(chooseConnector(kConnectors, c.wanted, kDevice, diags), c.expected);
    if (c.expected >= 0) {
        EXPECT_TRUE(diags.empty()) << diags.format();
        return;
    }
    ASSERT_EQ(diags.size(), 1u) << diags.format();
    EXPECT_EQ(diags.items()[0].code, c.code);
    const std::string text = diags.format();
    EXPECT_NE(text.find(c.substring), std::string::npos) << text;
    EXPECT_EQ(text.find('\n'), text.size() - 1) << "one line: " << text;
}

INSTANTIATE_TEST_SUITE_P(Kms, ChooseConnector, ::testing::ValuesIn(kConnectorCases),
                         [](const auto& p) { return std::string(p.param.name); });

TEST(ChooseConnector, NothingConnectedListsConnectors) {
    const std::vector<ConnectorInfo> none = {{"HDMI-A-1", false, {}}, {"HDMI-A-2", false, {}}};
    Diagnostics diags;
    EXPECT_EQ(chooseConnector(none, "", kDevice, diags), -1);
    ASSERT_EQ(diags.size(), 1u);
    EXPECT_EQ(diags.items()[0].code, "PLATFORM_DRM_NO_CONNECTOR");
    EXPECT_NE(diags.format().find("no connected display on /dev/dri/card1 (connectors: "
                                  "0:HDMI-A-1, 1:HDMI-A-2)"),
              std::string::npos)
        << diags.format();
}

TEST(ChooseConnector, NoConnectorsAtAll) {
    Diagnostics diags;
    EXPECT_EQ(chooseConnector({}, "", kDevice, diags), -1);
    EXPECT_NE(diags.format().find("(connectors: none)"), std::string::npos) << diags.format();
}

TEST(ChooseMode, PreferredWhenNoSizeIsGiven) {
    Diagnostics diags;
    EXPECT_EQ(chooseMode({k720p60, k4k30, k1080p60}, 0, 0, "HDMI-A-1", diags), 2);
    EXPECT_TRUE(diags.empty());
}

TEST(ChooseMode, LargestWhenNothingIsPreferred) {
    Diagnostics diags;
    EXPECT_EQ(chooseMode({k720p60, k1080p50, k4k30}, 0, 0, "HDMI-A-1", diags), 2);
}

TEST(ChooseMode, RequestedSizePrefersPreferredThenRefresh) {
    Diagnostics diags;
    EXPECT_EQ(chooseMode({k1080p50, k720p60, k1080p60}, 1920, 1080, "HDMI-A-1", diags), 2);
    const ModeInfo k1080p30{1920, 1080, 30, false};
    EXPECT_EQ(chooseMode({k1080p30, k1080p50, k720p60}, 1920, 1080, "HDMI-A-1", diags), 1);
    EXPECT_EQ(chooseMode({k4k30, k720p60}, 1280, 720, "HDMI-A-1", diags), 1);
    EXPECT_TRUE(diags.empty()) << diags.format();
}

TEST(ChooseMode, MissingSizeListsModes) {
    Diagnostics diags;
    EXPECT_EQ(chooseMode({k1080p60, k720p60}, 1024, 768, "HDMI-A-2", diags), -1);
    ASSERT_EQ(diags.size(), 1u);
    EXPECT_EQ(diags.items()[0].code, "PLATFORM_DRM_MODE");
    EXPECT_NE(
        diags.format().find("HDMI-A-2 has no 1024x768 mode; available: 1920x1080@60, 1280x720@60"),
        std::string::npos)
        << diags.format();
}

}  // namespace
}  // namespace kiosk::platform::kms
