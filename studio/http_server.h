#pragma once
// The studio's HTTP server: cpp-httplib (Debian's libcpp-httplib-dev) on 127.0.0.1, a
// pool of threads answering many connections at once, each with its own time-outs. The studio's
// routes (studio/studio_server.h) see a plain HttpRequest and answer an
// HttpResponse; nothing of the library shows through this header.
//
// Why cpp-httplib: it is one small, widely used library packaged by Debian, its
// thread-per-connection pool needs no asynchronous code of ours, and it reads requests
// with the limits a server must have (head and body sizes, read and write time-outs,
// keep-alive counts). Boost.Beast would scale past a few dozen connections, which a page
// on one person's machine never opens, at the price of several hundred lines of
// asynchronous handlers.

#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace ontogen::studio {

struct HttpRequest {
  std::string method;                          ///< "GET", "POST", ...
  std::string path;                            ///< decoded, without the query: "/model.glb"
  std::map<std::string, std::string> query;    ///< decoded ?name=value pairs
  std::map<std::string, std::string> headers;  ///< by lower-case name; the first of repeated ones
  std::string body;
  uint16_t port = 0;  ///< the port of 127.0.0.1 the server listens on, which the request came to

  /// The value of a header by its lower-case name; empty when absent.
  std::string header(const std::string& lowerCaseName) const {
    const auto found = headers.find(lowerCaseName);
    return found == headers.end() ? std::string() : found->second;
  }
};

struct HttpResponse {
  int status = 200;
  std::string contentType = "text/plain; charset=utf-8";
  std::string body;
  std::vector<std::pair<std::string, std::string>> headers = {};  ///< more headers to send
  /// A stream instead of a body (server-sent events): called again and again on the
  /// connection's thread, it sets the next piece to send (it may wait for one, half a
  /// second at most, so the server can stop) and returns false to end the stream. It
  /// ends too when the page goes away or the server stops.
  std::function<bool(std::string& next)> stream = {};
};

struct HttpServerDef {
  uint16_t port = 0;  ///< on 127.0.0.1; 0: a free port the system picks
  /// false: listens nowhere, and answers only answerBytes() as if it listened at port
  /// (the fuzz target of requests, tests/fuzz/fuzz_request.cpp).
  bool listen = true;
  /// Connections answered at once; each open connection (an idle one too, until its
  /// time-out) holds a thread. A page opens at most six, a browser's limit.
  int threads = 48;
  /// Seconds a connection may take to send its request, and to take a response.
  int readTimeoutSeconds = 5;
  int writeTimeoutSeconds = 5;
  /// Seconds an idle connection is kept open for the next request.
  int keepAliveSeconds = 5;
  std::size_t maxBodyBytes = 4 * 1024 * 1024;  ///< larger requests are answered 413
};

class HttpServer {
 public:
  using Handler = std::function<HttpResponse(const HttpRequest&)>;
  /// Listens on 127.0.0.1:def.port and answers with handler, which is called on many
  /// threads at once. Throws std::runtime_error with the reason when the port cannot be
  /// had or the definition is bad. Serving starts with start().
  HttpServer(const HttpServerDef& def, Handler handler);
  /// Stops serving (see stop()).
  ~HttpServer();
  HttpServer(const HttpServer&) = delete;
  HttpServer& operator=(const HttpServer&) = delete;

  /// The port it listens on.
  uint16_t port() const { return port_; }
  /// Answers requests on threads of its own until stop().
  void start();
  /// Stops listening, ends the streams of events and waits for the requests at hand.
  void stop();
  /// The bytes the server answers to `request`, the bytes a client sent on one connection
  /// before it closed: parsed and answered as over a socket (with keep-alive, at most five
  /// requests), without one. Of a stream of events only the head is sent (the library
  /// streams only while it listens). Only on a server that is not serving (start());
  /// not thread-safe.
  std::string answerBytes(std::string_view request);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
  uint16_t port_ = 0;
};

}  // namespace ontogen::studio
