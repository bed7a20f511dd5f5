// The studio's HTTP server (studio/http_server.h) over a real socket and without one:
// requests parsed and answered, many connections at once, streams of events.

#include <sys/socket.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <chrono>
#include <string>
#include <thread>
#include <vector>

#include <gtest/gtest.h>

#include "studio/http_server.h"
#include "tests/studio/socket_client.h"

namespace ontogen::studio {
namespace {

using test::connectTo;
using test::exchange;

HttpResponse echo(const HttpRequest& request) {
  return HttpResponse{200, "text/plain", "path " + request.path + " q " + (request.query.count("g") ? request.query.at("g") : "") +
                                             " host " + request.header("host") + " body " + request.body};
}

TEST(HttpServer, AnswersOverASocketAndRefusesBadRequests) {
  HttpServerDef def;
  def.readTimeoutSeconds = 1;  // the request cut short below ends after it,
  def.keepAliveSeconds = 1;    // and the bad ones, which the server keeps alive
  HttpServer server(def, echo);
  ASSERT_GT(server.port(), 0);
  server.start();
  const std::string ok = exchange(server.port(), "GET /a%20b?g=2 HTTP/1.1\r\nHost: here\r\nConnection: close\r\n\r\n");
  EXPECT_TRUE(ok.starts_with("HTTP/1.1 200 OK\r\n")) << ok;
  EXPECT_NE(ok.find("Cache-Control: no-store\r\n"), std::string::npos) << ok;
  EXPECT_TRUE(ok.ends_with("\r\n\r\npath /a b q 2 host here body ")) << ok;
  const std::string posted =
      exchange(server.port(), "POST /p HTTP/1.1\r\nContent-Length: 5\r\nConnection: close\r\n\r\n{\"a\"}tail");
  EXPECT_TRUE(posted.ends_with("body {\"a\"}")) << posted;
  EXPECT_TRUE(exchange(server.port(), "NONSENSE\r\n\r\n").starts_with("HTTP/1.1 400 "));
  EXPECT_TRUE(exchange(server.port(), "POST / HTTP/1.1\r\nContent-Length: 99999999\r\n\r\n").starts_with("HTTP/1.1 413 "));
  // A request cut short is never answered from half of it.
  const std::string cut = exchange(server.port(), "GET /cut HTTP/1.1\r\n");
  EXPECT_TRUE(cut.empty() || cut.starts_with("HTTP/1.1 400 ")) << cut;
  server.stop();
}

// A body is sent as it is, even to a browser that accepts compression: compressing the
// page's 650 KB script with brotli on every request held the page for seconds.
TEST(HttpServer, SendsABodyUncompressed) {
  std::string script(700'000, ' ');
  for (std::size_t i = 0; i < script.size(); ++i) script[i] = "let a = 1; // page\n"[i % 19];
  HttpServer server(HttpServerDef{}, [&script](const HttpRequest&) { return HttpResponse{200, "text/javascript", script}; });
  server.start();
  const std::string answer = exchange(
      server.port(), "GET /studio.js HTTP/1.1\r\nAccept-Encoding: gzip, deflate, br\r\nConnection: close\r\n\r\n");
  EXPECT_TRUE(answer.starts_with("HTTP/1.1 200 OK\r\n")) << answer.substr(0, 300);
  const std::string head = answer.substr(0, answer.find("\r\n\r\n") + 4);
  EXPECT_EQ(head.find("Content-Encoding"), std::string::npos) << head;
  EXPECT_NE(head.find("Content-Length: 700000\r\n"), std::string::npos) << head;
  EXPECT_NE(head.find("Content-Type: text/javascript\r\n"), std::string::npos) << head;
  EXPECT_EQ(answer.substr(head.size()), script);
  server.stop();
}

// Idle connections do not hold up the others: with 20 connections open that send nothing,
// a request is answered while they are all still open, long before their time-out (the
// sequential server answered it only after 20 of them). Nothing here asserts a duration:
// the idle sockets' own time-out is the clock.
TEST(HttpServer, IdleConnectionsDoNotDelayARequest) {
  HttpServerDef def;
  def.readTimeoutSeconds = 20;
  def.keepAliveSeconds = 20;
  HttpServer server(def, echo);
  server.start();
  std::vector<int> idle;
  for (int i = 0; i < 20; ++i) {
    idle.push_back(connectTo(server.port()));
    ASSERT_GE(idle.back(), 0);
  }
  const std::string answer = exchange(server.port(), "GET /busy HTTP/1.1\r\nConnection: close\r\n\r\n");
  EXPECT_TRUE(answer.starts_with("HTTP/1.1 200 OK\r\n")) << answer;
  // Every idle connection is still open: the server has not closed one to get to the request.
  for (int socket : idle) {
    char byte = 0;
    EXPECT_EQ(::recv(socket, &byte, 1, MSG_DONTWAIT), -1);
    EXPECT_TRUE(errno == EAGAIN || errno == EWOULDBLOCK);
    ::close(socket);
  }
  server.stop();
}

// A stream of events (server-sent events) goes on while other requests are answered, and
// ends when the server stops.
TEST(HttpServer, StreamsEventsWhileAnsweringOthersAndEndsThemWhenItStops) {
  std::atomic<int> sent{0};
  HttpServer server(HttpServerDef{}, [&sent](const HttpRequest& request) {
    if (request.path != "/events") return echo(request);
    HttpResponse response{200, "text/event-stream", ""};
    response.stream = [&sent](std::string& next) {
      const int n = ++sent;
      if (n > 3) {  // nothing more to say: wait a while, as the studio waits for a change
        std::this_thread::sleep_for(std::chrono::milliseconds(20));
        next.clear();
      } else {
        next = "data: " + std::to_string(n) + "\n\n";
      }
      return true;
    };
    return response;
  });
  server.start();
  const int client = connectTo(server.port());
  ASSERT_GE(client, 0);
  const std::string ask = "GET /events HTTP/1.1\r\nHost: here\r\n\r\n";
  ::send(client, ask.data(), ask.size(), MSG_NOSIGNAL);
  std::string stream;
  char buffer[4096];
  while (stream.find("data: 3\n\n") == std::string::npos) {
    const ssize_t n = ::recv(client, buffer, sizeof buffer, 0);
    ASSERT_GT(n, 0) << stream;
    stream.append(buffer, static_cast<size_t>(n));
  }
  EXPECT_TRUE(stream.starts_with("HTTP/1.1 200 OK\r\n")) << stream;
  EXPECT_NE(stream.find("Content-Type: text/event-stream"), std::string::npos) << stream;
  EXPECT_NE(stream.find("data: 1\n\n"), std::string::npos) << stream;
  const std::string other = exchange(server.port(), "GET /other HTTP/1.1\r\nConnection: close\r\n\r\n");
  EXPECT_TRUE(other.starts_with("HTTP/1.1 200 OK\r\n")) << other;
  server.stop();
  // The stream has ended: what is left is its last chunk, then the end of the connection.
  ssize_t n = 0;
  while ((n = ::recv(client, buffer, sizeof buffer, 0)) > 0) stream.append(buffer, static_cast<size_t>(n));
  EXPECT_EQ(n, 0);
  ::close(client);
}

// The bytes of one connection answered without a socket (the fuzz target's way in): each
// request kept alive answered in turn; of a stream of events only its head.
TEST(HttpServer, AnswersTheBytesOfAConnectionWithoutListening) {
  HttpServerDef def;
  def.port = 8420;
  def.listen = false;
  int pieces = 0;
  HttpServer server(def, [&pieces](const HttpRequest& request) {
    if (request.path != "/events") {
      HttpResponse response = echo(request);
      response.body += " port " + std::to_string(request.port);
      return response;
    }
    HttpResponse response{200, "text/event-stream", ""};
    response.stream = [&pieces](std::string& next) {
      next = "data: " + std::to_string(++pieces) + "\n\n";
      return true;
    };
    return response;
  });
  EXPECT_EQ(server.port(), 8420);
  EXPECT_THROW(server.start(), std::logic_error);
  const std::string two = server.answerBytes(
      "GET /a?g=1 HTTP/1.1\r\nHost: h\r\n\r\nPOST /b HTTP/1.1\r\nContent-Length: 2\r\n\r\nxy");
  EXPECT_TRUE(two.starts_with("HTTP/1.1 200 OK\r\n")) << two;
  EXPECT_NE(two.find("path /a q 1 host h body  port 8420HTTP/1.1 200 OK\r\n"), std::string::npos) << two;
  EXPECT_TRUE(two.ends_with("path /b q  host  body xy port 8420")) << two;
  EXPECT_TRUE(server.answerBytes("NONSENSE\r\n\r\n").starts_with("HTTP/1.1 400 "));
  const std::string events = server.answerBytes("GET /events HTTP/1.1\r\n\r\n");
  EXPECT_TRUE(events.starts_with("HTTP/1.1 200 OK\r\n")) << events;
  EXPECT_NE(events.find("Content-Type: text/event-stream\r\n"), std::string::npos) << events;
  EXPECT_EQ(pieces, 0);
}

}  // namespace
}  // namespace ontogen::studio
