#pragma once
// The viewer's HTTP server (cpp-httplib): the JSON API over a ViewerSession and the page's
// static files. Binds 127.0.0.1 unless told otherwise. The API (docs/ARCHITECTURE.md, "The
// viewer's server"):
//   GET  /api/progress  {"ready", "progress"}: the solve's progress before the rest answers (503)
//   GET  /api/scene     the session's summary (JSON)
//   GET  /api/mesh.glb  the display mesh (binary glTF)
//   GET  /api/colors    its vertices' linear radiance, float32 RGB in the .glb's vertex order
//   GET  /api/irradiance  its vertices' irradiance H (W per square scene unit), as the colours
//   GET  /api/objects.csv  each object's mean irradiance and radiosity
//   GET  /api/dynamic?t=   the dynamic objects placed at t seconds, lit by probes (JSON)
//   POST /api/lights    a light state (JSON, see ViewerSession::applyLights); answers the new
//                       colours as /api/colors does, with the relight's time in X-Relight-Ms
// A bad request gets 400 with {"error": message} and changes nothing. Static files come only
// from the page's folder. Only the server's own page and command-line clients drive it: every
// request must name the server in its Host (localhost, 127.0.0.1, [::1] or the address it was
// bound to: no DNS rebinding), and a POST must come from the same origin (or carry no Origin, as
// command-line clients send) with Content-Type application/json (no cross-site "simple"
// request); else 403. No CORS headers are sent unless allowOrigin() names one other page's origin.
// A port another server holds is refused.

#include <atomic>
#include <filesystem>
#include <memory>
#include <string>

namespace httplib {
class Server;
struct Request;
struct Response;
}  // namespace httplib

namespace rad {

class BoundedHttpServer;
class ViewerSession;

class ViewerServer {
 public:
  /// Serves the files under `webRoot` (none if it does not exist); the API answers 503 with the
  /// solve's progress (GET /api/progress) until serve() gives it a session.
  explicit ViewerServer(const std::filesystem::path& webRoot);
  /// Serves `session` and the files under `webRoot`.
  ViewerServer(ViewerSession& session, const std::filesystem::path& webRoot);
  /// From now on the API answers from `session` (which must outlive the server).
  void serve(ViewerSession& session);
  /// The solve's progress while there is no session yet, in [0, 1].
  void setProgress(double fraction);
  ~ViewerServer();

  /// Lets the page served from `origin` ("http://host:port", as a browser sends it in Origin)
  /// drive the server too: its requests are answered with CORS headers (Access-Control-Allow-
  /// Origin: origin, Vary: Origin) and its preflights (OPTIONS) with the methods and headers the
  /// API takes. Throws InputError naming --allow-origin for anything but a scheme, a host and an
  /// optional port ("*" included: every site would drive it).
  void allowOrigin(const std::string& origin);

  /// Binds `host`:`port` (0: a free port) and returns the port; throws InputError naming the
  /// address if it cannot (the port is taken: no other server shares it).
  int bind(const std::string& host, int port);
  /// Answers requests until stop(); call after bind().
  void run();
  /// Returns once run() (on another thread) is answering, so that a stop() after it ends it.
  void waitUntilRunning() const;
  /// Ends run() (from any thread).
  void stop();

  /// The largest request body accepted (bytes): more is a 413, refused before it is read.
  static constexpr size_t kMaxBody = 1 << 20;

 private:
  template <class F>
  void withSession(httplib::Response& response, F&& f) const;

  /// Why a request is refused (403) before any route sees it: a Host that is not this server,
  /// a state change from another origin or not as JSON; "" when it is not.
  std::string refusal(const httplib::Request& request) const;

  std::unique_ptr<BoundedHttpServer> http_;
  /// The CORS headers for a request from the allowed origin (none for any other).
  void addCorsHeaders(const httplib::Request& request, httplib::Response& response) const;

  std::string host_;           ///< the address bound to; a request's Host may name it
  std::string allowedOrigin_;  ///< another page's origin that may drive it; "" for none
  std::atomic<ViewerSession*> session_{nullptr};
  std::atomic<double> progress_{0.0};
};

}  // namespace rad
