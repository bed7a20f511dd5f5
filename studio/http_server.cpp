#include "studio/http_server.h"

#include <httplib.h>

#include <algorithm>
#include <atomic>
#include <memory>
#include <cctype>
#include <chrono>
#include <stdexcept>
#include <thread>

namespace ontogen::studio {

namespace {
// The library's server, with the request loop of one connection open to answerBytes().
struct LibraryServer : httplib::Server {
  using httplib::Server::process_request;
};

// One connection's bytes in, the answer's bytes out.
class BytesStream final : public httplib::Stream {
 public:
  explicit BytesStream(std::string_view in) : in_(in) {}
  bool is_readable() const override { return true; }
  bool is_writable() const override { return true; }
  ssize_t read(char* into, size_t size) override {
    const size_t n = std::min(size, in_.size());
    std::copy_n(in_.data(), n, into);
    in_.remove_prefix(n);
    return static_cast<ssize_t>(n);
  }
  ssize_t write(const char* from, size_t size) override {
    out_.append(from, size);
    return static_cast<ssize_t>(size);
  }
  void get_remote_ip_and_port(std::string& ip, int& port) const override {
    ip = "127.0.0.1";
    port = 0;
  }
  void get_local_ip_and_port(std::string& ip, int& port) const override {
    ip = "127.0.0.1";
    port = 0;
  }
  socket_t socket() const override { return INVALID_SOCKET; }
  bool atEnd() const { return in_.empty(); }
  std::string& out() { return out_; }

 private:
  std::string_view in_;
  std::string out_;
};

std::string lowerCase(std::string text) {
  for (char& c : text) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return text;
}
}  // namespace

struct HttpServer::Impl {
  LibraryServer server;
  Handler handler;
  uint16_t port = 0;
  bool listening = false;
  std::thread serving;
  std::atomic<bool> ended{false};     // listening ended (or never began)
  std::atomic<bool> stopping{false};  // streams end

  void answer(const httplib::Request& in, httplib::Response& out) {
    HttpRequest request;
    request.method = in.method;
    request.path = in.path;
    for (const auto& [name, value] : in.params) request.query.emplace(name, value);
    for (const auto& [name, value] : in.headers) request.headers.emplace(lowerCase(name), value);
    request.body = in.body;
    request.port = port;
    HttpResponse response = handler(request);
    out.status = response.status;
    // The page follows the model as it changes: no cache may answer for the server.
    out.set_header("Cache-Control", "no-store");
    for (const auto& [name, value] : response.headers) out.set_header(name, value);
    // A body is sent as it is, never compressed: the library compresses a body given whole
    // on every request that accepts it (brotli took seconds over the page's 650 KB script),
    // which over loopback only delays the page; a body of known length from a provider it
    // sends unchanged. (Without a socket, for answerBytes(), the library writes no
    // provider's body: there it is given whole.)
    if (!response.stream && (response.body.empty() || !listening)) {
      out.set_content(response.body, response.contentType);
      return;
    }
    if (!response.stream) {
      auto body = std::make_shared<const std::string>(std::move(response.body));
      out.set_content_provider(body->size(), response.contentType,
                               [body](std::size_t offset, std::size_t length, httplib::DataSink& sink) {
                                 return sink.write(body->data() + offset, std::min(length, body->size() - offset));
                               });
      return;
    }
    out.set_chunked_content_provider(
        response.contentType, [this, stream = std::move(response.stream)](std::size_t, httplib::DataSink& sink) {
          std::string next;
          if (stopping || !stream(next) || stopping) {
            sink.done();
            return true;
          }
          return next.empty() || sink.write(next.data(), next.size());
        });
  }
};

HttpServer::HttpServer(const HttpServerDef& def, Handler handler) : impl_(std::make_unique<Impl>()) {
  if (def.threads < 1 || def.readTimeoutSeconds < 1 || def.writeTimeoutSeconds < 1 || def.keepAliveSeconds < 1)
    throw std::runtime_error("the HTTP server needs a thread and time-outs of at least a second");
  impl_->handler = std::move(handler);
  httplib::Server& server = impl_->server;
  const auto threads = static_cast<std::size_t>(def.threads);
  server.new_task_queue = [threads] { return new httplib::ThreadPool(threads); };
  server.set_read_timeout(def.readTimeoutSeconds, 0);
  server.set_write_timeout(def.writeTimeoutSeconds, 0);
  server.set_keep_alive_timeout(def.keepAliveSeconds);
  server.set_payload_max_length(def.maxBodyBytes);
  auto route = [impl = impl_.get()](const httplib::Request& in, httplib::Response& out) { impl->answer(in, out); };
  server.Get(".*", route);
  server.Post(".*", route);
  server.Put(".*", route);
  server.Patch(".*", route);
  server.Delete(".*", route);
  server.Options(".*", route);
  server.set_exception_handler([](const httplib::Request&, httplib::Response& out, std::exception_ptr) {
    out.status = 500;
    out.set_content("{\"error\": \"internal error\"}", "application/json");
  });
  // Loopback only: never reachable from another machine.
  impl_->listening = def.listen;
  if (!def.listen) {
    port_ = def.port;
  } else if (def.port == 0) {
    const int port = server.bind_to_any_port("127.0.0.1");
    if (port <= 0) throw std::runtime_error("cannot listen on 127.0.0.1 at any port");
    port_ = static_cast<uint16_t>(port);
  } else {
    if (!server.bind_to_port("127.0.0.1", def.port))
      throw std::runtime_error("cannot listen on 127.0.0.1:" + std::to_string(def.port) + " (is it taken?)");
    port_ = def.port;
  }
  impl_->port = port_;
}

HttpServer::~HttpServer() { stop(); }

void HttpServer::start() {
  if (!impl_->listening) throw std::logic_error("a server that listens nowhere cannot start");
  if (impl_->serving.joinable()) return;
  impl_->serving = std::thread([impl = impl_.get()] {
    impl->server.listen_after_bind();
    impl->ended = true;
  });
  // stop() can end the serving only once it runs.
  while (!impl_->server.is_running() && !impl_->ended) std::this_thread::sleep_for(std::chrono::milliseconds(1));
}

void HttpServer::stop() {
  impl_->stopping = true;
  impl_->server.stop();
  if (impl_->serving.joinable()) impl_->serving.join();
}

std::string HttpServer::answerBytes(std::string_view request) {
  if (impl_->serving.joinable()) throw std::logic_error("answerBytes() on a server that is serving");
  BytesStream stream(request);
  // As the library answers a connection: requests one after another while it is kept alive.
  for (int left = 5; left > 0 && !stream.atEnd(); --left) {
    bool closed = false;
    if (!impl_->server.process_request(stream, left == 1, closed, nullptr) || closed) break;
  }
  return std::move(stream.out());
}

}  // namespace ontogen::studio
