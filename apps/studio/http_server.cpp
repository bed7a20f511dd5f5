#include "apps/studio/http_server.h"

#include <arpa/inet.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstring>
#include <stdexcept>

namespace ontogen::studio {

namespace {
constexpr std::size_t kMaxHeadBytes = 16 * 1024;
constexpr std::size_t kMaxBodyBytes = 4 * 1024 * 1024;
constexpr int kRequestMilliseconds = 5000;

int hexValue(char c) {
  if (c >= '0' && c <= '9') return c - '0';
  if (c >= 'a' && c <= 'f') return c - 'a' + 10;
  if (c >= 'A' && c <= 'F') return c - 'A' + 10;
  return -1;
}

const char* reasonOf(int status) {
  switch (status) {
    case 200: return "OK";
    case 400: return "Bad Request";
    case 404: return "Not Found";
    case 405: return "Method Not Allowed";
    case 408: return "Request Timeout";
    case 413: return "Payload Too Large";
    case 422: return "Unprocessable Content";
    case 500: return "Internal Server Error";
    default: return "Status";
  }
}

// Case-insensitive equality of ASCII header names.
bool sameName(std::string_view a, std::string_view b) {
  if (a.size() != b.size()) return false;
  for (std::size_t i = 0; i < a.size(); ++i) {
    char x = a[i], y = b[i];
    if (x >= 'A' && x <= 'Z') x = static_cast<char>(x - 'A' + 'a');
    if (y >= 'A' && y <= 'Z') y = static_cast<char>(y - 'A' + 'a');
    if (x != y) return false;
  }
  return true;
}

// The value of Content-Length in a head, 0 when absent; false when it is not a number.
bool contentLengthOf(std::string_view head, std::size_t& length) {
  length = 0;
  std::size_t start = head.find("\r\n");
  while (start != std::string_view::npos && start + 2 < head.size()) {
    const std::size_t end = head.find("\r\n", start + 2);
    const std::string_view line = head.substr(start + 2, (end == std::string_view::npos ? head.size() : end) - start - 2);
    const std::size_t colon = line.find(':');
    if (colon != std::string_view::npos && sameName(line.substr(0, colon), "content-length")) {
      std::string_view value = line.substr(colon + 1);
      while (!value.empty() && (value.front() == ' ' || value.front() == '\t')) value.remove_prefix(1);
      while (!value.empty() && (value.back() == ' ' || value.back() == '\t')) value.remove_suffix(1);
      if (value.empty() || value.size() > 12) return false;
      for (char c : value) {
        if (c < '0' || c > '9') return false;
        length = length * 10 + static_cast<std::size_t>(c - '0');
      }
    }
    start = end;
  }
  return true;
}

void sendAll(int connection, const std::string& bytes) {
  std::size_t sent = 0;
  while (sent < bytes.size()) {
    const ssize_t n = ::send(connection, bytes.data() + sent, bytes.size() - sent, MSG_NOSIGNAL);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) return;  // the page went away; nothing to tell it
    sent += static_cast<std::size_t>(n);
  }
}

void respond(int connection, const HttpResponse& response) {
  std::string head = "HTTP/1.1 " + std::to_string(response.status) + " " + reasonOf(response.status) + "\r\n";
  head += "Content-Type: " + response.contentType + "\r\n";
  head += "Content-Length: " + std::to_string(response.body.size()) + "\r\n";
  // The page polls for new versions; no cache may answer for the server.
  head += "Cache-Control: no-store\r\nConnection: close\r\n\r\n";
  sendAll(connection, head + response.body);
}
}  // namespace

bool decodeUrlComponent(std::string_view text, std::string& decoded) {
  decoded.clear();
  for (std::size_t i = 0; i < text.size(); ++i) {
    if (text[i] == '+') {
      decoded += ' ';
    } else if (text[i] == '%') {
      if (i + 2 >= text.size()) return false;
      const int high = hexValue(text[i + 1]), low = hexValue(text[i + 2]);
      if (high < 0 || low < 0) return false;
      decoded += static_cast<char>(high * 16 + low);
      i += 2;
    } else {
      decoded += text[i];
    }
  }
  return true;
}

bool parseHttpRequest(std::string_view text, HttpRequest& request) {
  const std::size_t headEnd = text.find("\r\n\r\n");
  if (headEnd == std::string_view::npos) return false;
  const std::string_view head = text.substr(0, headEnd);
  const std::string_view requestLine = head.substr(0, head.find("\r\n"));
  const std::size_t space1 = requestLine.find(' ');
  const std::size_t space2 = requestLine.find(' ', space1 == std::string_view::npos ? 0 : space1 + 1);
  if (space1 == std::string_view::npos || space2 == std::string_view::npos || space1 == 0) return false;
  if (!requestLine.substr(space2 + 1).starts_with("HTTP/1.")) return false;
  request.method = std::string(requestLine.substr(0, space1));
  for (char c : request.method)
    if (c < 'A' || c > 'Z') return false;
  const std::string_view target = requestLine.substr(space1 + 1, space2 - space1 - 1);
  if (!target.starts_with("/")) return false;
  const std::size_t question = target.find('?');
  if (!decodeUrlComponent(target.substr(0, question), request.path)) return false;
  request.query.clear();
  if (question != std::string_view::npos) {
    std::string_view rest = target.substr(question + 1);
    while (!rest.empty()) {
      const std::size_t amp = rest.find('&');
      const std::string_view pair = rest.substr(0, amp);
      const std::size_t equals = pair.find('=');
      std::string name, value;
      if (!decodeUrlComponent(pair.substr(0, equals), name)) return false;
      if (equals != std::string_view::npos && !decodeUrlComponent(pair.substr(equals + 1), value)) return false;
      if (!name.empty()) request.query[name] = value;
      if (amp == std::string_view::npos) break;
      rest.remove_prefix(amp + 1);
    }
  }
  std::size_t length = 0;
  if (!contentLengthOf(head, length)) return false;
  if (text.size() - headEnd - 4 < length) return false;
  request.body = std::string(text.substr(headEnd + 4, length));
  return true;
}

HttpServer::HttpServer(uint16_t port) {
  socket_ = ::socket(AF_INET, SOCK_STREAM | SOCK_CLOEXEC, 0);
  if (socket_ < 0) throw std::runtime_error(std::string("cannot open a socket: ") + std::strerror(errno));
  const int yes = 1;
  ::setsockopt(socket_, SOL_SOCKET, SO_REUSEADDR, &yes, sizeof yes);
  sockaddr_in address{};
  address.sin_family = AF_INET;
  address.sin_addr.s_addr = htonl(INADDR_LOOPBACK);  // never reachable from another machine
  address.sin_port = htons(port);
  if (::bind(socket_, reinterpret_cast<const sockaddr*>(&address), sizeof address) != 0 || ::listen(socket_, 16) != 0) {
    const std::string reason = std::strerror(errno);
    ::close(socket_);
    socket_ = -1;
    throw std::runtime_error("cannot listen on 127.0.0.1:" + std::to_string(port) + ": " + reason);
  }
  socklen_t size = sizeof address;
  ::getsockname(socket_, reinterpret_cast<sockaddr*>(&address), &size);
  port_ = ntohs(address.sin_port);
}

HttpServer::~HttpServer() {
  if (socket_ >= 0) ::close(socket_);
}

void HttpServer::serve(const Handler& handler, const std::function<void()>& idle, const std::function<bool()>& stop,
                       int idleMilliseconds) {
  while (!stop()) {
    pollfd listening{socket_, POLLIN, 0};
    const int ready = ::poll(&listening, 1, idleMilliseconds);
    if (ready > 0 && (listening.revents & POLLIN)) {
      const int connection = ::accept4(socket_, nullptr, nullptr, SOCK_CLOEXEC);
      if (connection >= 0) {
        answer(connection, handler);
        ::close(connection);
      }
    }
    idle();
  }
}

void HttpServer::answer(int connection, const Handler& handler) {
  using Clock = std::chrono::steady_clock;
  const auto deadline = Clock::now() + std::chrono::milliseconds(kRequestMilliseconds);
  std::string received;
  std::size_t wanted = 0;  // head + body, once the head is in
  char buffer[16384];
  while (wanted == 0 || received.size() < wanted) {
    const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(deadline - Clock::now()).count();
    if (left <= 0) return respond(connection, {408, "text/plain; charset=utf-8", "the request did not arrive in time\n"});
    pollfd readable{connection, POLLIN, 0};
    const int ready = ::poll(&readable, 1, static_cast<int>(left));
    if (ready < 0 && errno == EINTR) continue;
    if (ready <= 0) continue;
    const ssize_t n = ::recv(connection, buffer, sizeof buffer, 0);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) return;  // closed before a whole request
    received.append(buffer, static_cast<std::size_t>(n));
    if (wanted == 0) {
      const std::size_t headEnd = received.find("\r\n\r\n");
      if (headEnd == std::string::npos) {
        if (received.size() > kMaxHeadBytes)
          return respond(connection, {413, "text/plain; charset=utf-8", "the request's head is too long\n"});
        continue;
      }
      std::size_t length = 0;
      if (!contentLengthOf(std::string_view(received).substr(0, headEnd), length))
        return respond(connection, {400, "text/plain; charset=utf-8", "bad Content-Length\n"});
      if (length > kMaxBodyBytes)
        return respond(connection, {413, "text/plain; charset=utf-8", "the request's body is too long\n"});
      wanted = headEnd + 4 + length;
    }
  }
  HttpRequest request;
  if (!parseHttpRequest(received, request))
    return respond(connection, {400, "text/plain; charset=utf-8", "malformed request\n"});
  respond(connection, handler(request));
}

}  // namespace ontogen::studio
