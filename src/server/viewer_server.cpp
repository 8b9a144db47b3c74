// The viewer's routes on cpp-httplib.
#include <fmt/format.h>
#include <httplib.h>
#include <radiosity/error.h>
#include <radiosity/scene_builder.h>
#include <radiosity/viewer_server.h>
#include <radiosity/viewer_session.h>
#include <sys/socket.h>

#include <algorithm>
#include <charconv>
#include <chrono>
#include <cmath>
#include <glm/geometric.hpp>
#include <nlohmann/json.hpp>
#include <regex>
#include <stdexcept>
#include <thread>

#include "server/bounded_http_server.h"
#include "server/light_request.h"

namespace rad {

namespace {

void badRequest(httplib::Response& response, const std::string& message) {
  response.status = 400;
  response.set_content(nlohmann::json{{"error", message}}.dump(), "application/json");
}

void forbidden(httplib::Response& response, const std::string& message) {
  response.status = 403;
  response.set_content(nlohmann::json{{"error", message}}.dump(), "application/json");
}

// The host a Host header or an origin's authority names, without its port ("[::1]:8080" ->
// "::1").
std::string hostOf(std::string authority) {
  if (!authority.empty() && authority.front() == '[') {
    const size_t close = authority.find(']');
    return close == std::string::npos ? authority : authority.substr(1, close - 1);
  }
  return authority.substr(0, authority.find(':'));
}

// Listening sockets that share no port: SO_REUSEADDR (a restart need not wait out TIME_WAIT)
// without the SO_REUSEPORT httplib adds by default, under which a second server on the same
// port would take half the connections.
void exclusivePort(int socket) {
  int yes = 1;
  setsockopt(socket, SOL_SOCKET, SO_REUSEADDR, &yes, sizeof yes);
}

// The handler of a path asked with a method it does not take.
httplib::Server::Handler methodNotAllowed(const std::string& allowed) {
  return [allowed](const httplib::Request& request, httplib::Response& response) {
    response.status = 405;
    response.set_header("Allow", allowed);
    response.set_content(
        nlohmann::json{{"error", request.method + " " + request.path + ": expected " + allowed}}
            .dump(),
        "application/json");
  };
}

// An origin as a browser sends it: http or https, a host, an optional port, nothing after.
bool isOrigin(const std::string& origin) {
  static const std::regex form(R"(https?://([A-Za-z0-9.-]+|\[[0-9A-Fa-f:.]+\])(:[0-9]{1,5})?)");
  return std::regex_match(origin, form);
}

// A query parameter's number, or InputError naming it ("request ?t").
double numberParam(const std::string& name, const std::string& text) {
  double value = 0.0;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (ec != std::errc() || end != text.data() + text.size() || !std::isfinite(value))
    throw InputError("request ?" + name, fmt::format("'{}' is not a finite number", text));
  return value;
}

// ?t=SECONDS, 0 when absent.
double secondsParam(const httplib::Request& request) {
  return request.has_param("t") ? numberParam("t", request.get_param_value("t")) : 0.0;
}

// ?NAME=x,y,z: three finite numbers within the scene's coordinate range.
Vec3 tripleParam(const httplib::Request& request, const std::string& name) {
  if (!request.has_param(name))
    throw InputError("request ?" + name, "expected three numbers x,y,z");
  const std::string text = request.get_param_value(name);
  Vec3 v(0.0f);
  size_t start = 0;
  for (int i = 0; i < 3; ++i) {
    const size_t comma = i < 2 ? text.find(',', start) : text.size();
    if (comma == std::string::npos)
      throw InputError("request ?" + name, fmt::format("'{}': expected x,y,z", text));
    const double value = numberParam(name, text.substr(start, comma - start));
    if (std::abs(value) > kMaxSceneCoordinate)
      throw InputError("request ?" + name,
                       fmt::format("{:g} is beyond {:g} scene units", value, kMaxSceneCoordinate));
    v[i] = float(value);
    start = comma + 1;
  }
  return v;
}

// /api/sensor's point: ?position=x,y,z&normal=x,y,z, the normal made unit.
SensorPoint sensorParam(const httplib::Request& request) {
  const SensorPoint point{tripleParam(request, "position"), tripleParam(request, "normal")};
  const float length = glm::length(point.normal);
  if (!(length > 0.0f) || !std::isfinite(length))
    throw InputError("request ?normal", "expected a non-zero vector");
  return {point.position, point.normal / length};
}

void binary(httplib::Response& response, const std::string& bytes) {
  response.set_content(bytes, "application/octet-stream");
}

}  // namespace

ViewerServer::ViewerServer(ViewerSession& session, const std::filesystem::path& webRoot)
    : ViewerServer(webRoot) {
  serve(session);
}

void ViewerServer::serve(ViewerSession& session) {
  session_.store(&session);
  progress_.store(1.0);
}

void ViewerServer::setProgress(double fraction) {
  progress_.store(fraction);
}

// Calls f(session), or answers 503 with the solve's progress while there is none yet.
template <class F>
void ViewerServer::withSession(httplib::Response& response, F&& f) const {
  ViewerSession* session = session_.load();
  if (session) return f(*session);
  response.status = 503;
  response.set_content(nlohmann::json{{"error", "solving"}, {"progress", progress_.load()}}.dump(),
                       "application/json");
}

ViewerServer::ViewerServer(const std::filesystem::path& webRoot)
    : http_(std::make_unique<BoundedHttpServer>(HttpLimits{.maxBodyBytes = kMaxBody})) {
  httplib::Server& http = *http_;
  http.set_socket_options(exclusivePort);
  http.set_pre_routing_handler(
      [this](const httplib::Request& request, httplib::Response& response) {
        // The path as decoded: a NUL ends it for the file system, so "/index.html%00.js" would
        // serve index.html typed by its ".js" (and no file's name holds a control character).
        if (std::any_of(request.path.begin(), request.path.end(),
                        [](char c) { return static_cast<unsigned char>(c) < 0x20 || c == 0x7f; })) {
          badRequest(response, "the path holds a control character (a NUL or below a space)");
          return httplib::Server::HandlerResponse::Handled;
        }
        const std::string why = refusal(request);
        if (why.empty()) return httplib::Server::HandlerResponse::Unhandled;
        forbidden(response, why);
        return httplib::Server::HandlerResponse::Handled;
      });
  http.set_post_routing_handler(
      [this](const httplib::Request& request, httplib::Response& response) {
        addCorsHeaders(request, response);
      });
  // A preflight the allowed origin's page sends before its JSON POST (refusal() turns away any
  // other): what the API takes, for 10 minutes.
  http.Options(R"(/api/.*)", [](const httplib::Request&, httplib::Response& response) {
    response.status = 204;
    response.set_header("Access-Control-Allow-Methods", "GET, POST");
    response.set_header("Access-Control-Allow-Headers", "Content-Type");
    response.set_header("Access-Control-Max-Age", "600");
  });
  http.Get("/api/progress", [this](const httplib::Request&, httplib::Response& response) {
    response.set_content(
        nlohmann::json{{"ready", session_.load() != nullptr}, {"progress", progress_.load()}}
            .dump(),
        "application/json");
  });
  http.Get("/api/scene", [this](const httplib::Request&, httplib::Response& response) {
    withSession(response, [&](ViewerSession& session) {
      response.set_content(session.summary().dump(), "application/json");
    });
  });
  http.Get("/api/mesh.glb", [this](const httplib::Request&, httplib::Response& response) {
    withSession(response, [&](ViewerSession& session) {
      response.set_content(session.meshGlb(), "model/gltf-binary");
    });
  });
  http.Get("/api/colors", [this](const httplib::Request&, httplib::Response& response) {
    withSession(response, [&](ViewerSession& session) { binary(response, session.colors()); });
  });
  http.Get("/api/irradiance", [this](const httplib::Request&, httplib::Response& response) {
    withSession(response, [&](ViewerSession& session) { binary(response, session.irradiance()); });
  });
  http.Get("/api/objects.csv", [this](const httplib::Request&, httplib::Response& response) {
    withSession(response, [&](ViewerSession& session) {
      response.set_content(session.objectsCsv(), "text/csv");
    });
  });
  // A GET the session answers with JSON from the request's parameters; a bad one is a 400.
  const auto getJson = [&](const char* path, auto answer) {
    http.Get(path, [this, answer](const httplib::Request& request, httplib::Response& response) {
      withSession(response, [&](ViewerSession& session) {
        try {
          response.set_content(answer(session, request).dump(), "application/json");
        } catch (const InputError& e) {
          badRequest(response, e.what());
        }
      });
    });
  };
  // ?t=SECONDS (0 when absent): the dynamic objects there, lit by probes, and the sensors read
  // with the objects there.
  getJson("/api/dynamic", [](const ViewerSession& session, const httplib::Request& request) {
    return session.objectsAt(secondsParam(request));
  });
  getJson("/api/sensors", [](const ViewerSession& session, const httplib::Request& request) {
    return session.sensorSets(secondsParam(request));
  });
  getJson("/api/sensor", [](const ViewerSession& session, const httplib::Request& request) {
    return session.sensorAt(sensorParam(request), secondsParam(request));
  });
  http.Post("/api/lights", [this](const httplib::Request& request, httplib::Response& response) {
    withSession(response, [&](ViewerSession& session) {
      try {
        double ms = 0.0;
        binary(response, session.applyLights(lightRequestJson(request.body), &ms));
        response.set_header("X-Relight-Ms", fmt::format("{:.3f}", ms));
      } catch (const InputError& e) {
        badRequest(response, e.what());
      }
    });
  });
  // A known path asked with another method: 405 naming the one it takes.
  for (const char* path :
       {"/api/progress", "/api/scene", "/api/mesh.glb", "/api/colors", "/api/irradiance",
        "/api/objects.csv", "/api/dynamic", "/api/sensor", "/api/sensors"}) {
    http.Post(path, methodNotAllowed("GET"));
    http.Put(path, methodNotAllowed("GET"));
    http.Delete(path, methodNotAllowed("GET"));
  }
  http.Get("/api/lights", methodNotAllowed("POST"));
  http.Put("/api/lights", methodNotAllowed("POST"));
  http.Delete("/api/lights", methodNotAllowed("POST"));
  std::error_code ec;
  if (std::filesystem::is_directory(webRoot, ec)) http.set_mount_point("/", webRoot.string());
  http.set_exception_handler(
      [](const httplib::Request&, httplib::Response& response, std::exception_ptr error) {
        response.status = 500;
        try {
          std::rethrow_exception(error);
        } catch (const std::exception& e) {
          response.set_content(nlohmann::json{{"error", e.what()}}.dump(), "application/json");
        } catch (...) {
          response.set_content(R"({"error": "unknown"})", "application/json");
        }
      });
}

ViewerServer::~ViewerServer() = default;

void ViewerServer::allowOrigin(const std::string& origin) {
  if (!isOrigin(origin))
    throw InputError("--allow-origin " + origin,
                     "expected an origin as a browser sends it: http:// or https://, a host and "
                     "an optional port, nothing after (e.g. http://localhost:5173)");
  allowedOrigin_ = origin;
}

void ViewerServer::addCorsHeaders(const httplib::Request& request,
                                  httplib::Response& response) const {
  if (allowedOrigin_.empty()) return;
  response.set_header("Vary", "Origin");  // a cache must not give one origin's answer to another
  if (request.get_header_value("Origin") != allowedOrigin_) return;
  response.set_header("Access-Control-Allow-Origin", allowedOrigin_);
  response.set_header("Access-Control-Expose-Headers", "X-Relight-Ms");
}

std::string ViewerServer::refusal(const httplib::Request& request) const {
  const std::string host = request.get_header_value("Host");
  const std::string name = hostOf(host);
  if (name != "localhost" && name != "127.0.0.1" && name != "::1" && name != host_)
    return fmt::format("Host '{}' is not this server (expected localhost, 127.0.0.1, [::1]{})",
                       host, host_.empty() ? "" : " or " + host_);
  if (request.method == "GET" || request.method == "HEAD") return "";
  const std::string origin = request.get_header_value("Origin");
  const bool allowed = !allowedOrigin_.empty() && origin == allowedOrigin_;
  const std::string others = allowedOrigin_.empty()
                                 ? "no other page drives this server (serve --allow-origin ORIGIN)"
                                 : "only this server's own page and " + allowedOrigin_ + " do";
  if (request.method == "OPTIONS")
    return allowed ? "" : fmt::format("a preflight from origin '{}': {}", origin, others);
  if (request.has_header("Origin") && origin != "http://" + host && !allowed)
    return fmt::format("a request from origin '{}': {}", origin, others);
  const std::string type = request.get_header_value("Content-Type");
  if (type.substr(0, type.find(';')) != "application/json")
    return fmt::format("Content-Type '{}': expected application/json", type);
  return "";
}

int ViewerServer::bind(const std::string& host, int port) {
  host_ = host;
  const int bound = port == 0                         ? http_->bind_to_any_port(host)
                    : http_->bind_to_port(host, port) ? port
                                                      : -1;
  if (bound < 0)
    throw InputError(fmt::format("--host {} --port {}", host, port),
                     "cannot listen there: the port is taken (another server holds it) or the "
                     "address is not this machine's");
  http_->widenBacklog();
  return bound;
}

void ViewerServer::run() {
  http_->listen_after_bind();
}

void ViewerServer::waitUntilRunning() const {
  while (!http_->is_running()) std::this_thread::sleep_for(std::chrono::milliseconds(1));
}

void ViewerServer::stop() {
  http_->stop();
}

}  // namespace rad
