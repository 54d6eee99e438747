#include "services/console/adapter/stream_hub.h"

#include <gtest/gtest.h>

#include <thread>

namespace ssl::console {
namespace {

using std::chrono::milliseconds;

TEST(ConsoleStreams, MessagesAreServerSentEvents) {
  EXPECT_EQ(*sse_message("referee", R"({"command":"STOP"})"), "event: referee\ndata: {\"command\":\"STOP\"}\n\n");
}

TEST(ConsoleStreams, ASlowViewerGetsTheNewestFrameAndEveryOtherMessage) {
  StreamHub hub(4);
  auto client = hub.open();
  ASSERT_TRUE(client);
  hub.push(sse_message("referee", "1"));
  for (int i = 0; i < 10; ++i) hub.push_frame(sse_message("frame", std::to_string(i)));
  hub.push(sse_message("event", "2"));
  const std::vector<Message> sent = client->wait(milliseconds(0));
  ASSERT_EQ(sent.size(), 3u);
  EXPECT_EQ(*sent[0], "event: referee\ndata: 1\n\n");
  EXPECT_EQ(*sent[1], "event: event\ndata: 2\n\n");
  EXPECT_EQ(*sent[2], "event: frame\ndata: 9\n\n");  // the frame last, the newest only
  EXPECT_EQ(client->dropped(), 9u);
  EXPECT_EQ(hub.dropped(), 9u);
}

TEST(ConsoleStreams, TheQueueOfAViewerThatStopsReadingIsBounded) {
  StreamHub hub(4);
  auto stuck = hub.open();
  auto reading = hub.open();
  for (std::size_t i = 0; i < StreamClient::kQueueLimit + 10; ++i) {
    hub.push(sse_message("event", std::to_string(i)));
    if (i % 16 == 0) reading->wait(milliseconds(0));
  }
  EXPECT_EQ(stuck->dropped(), 10u);
  EXPECT_EQ(reading->dropped(), 0u);
  const std::vector<Message> sent = stuck->wait(milliseconds(0));
  ASSERT_EQ(sent.size(), StreamClient::kQueueLimit);
  EXPECT_EQ(*sent.front(), "event: event\ndata: 10\n\n");  // the oldest went
}

TEST(ConsoleStreams, ViewersBeyondTheLimitAreRefusedAndRemovedOnesFreeTheirPlace) {
  StreamHub hub(2);
  auto a = hub.open();
  auto b = hub.open();
  EXPECT_FALSE(hub.open());
  hub.push_frame(sse_message("frame", "x"));
  hub.push_frame(sse_message("frame", "y"));
  hub.remove(a);
  EXPECT_TRUE(a->closed());
  EXPECT_EQ(hub.size(), 1u);
  EXPECT_EQ(hub.dropped(), 2u);  // a's one drop is kept after it left
  EXPECT_TRUE(hub.open());
}

TEST(ConsoleStreams, AWaitingViewerWakesOnAMessageAndOnClose) {
  StreamHub hub(2);
  auto client = hub.open();
  std::thread pusher([&] { hub.push(sse_message("event", "now")); });
  const std::vector<Message> sent = client->wait(milliseconds(5000));
  pusher.join();
  ASSERT_EQ(sent.size(), 1u);
  std::thread closer([&] { hub.close_all(); });
  EXPECT_TRUE(client->wait(milliseconds(5000)).empty());
  closer.join();
  EXPECT_TRUE(client->closed());
}

}  // namespace
}  // namespace ssl::console
