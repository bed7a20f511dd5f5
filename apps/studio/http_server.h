#pragma once
// A small HTTP/1.1 server for the studio: loopback only (127.0.0.1), one connection at a
// time, every response closes its connection. The studio is one person's page on their
// own machine, so a sequential server is enough, and it keeps the re-growing of the model
// and the answering of requests on one thread with nothing shared.
//
// Requests are read with limits (16 KiB of head, 4 MiB of body, 5 s to arrive): a
// malformed or oversized request is answered 400 or 413 and closed, never a crash.

#include <cstdint>
#include <functional>
#include <map>
#include <string>
#include <string_view>

namespace ontogen::studio {

struct HttpRequest {
  std::string method;                        ///< "GET", "POST", ...
  std::string path;                          ///< decoded, without the query: "/model.glb"
  std::map<std::string, std::string> query;  ///< decoded ?name=value pairs
  std::string body;
};

struct HttpResponse {
  int status = 200;
  std::string contentType = "text/plain; charset=utf-8";
  std::string body;
};

/// Parses the head and body of a request; false when it is malformed. Exposed for tests.
bool parseHttpRequest(std::string_view text, HttpRequest& request);
/// Decodes %XX and '+' of a URL component; false on a bad escape.
bool decodeUrlComponent(std::string_view text, std::string& decoded);

class HttpServer {
 public:
  /// Listens on 127.0.0.1:port (0: a free port the system picks). Throws
  /// std::runtime_error with the reason when the port cannot be had.
  explicit HttpServer(uint16_t port);
  ~HttpServer();
  HttpServer(const HttpServer&) = delete;
  HttpServer& operator=(const HttpServer&) = delete;

  /// The port it listens on.
  uint16_t port() const { return port_; }

  using Handler = std::function<HttpResponse(const HttpRequest&)>;
  /// Answers requests with handler until stop() returns true; between requests, and at
  /// least every idleMilliseconds, calls idle() (the studio looks at its file there).
  void serve(const Handler& handler, const std::function<void()>& idle, const std::function<bool()>& stop,
             int idleMilliseconds = 100);

 private:
  void answer(int connection, const Handler& handler);

  int socket_ = -1;
  uint16_t port_ = 0;
};

}  // namespace ontogen::studio
