// The operator screen's text with hostile strings: HTML escaping with strict UTF-8, JSON that is
// safe inside a page, server-sent event framing that a string cannot break out of, and the
// operator panel found in both layouts.
#include "screen_format.h"

#include <cmath>

#include <gtest/gtest.h>

#include "hubrt/base/utf8.h"

namespace hubrt::hubctl::screen {
namespace {

using Clock = std::chrono::steady_clock;

TEST(ScreenHtmlEscape, EscapesMarkupAndQuotes) {
  EXPECT_EQ(html_escape("<script>alert('x')</script> & \"q\""),
            "&lt;script&gt;alert(&#39;x&#39;)&lt;/script&gt; &amp; &quot;q&quot;");
  EXPECT_EQ(html_escape("Anna Svensson"), "Anna Svensson");
  EXPECT_EQ(html_escape("Åsa Öberg — ✓"), "Åsa Öberg — ✓");
}

TEST(ScreenHtmlEscape, ReplacesIllFormedUtf8AndControls) {
  // A lone continuation byte, an overlong '<' (C0 BC), an encoded surrogate, a cut-off sequence,
  // NUL, ESC and DEL: each ill-formed byte or control becomes U+FFFD, nothing passes raw.
  const std::string hostile = std::string("a\x80") + "\xC0\xBC" + "\xED\xA0\x80" + "\xE2\x82" +
                              std::string(1, '\0') + "\x1B[2J\x7F" + "\n\tz";
  const std::string out = html_escape(hostile);
  EXPECT_TRUE(is_valid_utf8(out));
  EXPECT_EQ(out.find('<'), std::string::npos);
  EXPECT_EQ(out.find('\x1B'), std::string::npos);
  EXPECT_EQ(out.find('\0'), std::string::npos);
  EXPECT_EQ(out.find('\x7F'), std::string::npos);
  EXPECT_EQ(out.substr(0, 4), "a\xEF\xBF\xBD");
  EXPECT_EQ(out.substr(out.size() - 3), "\n\tz");
}

TEST(ScreenSafeJson, NoMarkupAndValidUtf8) {
  nlohmann::ordered_json value = {{"name", "</script><!-- & \xFF"}, {"n", 3}};
  const std::string out = safe_json(value);
  EXPECT_TRUE(is_valid_utf8(out));
  EXPECT_EQ(out.find('<'), std::string::npos);
  EXPECT_EQ(out.find('>'), std::string::npos);
  EXPECT_EQ(out.find('&'), std::string::npos);
  EXPECT_EQ(out.find('\n'), std::string::npos);
  // Still the same value for the page's JSON.parse (the bad byte as U+FFFD).
  const auto back = nlohmann::json::parse(out);
  EXPECT_EQ(back["name"], "</script><!-- & \xEF\xBF\xBD");
  EXPECT_EQ(back["n"], 3);
}

TEST(ScreenSseEvent, FramesEveryLineAndEndsWithBlankLine) {
  EXPECT_EQ(sse_event("state", "{\"a\":1}"), "event: state\ndata: {\"a\":1}\n\n");
  // A string cannot start its own event or field: each of CR, LF, CRLF starts a new data line.
  EXPECT_EQ(sse_event("state", "x\n\nevent: evil\r\ndata: y\rz"),
            "event: state\ndata: x\ndata: \ndata: event: evil\ndata: data: y\ndata: z\n\n");
  EXPECT_EQ(sse_event("st\nate: x", ""), "event: statex\ndata: \n\n");  // a name cannot break the line
}

WatchedState state_of(const std::string& topic, nlohmann::ordered_json json, Clock::time_point seen) {
  WatchedState w;
  w.topic = topic;
  w.last = std::move(json);
  w.last_seen = seen;
  w.received = 1;
  return w;
}

TEST(ScreenOperator, FoundInBothLayoutsAndSilentWhenOld) {
  const auto now = Clock::now();
  std::map<std::string, WatchedState> states;
  states.emplace("/dock/state", state_of("/dock/state", {{"fresh_msg", true}}, now));
  states.emplace(
      "/operator_hub/state",
      state_of("/operator_hub/state",
               {{"fresh_msg", true},
                {"panel", {{"operator_verified", true}, {"operator_name", "Bo Ek"}, {"confirm_seq", 4}}}},
               now));
  auto op = find_operator(states, "", now);
  EXPECT_EQ(op.topic, "/operator_hub/state");
  EXPECT_TRUE(op.verified);
  EXPECT_TRUE(op.fresh);
  EXPECT_EQ(op.name, "Bo Ek");
  EXPECT_EQ(op.confirm_seq, 4U);

  states.clear();
  states.emplace("/operator_hub/panel/state",
                 state_of("/operator_hub/panel/state", {{"operator_verified", true}, {"operator_name", "A"}},
                          now - std::chrono::seconds(5)));
  op = find_operator(states, "/operator_hub/panel/state", now);
  EXPECT_TRUE(op.verified);
  EXPECT_FALSE(op.fresh);  // silent: not verified as far as the screen is concerned
  EXPECT_FALSE(find_operator(states, "/other/state", now).verified);
  EXPECT_TRUE(find_operator(states, "/other/state", now).topic.empty());
}

TEST(ScreenSnapshot, StationRowsAndInitialHtmlEscaped) {
  const auto now = Clock::now();
  std::map<std::string, WatchedState> states;
  states.emplace("/a/state", state_of("/a/state",
                                      {{"header", {{"lifecycle", 2}}},
                                       {"echo", {{"action", "<b>go</b>"}}},
                                       {"fresh_msg", false},
                                       {"t_plus", 1.5},
                                       {"error_list", {"bad \xC3"}},
                                       {"operator_verified", true},
                                       {"operator_name", "<img src=x onerror=alert(1)>"}},
                                      now));
  states.emplace("/b/state", state_of("/b/state", {{"fresh_msg", true}}, now - std::chrono::seconds(3)));
  WatchedState waiting;
  states.emplace("/c/state", std::move(waiting));
  const auto op = find_operator(states, "", now);
  const auto snap = snapshot(op, Instruction{"bolts", "Place the <bolts>", 7}, states, now);
  EXPECT_EQ(snap["operator"]["name"], "<img src=x onerror=alert(1)>");  // JSON; the page uses textContent
  EXPECT_TRUE(snap["operator"]["verified"].get<bool>());
  EXPECT_EQ(snap["instruction"]["seq"], 7);
  ASSERT_EQ(snap["station"].size(), 3U);
  EXPECT_EQ(snap["station"][0]["fresh"], "no");
  EXPECT_EQ(snap["station"][0]["action"], "<b>go</b>");
  EXPECT_EQ(snap["station"][0]["errors"][0], "bad \xEF\xBF\xBD");
  EXPECT_EQ(snap["station"][1]["fresh"], "silent");
  EXPECT_EQ(snap["station"][2]["fresh"], "waiting");
  EXPECT_TRUE(is_valid_utf8(safe_json(snap)));

  const std::string html = initial_html(op, Instruction{"<bolts>", "Place the <bolts>", 7});
  EXPECT_NE(html.find("&lt;img src=x onerror=alert(1)&gt;"), std::string::npos);
  EXPECT_NE(html.find("Place the &lt;bolts&gt;"), std::string::npos);
  EXPECT_EQ(html.find("<img"), std::string::npos);
  EXPECT_NE(html.find("<h2 id=\"instruction-step\">&lt;bolts&gt;</h2>"), std::string::npos);
  EXPECT_EQ(html.find("<bolts"), std::string::npos);
}

// Floats a peer sent as NaN arrive as null (msgs/json.h: JSON has no NaN): the screen neither
// throws (nlohmann's value(key, 0.0) does on null) nor shows a number; the page prints "-".
TEST(ScreenSnapshot, NaNFloatsBecomeNullNotAnError) {
  const auto now = Clock::now();
  std::map<std::string, WatchedState> states;
  states.emplace(
      "/operator_hub/state",
      state_of("/operator_hub/state",
               {{"fresh_msg", true},
                {"t_plus", nullptr},
                {"panel", {{"operator_verified", true}, {"operator_name", "Bo"}, {"verified_for", nullptr}}}},
               now));
  const auto op = find_operator(states, "", now);
  EXPECT_TRUE(std::isnan(op.verified_for));
  const auto snap = snapshot(op, std::nullopt, states, now);
  EXPECT_TRUE(snap["station"][0]["t_plus"].is_null());
  EXPECT_TRUE(snap["operator"]["verified_for"].is_null());
  EXPECT_EQ(safe_json(snap).find("NaN"), std::string::npos);
}

}  // namespace
}  // namespace hubrt::hubctl::screen
