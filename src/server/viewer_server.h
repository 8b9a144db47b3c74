#pragma once
// The viewer's HTTP server (cpp-httplib): the JSON API over a ViewerSession and the page's
// static files. Binds 127.0.0.1 unless told otherwise. The API (README, "Viewer"):
//   GET  /api/scene     the session's summary (JSON)
//   GET  /api/mesh.glb  the display mesh (binary glTF)
//   GET  /api/colors    its vertices' linear radiance, float32 RGB in the .glb's vertex order
//   GET  /api/irradiance  its vertices' irradiance H (W per square scene unit), as the colours
//   GET  /api/objects.csv  each object's mean irradiance and radiosity
//   POST /api/lights    a light state (JSON, see ViewerSession::applyLights); answers the new
//                       colours as /api/colors does, with the relight's time in X-Relight-Ms
// A bad request gets 400 with {"error": message} and changes nothing. Static files come only
// from the page's folder.

#include <filesystem>
#include <memory>
#include <string>

namespace httplib {
class Server;
}

namespace rad {

class ViewerSession;

class ViewerServer {
 public:
  /// Serves `session` and the files under `webRoot` (none if it does not exist).
  ViewerServer(ViewerSession& session, const std::filesystem::path& webRoot);
  ~ViewerServer();

  /// Binds `host`:`port` (0: a free port) and returns the port; throws std::runtime_error if it
  /// cannot.
  int bind(const std::string& host, int port);
  /// Answers requests until stop(); call after bind().
  void run();
  /// Ends run() (from any thread).
  void stop();

  /// The largest request body accepted (bytes): more is a 400.
  static constexpr size_t kMaxBody = 1 << 20;

 private:
  std::unique_ptr<httplib::Server> http_;
};

}  // namespace rad
