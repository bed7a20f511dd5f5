#include "studio/request_guard.h"

#include <sys/random.h>

#include <cctype>
#include <cerrno>
#include <stdexcept>

namespace ontogen::studio {

std::string randomToken() {
  unsigned char bytes[32];
  std::size_t got = 0;
  while (got < sizeof bytes) {
    const ssize_t n = ::getrandom(bytes + got, sizeof bytes - got, 0);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) throw std::runtime_error("the system gives no random bytes for the studio's token");
    got += static_cast<std::size_t>(n);
  }
  static constexpr char kHex[] = "0123456789abcdef";
  std::string token;
  for (const unsigned char byte : bytes) {
    token += kHex[byte >> 4];
    token += kHex[byte & 15];
  }
  return token;
}

bool sameToken(std::string_view a, std::string_view b) {
  if (a.size() != b.size()) return false;
  unsigned char differ = 0;
  for (std::size_t i = 0; i < a.size(); ++i) differ |= static_cast<unsigned char>(a[i] ^ b[i]);
  return differ == 0;
}

namespace {
// A host name compares without regard to case (RFC 9110); the port as written.
bool sameHost(std::string_view given, std::string_view wanted) {
  if (given.size() != wanted.size()) return false;
  for (std::size_t i = 0; i < given.size(); ++i)
    if (std::tolower(static_cast<unsigned char>(given[i])) != wanted[i]) return false;
  return true;
}
}  // namespace

std::string refusalOf(const HttpRequest& request, uint16_t port, std::string_view token) {
  const std::string suffix = ":" + std::to_string(port);
  const std::string host = request.header("host");
  if (!sameHost(host, "127.0.0.1" + suffix) && !sameHost(host, "localhost" + suffix))
    return "the studio answers only requests to 127.0.0.1" + suffix + " or localhost" + suffix;
  if (request.method == "GET" || request.method == "HEAD") return "";
  const std::string origin = request.header("origin");
  if (origin != "http://127.0.0.1" + suffix && origin != "http://localhost" + suffix)
    return "a change must come from the studio's own page (its Origin)";
  const auto given = request.headers.find(kTokenHeader);
  if (token.empty() || given == request.headers.end() || !sameToken(given->second, token))
    return "a change must carry the page's token (X-Ontogen-Token)";
  return "";
}

}  // namespace ontogen::studio
