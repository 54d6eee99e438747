#include "libs/net/endpoint.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

namespace ssl::net {
namespace {

using ::testing::HasSubstr;

TEST(EndpointTest, ParsesAndFormatsLeagueEndpoints) {
  Result<Endpoint> vision = Endpoint::parse("224.5.23.2:10006");
  ASSERT_TRUE(vision) << vision.error().message;
  EXPECT_EQ(vision->address(), 0xE0051702u);
  EXPECT_EQ(vision->port(), 10006);
  EXPECT_TRUE(vision->is_multicast());
  EXPECT_FALSE(vision->is_loopback());
  EXPECT_EQ(vision->to_string(), "224.5.23.2:10006");
  EXPECT_EQ(vision->address_string(), "224.5.23.2");

  Result<Endpoint> simulator = Endpoint::parse("127.0.0.1:10300");
  ASSERT_TRUE(simulator);
  EXPECT_TRUE(simulator->is_loopback());
  EXPECT_FALSE(simulator->is_multicast());
  EXPECT_EQ(*simulator, Endpoint(0x7F000001u, 10300));
}

TEST(EndpointTest, FormatParseRoundTrip) {
  for (const char* text : {"0.0.0.0:0", "255.255.255.255:65535", "224.5.23.1:10003", "10.0.0.7:20011"}) {
    Result<Endpoint> parsed = Endpoint::parse(text);
    ASSERT_TRUE(parsed) << text;
    EXPECT_EQ(parsed->to_string(), text);
  }
}

TEST(EndpointTest, MulticastRangeIs224To239) {
  EXPECT_TRUE(Endpoint::parse("224.0.0.0:1")->is_multicast());
  EXPECT_TRUE(Endpoint::parse("239.255.255.255:1")->is_multicast());
  EXPECT_FALSE(Endpoint::parse("223.255.255.255:1")->is_multicast());
  EXPECT_FALSE(Endpoint::parse("240.0.0.0:1")->is_multicast());
}

TEST(EndpointTest, BadAddressIsReportedWithTheText) {
  Result<Endpoint> parsed = Endpoint::parse("localhost:10300");
  ASSERT_FALSE(parsed);
  EXPECT_THAT(parsed.error().message, HasSubstr("bad IPv4 address 'localhost'"));
  EXPECT_THAT(parsed.error().message, HasSubstr("'localhost:10300'"));

  for (const char* text : {"1.2.3:5", "1.2.3.256:5", "1.2.3.4.5:5", ":5", "0x7f.0.0.1:5", " 1.2.3.4:5"}) {
    EXPECT_FALSE(Endpoint::parse(text)) << text;
  }
}

TEST(EndpointTest, MissingOrBadPortIsReported) {
  Result<Endpoint> no_port = Endpoint::parse("127.0.0.1");
  ASSERT_FALSE(no_port);
  EXPECT_THAT(no_port.error().message, HasSubstr("expected address:port like 127.0.0.1:10300"));

  Result<Endpoint> not_a_number = Endpoint::parse("127.0.0.1:http");
  ASSERT_FALSE(not_a_number);
  EXPECT_THAT(not_a_number.error().message, HasSubstr("port 'http' is not a number"));

  Result<Endpoint> too_big = Endpoint::parse("127.0.0.1:70000");
  ASSERT_FALSE(too_big);
  EXPECT_THAT(too_big.error().message, HasSubstr("port 70000 is out of range [0, 65535]"));

  EXPECT_FALSE(Endpoint::parse("127.0.0.1:-1"));
  EXPECT_FALSE(Endpoint::parse("127.0.0.1:99999999999999999999"));
  EXPECT_FALSE(Endpoint::parse("127.0.0.1:"));
  EXPECT_FALSE(Endpoint::parse("127.0.0.1:80x"));
}

TEST(EndpointTest, FromPartsValidatesBoth) {
  EXPECT_EQ(*Endpoint::from_parts("224.5.23.1", 10003), *Endpoint::parse("224.5.23.1:10003"));
  Result<Endpoint> bad_port = Endpoint::from_parts("127.0.0.1", 65536);
  ASSERT_FALSE(bad_port);
  EXPECT_EQ(bad_port.error().message, "port 65536 is out of range [0, 65535]");
  Result<Endpoint> bad_address = Endpoint::from_parts("300.1.1.1", 1);
  ASSERT_FALSE(bad_address);
  EXPECT_THAT(bad_address.error().message, HasSubstr("bad IPv4 address '300.1.1.1'"));
}

}  // namespace
}  // namespace ssl::net
