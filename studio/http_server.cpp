#include "studio/http_server.h"

#include <httplib.h>

#include <atomic>
#include <cctype>
#include <chrono>
#include <stdexcept>
#include <thread>

namespace ontogen::studio {

namespace {
std::string lowerCase(std::string text) {
  for (char& c : text) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return text;
}
}  // namespace

struct HttpServer::Impl {
  httplib::Server server;
  Handler handler;
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
    HttpResponse response = handler(request);
    out.status = response.status;
    // The page follows the model as it changes: no cache may answer for the server.
    out.set_header("Cache-Control", "no-store");
    for (const auto& [name, value] : response.headers) out.set_header(name, value);
    if (!response.stream) {
      out.set_content(response.body, response.contentType);
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
  if (def.port == 0) {
    const int port = server.bind_to_any_port("127.0.0.1");
    if (port <= 0) throw std::runtime_error("cannot listen on 127.0.0.1 at any port");
    port_ = static_cast<uint16_t>(port);
  } else {
    if (!server.bind_to_port("127.0.0.1", def.port))
      throw std::runtime_error("cannot listen on 127.0.0.1:" + std::to_string(def.port) + " (is it taken?)");
    port_ = def.port;
  }
}

HttpServer::~HttpServer() { stop(); }

void HttpServer::start() {
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

}  // namespace ontogen::studio
