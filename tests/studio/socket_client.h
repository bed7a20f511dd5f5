#pragma once
// A client of the studio's tests over a real socket to 127.0.0.1.

#include <arpa/inet.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <sys/time.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstdint>
#include <string>

namespace ontogen::studio::test {

// Sends raw bytes to 127.0.0.1:port and returns the whole answer.
inline std::string exchange(uint16_t port, const std::string& bytes) {
  const int client = ::socket(AF_INET, SOCK_STREAM, 0);
  sockaddr_in address{};
  address.sin_family = AF_INET;
  address.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  address.sin_port = htons(port);
  if (::connect(client, reinterpret_cast<const sockaddr*>(&address), sizeof address) != 0) {
    ::close(client);
    return "connect failed";
  }
  // No half-close: the server would take it for a page gone away. The requests say
  // `Connection: close`, or are bad ones the server closes after answering. An answer
  // that does not end (a stream of events) is cut after 10 s.
  const timeval wait{1, 0};
  ::setsockopt(client, SOL_SOCKET, SO_RCVTIMEO, &wait, sizeof wait);
  ::send(client, bytes.data(), bytes.size(), MSG_NOSIGNAL);
  std::string answer;
  char buffer[4096];
  const auto end = std::chrono::steady_clock::now() + std::chrono::seconds(10);
  for (ssize_t n; std::chrono::steady_clock::now() < end;) {
    if ((n = ::recv(client, buffer, sizeof buffer, 0)) > 0) answer.append(buffer, static_cast<size_t>(n));
    else if (n == 0 || (errno != EAGAIN && errno != EWOULDBLOCK && errno != EINTR)) break;
  }
  ::close(client);
  return answer;
}

// A socket connected to 127.0.0.1:port, or -1.
inline int connectTo(uint16_t port) {
  const int client = ::socket(AF_INET, SOCK_STREAM, 0);
  sockaddr_in address{};
  address.sin_family = AF_INET;
  address.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  address.sin_port = htons(port);
  if (::connect(client, reinterpret_cast<const sockaddr*>(&address), sizeof address) != 0) {
    ::close(client);
    return -1;
  }
  return client;
}

}  // namespace ontogen::studio::test
