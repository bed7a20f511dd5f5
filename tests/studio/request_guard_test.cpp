// Who may ask the studio (studio/request_guard.h), request by request, without a socket;
// tests/studio/studio_server_test.cpp sends the same over one.

#include <map>
#include <set>
#include <string>

#include <gtest/gtest.h>

#include "studio/request_guard.h"

namespace ontogen::studio {
namespace {

TEST(RequestGuard, TokensAre256RandomBitsInHex) {
  std::set<std::string> seen;
  for (int i = 0; i < 64; ++i) {
    const std::string token = randomToken();
    ASSERT_EQ(token.size(), 64u);
    EXPECT_EQ(token.find_first_not_of("0123456789abcdef"), std::string::npos) << token;
    seen.insert(token);
  }
  EXPECT_EQ(seen.size(), 64u);
}

TEST(RequestGuard, TokensCompareWhole) {
  EXPECT_TRUE(sameToken("ab12", "ab12"));
  EXPECT_FALSE(sameToken("ab12", "ab13"));
  EXPECT_FALSE(sameToken("ab12", "ab1"));
  EXPECT_FALSE(sameToken("ab12", "ab120"));
  EXPECT_FALSE(sameToken("", "ab12"));
  EXPECT_TRUE(sameToken(std::string("a\0b", 3), std::string("a\0b", 3)));
  EXPECT_FALSE(sameToken(std::string("a\0b", 3), std::string("a\0c", 3)));
}

HttpRequest request(std::string method, std::map<std::string, std::string> headers) {
  HttpRequest made;
  made.method = std::move(method);
  made.path = "/api/state";
  made.headers = std::move(headers);
  return made;
}

TEST(RequestGuard, AnswersOnlyTheStudiosAddressAndItsPagesChanges) {
  const std::string token = "f00d";
  auto refusal = [&](const HttpRequest& r) { return refusalOf(r, 8420, token); };
  EXPECT_EQ(refusal(request("GET", {{"host", "127.0.0.1:8420"}})), "");
  EXPECT_EQ(refusal(request("HEAD", {{"host", "LocalHost:8420"}})), "");  // a host name's case does not count
  for (const char* host : {"", "127.0.0.1", "127.0.0.1:842", "127.0.0.1:84200", "localhost", "[::1]:8420",
                           "attacker.com", "evil.example:8420", "127.0.0.1:8420 ", "127.0.0.2:8420"})
    EXPECT_EQ(refusal(request("GET", {{"host", host}})), "the studio answers only requests to 127.0.0.1:8420 or localhost:8420")
        << host;
  const std::map<std::string, std::string> page = {
      {"host", "localhost:8420"}, {"origin", "http://localhost:8420"}, {"x-ontogen-token", token}};
  EXPECT_EQ(refusal(request("POST", page)), "");
  for (const char* method : {"POST", "PUT", "DELETE", "OPTIONS", "PATCH"}) {
    for (const char* origin : {"", "null", "http://evil.example", "https://127.0.0.1:8420", "http://127.0.0.1:8421",
                               "http://127.0.0.1:8420/", "HTTP://127.0.0.1:8420"}) {
      auto headers = page;
      headers["origin"] = origin;
      EXPECT_EQ(refusal(request(method, headers)), "a change must come from the studio's own page (its Origin)")
          << method << " " << origin;
    }
    for (const char* given : {"", "f00", "f00d0", "F00D", "beef"}) {
      auto headers = page;
      headers["x-ontogen-token"] = given;
      EXPECT_EQ(refusal(request(method, headers)), "a change must carry the page's token (X-Ontogen-Token)") << given;
    }
    auto without = page;
    without.erase("x-ontogen-token");
    EXPECT_NE(refusal(request(method, without)), "");
  }
  // A run always has a token: an empty one lets no change through.
  auto empty = page;
  empty["x-ontogen-token"] = "";
  EXPECT_NE(refusalOf(request("POST", empty), 8420, ""), "");
}

}  // namespace
}  // namespace ontogen::studio
