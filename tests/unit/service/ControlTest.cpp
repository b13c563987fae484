#include "runtime/service/Control.h"
#include "runtime/service/HttpServer.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <fstream>

namespace kiosk::service {
namespace {

TEST(ControlTest, ConstantTimeEqualsComparesWholeStrings) {
    EXPECT_TRUE(constantTimeEquals("secret", "secret"));
    EXPECT_FALSE(constantTimeEquals("secret", "secreT"));
    EXPECT_FALSE(constantTimeEquals("secret", "secret2"));
    EXPECT_FALSE(constantTimeEquals("secret", ""));
    EXPECT_TRUE(constantTimeEquals("", ""));
}

TEST(ControlTest, TokenGuardStatuses) {
    EXPECT_EQ(TokenGuard().check("Bearer anything"), 403);
    const TokenGuard g("s3cret");
    EXPECT_EQ(g.check(""), 401);
    EXPECT_EQ(g.check("Bearer wrong"), 401);
    EXPECT_EQ(g.check("Basic s3cret"), 401);
    EXPECT_EQ(g.check("Bearer s3cret"), 200);
    EXPECT_EQ(g.check("Bearer s3cret "), 401);
}

TEST(ControlTest, TokenFileIsTrimmedAndEmptyIsRefused) {
    const std::string path = testing::TempDir() + "/token";
    std::ofstream(path) << "  abc123 \n second line ignored\n";
    std::string why;
    auto g = TokenGuard::fromFile(path, why);
    ASSERT_TRUE(g) << why;
    EXPECT_EQ(g->check("Bearer abc123"), 200);
    std::ofstream(path) << "   \n";
    EXPECT_FALSE(TokenGuard::fromFile(path, why));
    EXPECT_NE(why.find("is empty"), std::string::npos) << why;
    EXPECT_FALSE(TokenGuard::fromFile(path + ".missing", why));
    EXPECT_NE(why.find("cannot be read"), std::string::npos) << why;
    std::remove(path.c_str());
}

TEST(ControlTest, ParseControl) {
    std::string why;
    bool notFound = false;
    auto seek = parseControl("seek", "+3h", "", why, notFound);
    ASSERT_TRUE(seek) << why;
    EXPECT_EQ(seek->action, ControlAction::Seek);
    EXPECT_TRUE(seek->time.isOffset);
    EXPECT_DOUBLE_EQ(seek->time.seconds, 3 * 3600.0);
    auto iso = parseControl("seek", "2026-03-14T06:40:00Z", "", why, notFound);
    ASSERT_TRUE(iso);
    EXPECT_FALSE(iso->time.isOffset);
    EXPECT_FALSE(parseControl("seek", "", "", why, notFound));
    EXPECT_FALSE(notFound);
    EXPECT_FALSE(parseControl("seek", "yesterday", "", why, notFound));
    auto rate = parseControl("rate", "", "-120", why, notFound);
    ASSERT_TRUE(rate);
    EXPECT_DOUBLE_EQ(rate->rate, -120.0);
    EXPECT_FALSE(parseControl("rate", "", "fast", why, notFound));
    EXPECT_FALSE(parseControl("rate", "", "nan", why, notFound));
    EXPECT_FALSE(parseControl("shutdown", "", "", why, notFound));
    EXPECT_TRUE(notFound);
    for (const char* name : {"pause", "play", "next", "previous", "reload"}) {
        auto c = parseControl(name, "", "", why, notFound);
        ASSERT_TRUE(c) << name;
        EXPECT_STREQ(controlActionName(c->action), name);
    }
}

TEST(ControlTest, QueueIsBoundedAndDrainsInOrder) {
    ControlQueue q;
    ControlCommand c;
    for (std::size_t i = 0; i < ControlQueue::kMaxPending; ++i) {
        c.rate = double(i);
        EXPECT_TRUE(q.push(c));
    }
    EXPECT_FALSE(q.push(c));
    std::vector<ControlCommand> out;
    q.drain(out);
    ASSERT_EQ(out.size(), ControlQueue::kMaxPending);
    EXPECT_DOUBLE_EQ(out[5].rate, 5.0);
    q.drain(out);
    EXPECT_TRUE(out.empty());
}

TEST(ControlTest, ListenAddress) {
    std::string why;
    auto a = parseListenAddress("127.0.0.1:9100", why);
    ASSERT_TRUE(a);
    EXPECT_EQ(a->host, "127.0.0.1");
    EXPECT_EQ(a->port, 9100);
    EXPECT_TRUE(parseListenAddress("0.0.0.0:0", why));
    EXPECT_FALSE(parseListenAddress("9100", why));
    EXPECT_FALSE(parseListenAddress("host:", why));
    EXPECT_FALSE(parseListenAddress("host:70000", why));
    EXPECT_FALSE(parseListenAddress("host:9x", why));
}

}  // namespace
}  // namespace kiosk::service
