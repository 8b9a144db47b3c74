// The viewer's API over HTTP: the scene, mesh and colours it serves; a light move answered with
// the colours the library's relighter gives for the same lights; bad requests refused with 400
// and nothing changed; no file served from outside the page's folder.
#include <fmt/format.h>
#include <gtest/gtest.h>
#include <httplib.h>
#include <netinet/in.h>
#include <radiosity/baked_mesh.h>
#include <radiosity/error.h>
#include <radiosity/gltf_export.h>
#include <radiosity/radiosity_engine.h>
#include <radiosity/relighter.h>
#include <radiosity/scene_builder.h>
#include <radiosity/scene_loader.h>
#include <radiosity/viewer_server.h>
#include <radiosity/viewer_session.h>
#include <radiosity/voxel_radiosity.h>
#include <sys/socket.h>
#include <sys/wait.h>
#include <unistd.h>

#include <atomic>
#include <cmath>
#include <csignal>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <thread>

#include "cli/cli_run.h"
#include "scene/builtin/builtin_shapes.h"

namespace rad {
namespace {

namespace fs = std::filesystem;

PatchRadiositySettings smallSettings() {
  PatchRadiositySettings s;
  s.targetPatches = 600;
  s.formFactorRays = 64;
  return s;
}

constexpr float kDisplayEdge = 60.0f;

// The session `radiosity serve --method patch` makes at smallSettings(): the engine's relighting.
std::unique_ptr<ViewerSession> patchSession(const Scene& scene) {
  MethodSettings settings;
  settings.method = "patch";
  settings.section<PatchRadiositySettings>() = smallSettings();
  auto engine = std::make_unique<const RadiosityEngine>(scene, settings);
  std::unique_ptr<Relighting> relighting = engine->startRelighting(scene.lights, "", {});
  return std::make_unique<ViewerSession>(std::move(engine), scene.lights, std::move(relighting),
                                         kDisplayEdge);
}

// cornell-spot with a 100 mm box that moves 250 mm along x in 2 s on the floor.
Scene cornellSpotWithAMovingBox() {
  Scene scene = loadScene("cornell-spot");
  SceneBuilder b("box");
  addBox(b, Vec3(-50.0f, 0.0f, -50.0f), Vec3(50.0f, 100.0f, 50.0f),
         b.addMaterial({"white", Color(0.8f), Color(0.0f), false}), b.addObject("box"),
         BoxSide::Outside);
  scene.dynamicObjects.push_back({"box",
                                  std::make_shared<const Scene>(b.build()),
                                  std::nullopt,
                                  {{0.0, Vec3(150.0f, 0.0f, 250.0f), std::nullopt},
                                   {2.0, Vec3(400.0f, 0.0f, 250.0f), std::nullopt}}});
  return scene;
}

// A server on a free port of 127.0.0.1 over a session of cornell-spot, in a thread of its own.
class ViewerServerTest : public ::testing::Test {
 protected:
  void SetUp() override {
    web_ = fs::path(::testing::TempDir()) / "viewer_web";
    fs::create_directories(web_);
    std::ofstream(web_ / "index.html") << "<!doctype html><title>viewer</title>";
    session_ = patchSession(scene_);
    server_ = std::make_unique<ViewerServer>(*session_, web_);
    port_ = server_->bind("127.0.0.1", 0);
    thread_ = std::thread([this] { server_->run(); });
    server_->waitUntilRunning();  // a stop() before run() listens would not end it
    client_ = std::make_unique<httplib::Client>("127.0.0.1", port_);
  }
  void TearDown() override {
    server_->stop();
    thread_.join();
  }

  // The colours a relighter of our own gives on the same display mesh, in the .glb's vertex
  // order, after a relight to `lights` (none: as it starts): what the server must answer.
  std::string expectedColors(const std::vector<Light>* lights) const {
    Relighter relighter(model_, scene_.lights);
    if (lights) relighter.relight(*lights);
    SurfaceBake bake = cutSurfaces(scene_, kDisplayEdge);
    shadeSurfaces(bake, relighter.solution());
    std::string bytes;
    for (uint32_t v : glbVertexOrder(bake.mesh))
      bytes.append(reinterpret_cast<const char*>(&bake.mesh.colors[v]), 3 * sizeof(float));
    return bytes;
  }

  httplib::Result post(const std::string& body) {
    return client_->Post("/api/lights", body, "application/json");
  }

  const Scene scene_ = cornellSpotWithAMovingBox();
  const PatchModel model_{scene_, smallSettings()};
  fs::path web_;
  std::unique_ptr<ViewerSession> session_;
  std::unique_ptr<ViewerServer> server_;
  int port_ = 0;
  std::thread thread_;
  std::unique_ptr<httplib::Client> client_;
};

TEST_F(ViewerServerTest, ServesTheSceneMeshAndColours) {
  const auto scene = client_->Get("/api/scene");
  ASSERT_TRUE(scene);
  ASSERT_EQ(scene->status, 200);
  const nlohmann::json j = nlohmann::json::parse(scene->body);
  EXPECT_EQ(j["scene"], "cornell-spot");
  // The page's false colours: square millimetres to square metres, lux at 179 lm/W.
  EXPECT_EQ(j["unit"]["name"], "mm");
  EXPECT_DOUBLE_EQ(j["unit"]["metres"].get<double>(), 0.001);
  EXPECT_DOUBLE_EQ(j["lumens_per_watt"].get<double>(), 179.0);
  ASSERT_EQ(j["lights"].size(), 1u);
  EXPECT_EQ(j["lights"][0]["type"], "spot");
  const auto mesh = client_->Get("/api/mesh.glb");
  ASSERT_TRUE(mesh);
  EXPECT_EQ(mesh->body.substr(0, 4), "glTF");
  const auto colors = client_->Get("/api/colors");
  ASSERT_TRUE(colors);
  EXPECT_EQ(colors->body.size(), 12 * j["vertices"].get<size_t>());
  EXPECT_TRUE(colors->body == expectedColors(nullptr));  // (no dump of binary bodies)
  // The irradiance per vertex is the H the colours were made of: L = rho H / pi off the lamp.
  const auto irradiance = client_->Get("/api/irradiance");
  ASSERT_TRUE(irradiance);
  ASSERT_EQ(irradiance->body.size(), colors->body.size());
  const SurfaceBake bake = cutSurfaces(scene_, kDisplayEdge);
  const std::vector<uint32_t> order = glbVertexOrder(bake.mesh);
  const float* l = reinterpret_cast<const float*>(colors->body.data());
  const float* h = reinterpret_cast<const float*>(irradiance->body.data());
  size_t checked = 0;
  for (size_t k = 0; k < order.size(); ++k) {
    const Material& m = scene_.materialOf(bake.at[order[k]].triangle);
    if (m.emits() || !bake.at[order[k]].frontFace) continue;
    for (int c = 0; c < 3; ++c)
      EXPECT_NEAR(l[3 * k + size_t(c)], m.rho[c] * h[3 * k + size_t(c)] / 3.14159265f,
                  1e-5f + 1e-5f * l[3 * k + size_t(c)]);
    ++checked;
  }
  EXPECT_GT(checked, order.size() / 2);
  const auto objects = client_->Get("/api/objects.csv");
  ASSERT_TRUE(objects);
  EXPECT_EQ(objects->body.rfind("object,area,H_r,H_g,H_b,B_r,B_g,B_b\n", 0), 0u);
  EXPECT_NE(objects->body.find("\nfloor,"), std::string::npos);
}

TEST_F(ViewerServerTest, ALightMoveAnswersTheRelightersColours) {
  std::vector<Light> lights = scene_.lights;
  lights[0].direction = glm::normalize(Vec3(0.4f, -1.0f, 0.0f));
  lights[0].position.x += 30.0f;
  const nlohmann::json body = {
      {"lights",
       {{{"id", 0},
         {"position", {lights[0].position.x, lights[0].position.y, lights[0].position.z}},
         {"direction", {0.4, -1.0, 0.0}}}}}};
  const auto moved = post(body.dump());
  ASSERT_TRUE(moved);
  ASSERT_EQ(moved->status, 200) << moved->body;
  EXPECT_TRUE(moved->has_header("X-Relight-Ms"));
  EXPECT_TRUE(moved->body == expectedColors(&lights));
  EXPECT_FALSE(moved->body == expectedColors(nullptr));  // the beam moved
  // A dimmer on the spot's group: the colours the relighter gives at that intensity.
  const auto dimmed = post(R"({"groups": {"light0": 0.5}})");
  ASSERT_TRUE(dimmed);
  ASSERT_EQ(dimmed->status, 200) << dimmed->body;
  lights[0].intensity *= 0.5f;
  // The server relit twice, our relighter once: equal within the relighter's tolerance.
  const std::string expected = expectedColors(&lights);
  ASSERT_EQ(dimmed->body.size(), expected.size());
  const float* got = reinterpret_cast<const float*>(dimmed->body.data());
  const float* want = reinterpret_cast<const float*>(expected.data());
  double worst = 0.0, mean = 0.0;
  for (size_t k = 0; k < expected.size() / 4; ++k) {
    worst = std::max(worst, double(std::abs(got[k] - want[k])));
    mean += want[k] / double(expected.size() / 4);
  }
  EXPECT_LE(worst, 0.01 * mean);
}

TEST_F(ViewerServerTest, BadRequestsAre400AndChangeNothing) {
  const auto before = client_->Get("/api/scene")->body;
  const auto colorsBefore = client_->Get("/api/colors")->body;
  for (const std::string bad :
       {"not json", "[]", R"({"lihgts": []})", R"({"lights": [{"id": 3}]})",
        R"({"lights": [{"id": 0, "position": [1, 2]}]})",
        R"({"lights": [{"id": 0, "direction": [0, 0, 0]}]})",
        R"({"lights": [{"id": 0, "intensity": [-1, 0, 0]}]})",
        R"({"lights": [{"id": 0, "position": [1e30, 0, 0]}]})",  // beyond kMaxSceneCoordinate
        "[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[["
        "[[[]]",
        R"({"lights": [{"id": 0, "position": [1, 2, 3]}, {"id": 0, "colour": 1}]})",
        R"({"groups": {"nope": 1}})", R"({"groups": {"light0": "dim"}})"}) {
    const auto r = post(bad);
    ASSERT_TRUE(r) << bad;
    EXPECT_EQ(r->status, 400) << bad;
    EXPECT_NE(nlohmann::json::parse(r->body)["error"].get<std::string>(), "") << bad;
  }
  // A body beyond 1 MiB is refused by its Content-Length, before it is read.
  const auto big = post(std::string(ViewerServer::kMaxBody + 1, ' '));
  ASSERT_TRUE(big);
  EXPECT_EQ(big->status, 413);
  EXPECT_NE(nlohmann::json::parse(big->body)["error"].get<std::string>().find("1048576"),
            std::string::npos);
  EXPECT_EQ(client_->Get("/api/scene")->body, before);
  EXPECT_TRUE(client_->Get("/api/colors")->body == colorsBefore);
}

// A request cannot poison the session: an intensity times its group's scale beyond what a scene
// may hold (kMaxLight) is refused as a whole, and the relights after it stay finite.
TEST_F(ViewerServerTest, LightBeyondWhatASceneMayHoldIsRefused) {
  const std::string colorsBefore = client_->Get("/api/colors")->body;
  for (const std::string bad :
       {R"({"lights": [{"id": 0, "intensity": [3e38, 3e38, 3e38]}], "groups": {"light0": 10}})",
        R"({"lights": [{"id": 0, "intensity": [1e19, 0, 0]}]})",
        R"({"lights": [{"id": 0, "intensity": [1e17, 1e17, 1e17]}], "groups": {"light0": 100}})",
        R"({"groups": {"light0": 3e38}})", R"({"groups": {"light0": 1e300}})"}) {
    const auto r = post(bad);
    ASSERT_TRUE(r) << bad;
    EXPECT_EQ(r->status, 400) << bad << " " << r->body;
  }
  EXPECT_TRUE(client_->Get("/api/colors")->body == colorsBefore);
  const auto normal = post(R"({"lights": [{"id": 0, "intensity": [1e5, 1e5, 1e5]}]})");
  ASSERT_TRUE(normal);
  ASSERT_EQ(normal->status, 200) << normal->body;
  const float* c = reinterpret_cast<const float*>(normal->body.data());
  for (size_t k = 0; k < normal->body.size() / 4; ++k)
    ASSERT_TRUE(std::isfinite(c[k]) && c[k] >= 0.0f) << k << " " << c[k];
}

// A direction's length is not what it is read by: [1e20, 0, 0] is the +x axis (its length
// overflows a float).
TEST_F(ViewerServerTest, AHugeDirectionIsItsAxis) {
  const auto r = post(R"({"lights": [{"id": 0, "direction": [1e20, 0, 0]}]})");
  ASSERT_TRUE(r);
  ASSERT_EQ(r->status, 200) << r->body;
  const nlohmann::json light = nlohmann::json::parse(client_->Get("/api/scene")->body)["lights"][0];
  EXPECT_EQ(light["direction"], nlohmann::json::array({1.0, 0.0, 0.0}));
}

// Only this server's own page and command-line clients drive it: another Host (DNS
// rebinding), a cross-site "simple" request (text/plain, another Origin) or a POST that is not
// JSON gets 403 and changes nothing; reading from a command-line client needs no Origin.
TEST_F(ViewerServerTest, RequestsFromOtherSitesAre403) {
  const std::string colorsBefore = client_->Get("/api/colors")->body;
  const std::string move = R"({"lights": [{"id": 0, "position": [100, 400, 100]}]})";
  const auto rebound = client_->Get("/api/scene", {{"Host", "evil.example"}});
  ASSERT_TRUE(rebound);
  EXPECT_EQ(rebound->status, 403);
  const auto simple =
      client_->Post("/api/lights", {{"Origin", "http://evil.example"}}, move, "text/plain");
  ASSERT_TRUE(simple);
  EXPECT_EQ(simple->status, 403);
  const auto crossOrigin =
      client_->Post("/api/lights", {{"Origin", "http://evil.example"}}, move, "application/json");
  ASSERT_TRUE(crossOrigin);
  EXPECT_EQ(crossOrigin->status, 403);
  const auto plain = client_->Post("/api/lights", move, "text/plain");
  ASSERT_TRUE(plain);
  EXPECT_EQ(plain->status, 403);
  EXPECT_FALSE(simple->has_header("Access-Control-Allow-Origin"));
  EXPECT_TRUE(client_->Get("/api/colors")->body == colorsBefore);
  // The page itself: same origin, JSON.
  const std::string self = "http://127.0.0.1:" + std::to_string(port_);
  const auto own = client_->Post("/api/lights", {{"Origin", self}}, move, "application/json");
  ASSERT_TRUE(own);
  EXPECT_EQ(own->status, 200) << own->body;
}

// Without --allow-origin no CORS header is sent, whatever the Origin, and a preflight is 403.
TEST_F(ViewerServerTest, NoCorsHeadersUnlessAnOriginIsAllowed) {
  const auto read = client_->Get("/api/scene", {{"Origin", "http://localhost:5173"}});
  ASSERT_TRUE(read);
  EXPECT_EQ(read->status, 200);
  EXPECT_FALSE(read->has_header("Access-Control-Allow-Origin"));
  EXPECT_FALSE(read->has_header("Vary"));
  const auto preflight = client_->Options(
      "/api/lights",
      {{"Origin", "http://localhost:5173"}, {"Access-Control-Request-Method", "POST"}});
  ASSERT_TRUE(preflight);
  EXPECT_EQ(preflight->status, 403);
  EXPECT_FALSE(preflight->has_header("Access-Control-Allow-Origin"));
  EXPECT_NE(preflight->body.find("--allow-origin"), std::string::npos) << preflight->body;
}

// serve --allow-origin: the page of that origin drives the server as its own page does, with
// CORS headers; its preflight names what the API takes; any other origin is still refused, with
// no CORS header.
TEST_F(ViewerServerTest, TheAllowedOriginGetsCorsHeaders) {
  const std::string page = "http://localhost:5173";
  server_->allowOrigin(page);
  const auto preflight =
      client_->Options("/api/lights", {{"Origin", page},
                                       {"Access-Control-Request-Method", "POST"},
                                       {"Access-Control-Request-Headers", "content-type"}});
  ASSERT_TRUE(preflight);
  EXPECT_EQ(preflight->status, 204);
  EXPECT_EQ(preflight->get_header_value("Access-Control-Allow-Origin"), page);
  EXPECT_EQ(preflight->get_header_value("Access-Control-Allow-Methods"), "GET, POST");
  EXPECT_EQ(preflight->get_header_value("Access-Control-Allow-Headers"), "Content-Type");
  const std::string move = R"({"lights": [{"id": 0, "position": [100, 400, 100]}]})";
  const auto moved = client_->Post("/api/lights", {{"Origin", page}}, move, "application/json");
  ASSERT_TRUE(moved);
  EXPECT_EQ(moved->status, 200) << moved->body;
  EXPECT_EQ(moved->get_header_value("Access-Control-Allow-Origin"), page);
  EXPECT_EQ(moved->get_header_value("Vary"), "Origin");
  EXPECT_EQ(moved->get_header_value("Access-Control-Expose-Headers"), "X-Relight-Ms");
  const auto read = client_->Get("/api/scene", {{"Origin", page}});
  ASSERT_TRUE(read);
  EXPECT_EQ(read->get_header_value("Access-Control-Allow-Origin"), page);
  // Another origin, and the allowed one's look-alikes: refused, no CORS header.
  const std::string colors = client_->Get("/api/colors")->body;
  for (const std::string other : {"http://evil.example", "http://localhost:5174",
                                  "https://localhost:5173", "http://localhost:5173.evil.example"}) {
    const auto r = client_->Post("/api/lights", {{"Origin", other}},
                                 R"({"groups": {"light0": 0.5}})", "application/json");
    ASSERT_TRUE(r) << other;
    EXPECT_EQ(r->status, 403) << other;
    EXPECT_FALSE(r->has_header("Access-Control-Allow-Origin")) << other;
    const auto p = client_->Options("/api/lights", {{"Origin", other}});
    ASSERT_TRUE(p) << other;
    EXPECT_EQ(p->status, 403) << other;
    EXPECT_FALSE(p->has_header("Access-Control-Allow-Origin")) << other;
  }
  EXPECT_TRUE(client_->Get("/api/colors")->body == colors);
}

TEST(ViewerServer, AnAllowedOriginIsAnOriginAlone) {
  ViewerServer server(fs::path(::testing::TempDir()) / "no_page_here");
  for (const std::string bad : {"", "*", "localhost:5173", "http://localhost:5173/",
                                "http://localhost:5173/page", "null", "ftp://example.org"})
    EXPECT_THROW(server.allowOrigin(bad), InputError) << bad;
  for (const std::string good : {"http://localhost:5173", "https://example.org", "http://[::1]:80"})
    EXPECT_NO_THROW(server.allowOrigin(good)) << good;
  // The command refuses it before listening, as bad input: exit 2.
  const test::CliResult r = test::run({"serve", "cornell-spot", "--allow-origin", "*"});
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.err.find("--allow-origin"), std::string::npos) << r.err;
}

// A known path asked with a method it does not take is 405 with Allow; a body with a NUL byte
// (JSON, then a NUL and junk) is refused whole.
TEST_F(ViewerServerTest, WrongMethodsAre405AndNulBytes400) {
  const auto get = client_->Get("/api/lights");
  ASSERT_TRUE(get);
  EXPECT_EQ(get->status, 405);
  EXPECT_EQ(get->get_header_value("Allow"), "POST");
  const auto post = client_->Post("/api/colors", "{}", "application/json");
  ASSERT_TRUE(post);
  EXPECT_EQ(post->status, 405);
  EXPECT_EQ(post->get_header_value("Allow"), "GET");
  const std::string colorsBefore = client_->Get("/api/colors")->body;
  const auto nul =
      client_->Post("/api/lights", std::string(R"({"groups": {"light0": 0.5}})") + '\0' + "junk",
                    "application/json");
  ASSERT_TRUE(nul);
  EXPECT_EQ(nul->status, 400);
  EXPECT_TRUE(client_->Get("/api/colors")->body == colorsBefore);
}

// A client's own socket to the server: what it sends, as it sends it.
class RawConnection {
 public:
  explicit RawConnection(int port) : socket_(::socket(AF_INET, SOCK_STREAM, 0)) {
    sockaddr_in address{};
    address.sin_family = AF_INET;
    address.sin_port = htons(uint16_t(port));
    address.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    connected_ = ::connect(socket_, reinterpret_cast<sockaddr*>(&address), sizeof address) == 0;
    timeval wait{5, 0};
    ::setsockopt(socket_, SOL_SOCKET, SO_RCVTIMEO, &wait, sizeof wait);
  }
  ~RawConnection() { ::close(socket_); }
  RawConnection(const RawConnection&) = delete;
  RawConnection& operator=(const RawConnection&) = delete;
  bool connected() const { return connected_; }
  /// False once the server has closed the connection (or reset it).
  bool send(const std::string& bytes) {
    return ::send(socket_, bytes.data(), bytes.size(), MSG_NOSIGNAL) == ssize_t(bytes.size());
  }
  /// What the server answers until it closes the connection (or 5 s pass).
  std::string answer() {
    std::string text;
    char buffer[4096];
    for (ssize_t n; (n = ::recv(socket_, buffer, sizeof buffer, 0)) > 0;)
      text.append(buffer, size_t(n));
    return text;
  }

 private:
  int socket_;
  bool connected_ = false;
};

// The resident memory of this process (the server runs in it), bytes.
size_t residentBytes() {
  std::ifstream statm("/proc/self/statm");
  size_t pages = 0, resident = 0;
  statm >> pages >> resident;
  return resident * size_t(::sysconf(_SC_PAGESIZE));
}

// Slow clients hold no worker: with 16 connections sending a request a byte every 50 ms, 8
// connected and silent, and 100 more idle ones than the server keeps (the oldest closed for the
// newest), a plain GET is answered at once. Before (a worker per connection, 8 workers), 12
// dribbling clients kept a GET waiting 25 s and 8 silent ones delayed it 4.7 s.
TEST_F(ViewerServerTest, SlowClientsDoNotStarveAGet) {
  const auto tc = std::chrono::steady_clock::now();
  std::vector<std::unique_ptr<RawConnection>> silent, dribbling;
  for (int k = 0; k < 108; ++k) silent.push_back(std::make_unique<RawConnection>(port_));
  for (int k = 0; k < 16; ++k) dribbling.push_back(std::make_unique<RawConnection>(port_));
  // Connected at once: the kernel keeps more than httplib's 5 waiting to be accepted.
  EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - tc).count(), 0.5);
  std::atomic<bool> done = false;
  std::thread dribble([&] {
    const std::string request = "GET /api/scene HTTP/1.1\r\nHost: 127.0.0.1\r\nX-Slow: ";
    for (size_t at = 0; !done; at = (at + 1) % request.size()) {
      for (auto& c : dribbling) c->send(request.substr(std::min(at, request.size() - 1), 1));
      std::this_thread::sleep_for(std::chrono::milliseconds(50));
    }
  });
  std::this_thread::sleep_for(std::chrono::milliseconds(300));
  for (int k = 0; k < 5; ++k) {
    const auto start = std::chrono::steady_clock::now();
    const auto scene = client_->Get("/api/scene");
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    ASSERT_TRUE(scene);
    EXPECT_EQ(scene->status, 200);
    EXPECT_LT(seconds, 1.0) << "GET " << k;
  }
  done = true;
  dribble.join();
}

// A request's head is bounded: more than 100 headers or 32 KiB is a 431 and the connection is
// closed; 400,000 headers are not read into memory (before: all of them, +44 MB).
TEST_F(ViewerServerTest, TooManyOrTooLargeHeadersAre431) {
  const std::string start = "GET /api/scene HTTP/1.1\r\nHost: 127.0.0.1\r\n";
  std::string many = start;
  for (int k = 0; k < 101; ++k) many += fmt::format("X-{}: {}\r\n", k, k);
  for (const std::string& head :
       {many + "\r\n", start + "X-Large: " + std::string(40000, 'a') + "\r\n\r\n"}) {
    RawConnection c(port_);
    ASSERT_TRUE(c.connected());
    c.send(head);
    const std::string answer = c.answer();
    EXPECT_EQ(answer.rfind("HTTP/1.1 431 ", 0), 0u) << answer.substr(0, 200);
  }
  // Host, 98 more and Connection: 100 headers pass; one more does not.
  std::string hundred = start;
  for (int k = 0; k < 98; ++k) hundred += fmt::format("X-{}: {}\r\n", k, k);
  hundred += "Connection: close\r\n";
  RawConnection passes(port_);
  passes.send(hundred + "\r\n");
  EXPECT_EQ(passes.answer().rfind("HTTP/1.1 200 ", 0), 0u);
  RawConnection refused(port_);
  refused.send(hundred + "X-One-More: 1\r\n\r\n");
  EXPECT_EQ(refused.answer().rfind("HTTP/1.1 431 ", 0), 0u);
  // 400,000 headers in 4 MiB pieces: refused after the first 32 KiB, the rest never kept.
  const size_t before = residentBytes();
  RawConnection flood(port_);
  flood.send(start);
  std::string piece;
  while (piece.size() < (4 << 20)) piece += "X-Flood: 1\r\n";
  for (int k = 0; k < 4 && flood.send(piece); ++k) {
  }
  const std::string answer = flood.answer();
  EXPECT_TRUE(answer.empty() || answer.rfind("HTTP/1.1 431 ", 0) == 0) << answer.substr(0, 200);
  EXPECT_LT(residentBytes(), before + (8 << 20));
  EXPECT_EQ(client_->Get("/api/scene")->status, 200);
}

// A port another server listens on is refused, not shared (no SO_REUSEPORT).
TEST_F(ViewerServerTest, ABusyPortIsRefused) {
  ViewerServer second(web_);
  EXPECT_THROW(second.bind("127.0.0.1", port_), InputError);
}

// The moving box as the page asks for it: where its path puts it at each time (held after its
// last keyframe), lit, and a time that is not one refused.
TEST_F(ViewerServerTest, ServesTheDynamicObjectsWhereTheirPathsPutThem) {
  const nlohmann::json summary = nlohmann::json::parse(client_->Get("/api/scene")->body);
  EXPECT_EQ(summary["dynamic_objects"], nlohmann::json::array({"box"}));
  EXPECT_EQ(summary["paths_end_s"], 2.0);
  auto at = [&](const std::string& t) {
    const auto r = client_->Get("/api/dynamic?t=" + t);
    EXPECT_TRUE(r && r->status == 200) << t;
    return nlohmann::json::parse(r->body);
  };
  for (const auto& [t, x] : std::vector<std::pair<std::string, float>>{
           {"0", 150.0f}, {"1", 275.0f}, {"2", 400.0f}, {"5", 400.0f}}) {
    const nlohmann::json answer = at(t);
    ASSERT_EQ(answer["objects"].size(), 1u) << t;
    const auto positions = answer["objects"][0]["positions"].get<std::vector<float>>();
    const auto colors = answer["objects"][0]["colors"].get<std::vector<float>>();
    ASSERT_EQ(positions.size(), 6u * 2 * 9) << t;  // 6 faces, 2 triangles each, 3 vertices
    ASSERT_EQ(colors.size(), positions.size());
    float lo = 1e30f, hi = -1e30f, light = 0.0f;
    for (size_t v = 0; v < positions.size(); v += 3) {
      lo = std::min(lo, positions[v]);
      hi = std::max(hi, positions[v]);
      light += colors[v] + colors[v + 1] + colors[v + 2];
    }
    EXPECT_NEAR(0.5f * (lo + hi), x, 1e-3f) << t;
    EXPECT_GT(light, 0.0f) << t;
  }
  for (const std::string bad : {"soon", "-1", "nan", "1e300", "1x"}) {
    const auto r = client_->Get("/api/dynamic?t=" + bad);
    ASSERT_TRUE(r) << bad;
    EXPECT_EQ(r->status, 400) << bad;
  }
}

// The page's lux at a clicked point is what `solve --sensors` reads there: the engine's sensors of
// the same solution (the relighter's, as ALightMoveAnswersTheRelightersColours shows) with the
// objects placed at the time asked (the box reaches the point at t = 1).
TEST_F(ViewerServerTest, ASensorReadsWhatTheEnginesSensorsRead) {
  MethodSettings settings;
  settings.method = "patch";
  settings.section<PatchRadiositySettings>() = smallSettings();
  const RadiosityEngine engine(scene_, settings);
  const Relighter relighter(model_, scene_.lights);
  const SensorPoint points[] = {{Vec3(275.0f, 0.5f, 250.0f), Vec3(0, 1, 0)}};
  std::vector<double> read;
  for (const char* t : {"0", "1"}) {
    const auto answer =
        client_->Get(std::string("/api/sensor?position=275,0.5,250&normal=0,2,0&t=") + t);
    ASSERT_TRUE(answer);
    ASSERT_EQ(answer->status, 200) << answer->body;
    const nlohmann::json j = nlohmann::json::parse(answer->body);
    EXPECT_EQ(j["normal"], nlohmann::json::array({0.0, 1.0, 0.0}));
    const Color expected =
        engine.sensorIrradiance(relighter.solution(), std::stod(t), points, {})[0];
    ASSERT_GT(expected.g, 0.0f);
    for (int c = 0; c < 3; ++c)
      EXPECT_NEAR(j["irradiance"][size_t(c)].get<double>(), expected[c], 0.01 * expected[c]) << t;
    const double lux = *illuminanceLux(expected, scene_.unit);
    EXPECT_NEAR(j["illuminance_lux"].get<double>(), lux, 0.01 * lux) << t;
    read.push_back(lux);
  }
  EXPECT_LT(read[1], 0.5 * read[0]);  // the box shades it
  // The scene's own sets (it has none; the office's are read in the browser test).
  const auto sets = client_->Get("/api/sensors?t=1");
  ASSERT_TRUE(sets && sets->status == 200);
  EXPECT_EQ(nlohmann::json::parse(sets->body)["sets"], nlohmann::json::object());
  EXPECT_EQ(client_->Get("/api/sensors?t=-1")->status, 400);
  for (const std::string bad :
       {"position=1,2,3", "position=1,2&normal=0,1,0", "position=1,2,3&normal=0,0,0",
        "position=1,x,3&normal=0,1,0", "position=1,2,3e30&normal=0,1,0",
        "position=1,2,3&normal=0,1,0&t=-1"}) {
    const auto r = client_->Get("/api/sensor?" + bad);
    ASSERT_TRUE(r) << bad;
    EXPECT_EQ(r->status, 400) << bad;
    EXPECT_NE(r->body.find("request ?"), std::string::npos) << r->body;
  }
}

TEST_F(ViewerServerTest, ServesThePageButNothingOutsideItsFolder) {
  const auto page = client_->Get("/index.html");
  ASSERT_TRUE(page);
  EXPECT_EQ(page->status, 200);
  std::ofstream(web_.parent_path() / "secret.txt") << "secret";
  for (const std::string path : {"/../secret.txt", "/%2e%2e/secret.txt", "/..%2fsecret.txt"}) {
    const auto r = client_->Get(path);
    ASSERT_TRUE(r) << path;
    EXPECT_NE(r->status, 200) << path;
    EXPECT_EQ(r->body.find("secret"), std::string::npos) << path;
  }
  // A NUL (or another control character) in the decoded path: the file system would read
  // index.html, typed as the ".js" after the NUL says.
  for (const std::string path : {"/index.html%00.js", "/index.html%00", "/index.html%0a.js"}) {
    const auto r = client_->Get(path);
    ASSERT_TRUE(r) << path;
    EXPECT_EQ(r->status, 400) << path;
    EXPECT_EQ(r->body.find("<title>viewer"), std::string::npos) << path;
    EXPECT_NE(r->get_header_value("Content-Type"), "text/javascript") << path;
  }
}

}  // namespace
}  // namespace rad

namespace rad {
namespace {

// `radiosity serve cornell-spot` started by fork and exec, its output into `log`; waits until
// it answers (its URL printed, /api/progress ready) and returns its pid and port.
std::pair<pid_t, int> startServe(const fs::path& log) {
  fs::remove(log);
  const std::string command = std::string(RADIOSITY_BINARY_DIR) +
                              "/radiosity serve cornell-spot --port 0 --patches 300 "
                              "--cache-dir none > " +
                              log.string() + " 2>&1";
  const pid_t pid = ::fork();
  if (pid == 0) {
    ::execl("/bin/sh", "sh", "-c", ("exec " + command).c_str(), nullptr);
    ::_exit(127);
  }
  int port = 0;
  for (int tries = 0; tries < 600 && port == 0; ++tries) {
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
    std::ifstream in(log);
    const std::string text((std::istreambuf_iterator<char>(in)), {});
    const size_t at = text.find("http://127.0.0.1:");
    if (at != std::string::npos) port = std::atoi(text.c_str() + at + 17);
  }
  if (port == 0) return {pid, 0};
  httplib::Client client("127.0.0.1", port);
  // It listens while it solves: the API answers once /api/progress says ready.
  for (int tries = 0; tries < 600; ++tries) {
    const auto progress = client.Get("/api/progress");
    if (progress && nlohmann::json::parse(progress->body)["ready"].get<bool>()) break;
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
  return {pid, port};
}

// The exit status after `signal`, or -1 when it did not exit by itself within 20 s.
int exitStatusAfter(pid_t pid, int signal) {
  ::kill(pid, signal);
  int status = 0;
  for (int tries = 0; tries < 2000; ++tries) {
    if (::waitpid(pid, &status, WNOHANG) == pid)
      return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  ::kill(pid, SIGKILL);
  ::waitpid(pid, &status, 0);
  return -1;
}

// `radiosity serve` itself: it prints where it listens, answers there, and Ctrl-C (SIGINT) stops
// it cleanly (status 0).
TEST(Serve, ListensWhereItSaysAndStopsOnCtrlC) {
  const auto [pid, port] = startServe(fs::path(::testing::TempDir()) / "serve.log");
  ASSERT_GT(pid, 0);
  ASSERT_GT(port, 0) << "no URL printed";
  httplib::Client client("127.0.0.1", port);
  const auto scene = client.Get("/api/scene");
  ASSERT_TRUE(scene);
  EXPECT_EQ(scene->status, 200);
  EXPECT_EQ(exitStatusAfter(pid, SIGINT), 0);
}

// SIGTERM (a service manager's stop) is Ctrl-C: relights in flight when it comes are answered
// whole or not at all (no connection cut mid-answer), and it exits 0 saying it stopped. Before,
// SIGTERM killed it where it stood.
TEST(Serve, SigtermStopsItAsCtrlCDoes) {
  const fs::path log = fs::path(::testing::TempDir()) / "serve_sigterm.log";
  const auto [pid, port] = startServe(log);
  ASSERT_GT(pid, 0);
  ASSERT_GT(port, 0) << "no URL printed";
  const size_t colorBytes = [&] {
    httplib::Client client("127.0.0.1", port);
    const auto colors = client.Get("/api/colors");
    return colors ? colors->body.size() : 0;
  }();
  ASSERT_GT(colorBytes, 0u);
  std::atomic<int> answered = 0, partial = 0;
  std::atomic<bool> stopping = false;
  std::thread relights([&] {
    httplib::Client client("127.0.0.1", port);
    for (int k = 0; !stopping || k < 3; ++k) {
      const std::string body =
          fmt::format(R"({{"lights": [{{"id": 0, "position": [{}, 500, 250]}}]}})", 100 + k % 50);
      const auto r = client.Post("/api/lights", body, "application/json");
      if (!r) break;  // it stopped listening
      if (r->status == 200 && r->body.size() == colorBytes)
        ++answered;
      else
        ++partial;
    }
  });
  std::this_thread::sleep_for(std::chrono::milliseconds(300));
  stopping = true;
  EXPECT_EQ(exitStatusAfter(pid, SIGTERM), 0);
  relights.join();
  EXPECT_GT(answered.load(), 0);
  EXPECT_EQ(partial.load(), 0);
  std::ifstream in(log);
  const std::string text((std::istreambuf_iterator<char>(in)), {});
  EXPECT_NE(text.find("stopped"), std::string::npos) << text;
}

}  // namespace
}  // namespace rad

namespace rad {
namespace {

// The Cornell box's only light is its glowing lamp (group "light"): its dimmer darkens every
// vertex by its scale (all the light is the lamp's), within the relighter's tolerance.
TEST(ViewerSession, DimsAGroupOfGlowingSurfaces) {
  const Scene scene = loadScene("cornell");
  const std::unique_ptr<ViewerSession> held = patchSession(scene);
  ViewerSession& session = *held;
  const std::string before = session.colors();
  const std::string after =
      session.applyLights(nlohmann::json::parse(R"({"groups": {"light": 0.25}})"));
  ASSERT_EQ(before.size(), after.size());
  const float* a = reinterpret_cast<const float*>(before.data());
  const float* b = reinterpret_cast<const float*>(after.data());
  double sumBefore = 0.0, sumAfter = 0.0;
  for (size_t k = 0; k < before.size() / 4; ++k) sumBefore += a[k], sumAfter += b[k];
  EXPECT_NEAR(sumAfter / sumBefore, 0.25, 0.005);
}

// Every light off is no light at all, exactly (not the last state less a change shot to a
// tolerance), and on again the light comes back.
TEST(ViewerSession, EveryLightOffIsNoLight) {
  for (const char* name : {"cornell", "cornell-spot"}) {
    const Scene scene = loadScene(name);
    const std::unique_ptr<ViewerSession> session = patchSession(scene);
    const std::string group = scene.lights.empty() ? "light" : "light0";
    const std::string off =
        session->applyLights(nlohmann::json::parse(R"({"groups": {")" + group + R"(": 0}})"));
    const float* c = reinterpret_cast<const float*>(off.data());
    for (size_t k = 0; k < off.size() / 4; ++k) ASSERT_EQ(c[k], 0.0f) << name << " " << k;
    const std::string on =
        session->applyLights(nlohmann::json::parse(R"({"groups": {")" + group + R"(": 1}})"));
    const float* d = reinterpret_cast<const float*>(on.data());
    double sum = 0.0;
    for (size_t k = 0; k < on.size() / 4; ++k) {
      ASSERT_GE(d[k], 0.0f) << name << " " << k;
      sum += d[k];
    }
    EXPECT_GT(sum, 0.0) << name;
  }
}

}  // namespace
}  // namespace rad

namespace rad {
namespace {

// A voxel solution is shown and its groups dimmed (solved apart), never relit: a light edit is
// refused, and the state stays as it was.
TEST(ViewerSession, AVoxelSolutionDimsItsGroupsButMovesNoLight) {
  const Scene scene = loadScene("cornell");
  MethodSettings settings;
  settings.method = "voxel";
  settings.section<VoxelRadiositySettings>().targetVoxels = 5000;
  settings.section<VoxelRadiositySettings>().sphereRadius = 6;
  settings.section<VoxelRadiositySettings>().iterations = 3;
  settings.lightGroups = true;
  auto engine = std::make_unique<const RadiosityEngine>(scene, settings);
  std::unique_ptr<SurfaceSolution> solution = engine->solve(scene.lights, 0.0);
  ViewerSession session(std::move(engine), scene.lights, std::move(solution), kDisplayEdge);
  EXPECT_EQ(session.summary()["method"], "voxel");
  const std::string before = session.colors();
  EXPECT_THROW(session.applyLights(nlohmann::json::parse(R"({"lights": [{"id": 0}]})")),
               InputError);
  EXPECT_TRUE(session.colors() == before);
  const std::string after =
      session.applyLights(nlohmann::json::parse(R"({"groups": {"light": 0.5}})"));
  const float* a = reinterpret_cast<const float*>(before.data());
  const float* b = reinterpret_cast<const float*>(after.data());
  double sumBefore = 0.0, sumAfter = 0.0;
  for (size_t k = 0; k < before.size() / 4; ++k) sumBefore += a[k], sumAfter += b[k];
  EXPECT_NEAR(sumAfter / sumBefore, 0.5, 1e-3);  // all its light is the lamp's
}

}  // namespace
}  // namespace rad

namespace rad {
namespace {

// Before it has a session (while `serve` solves) the API answers 503 with the progress, and
// /api/progress says how far; then the session's answers.
TEST(ViewerServer, AnswersProgressUntilItHasASession) {
  ViewerServer server(fs::path(::testing::TempDir()) / "no_page_here");
  const int port = server.bind("127.0.0.1", 0);
  std::thread listener([&] { server.run(); });
  server.waitUntilRunning();
  server.setProgress(0.25);
  httplib::Client client("127.0.0.1", port);
  const auto early = client.Get("/api/scene");
  ASSERT_TRUE(early);
  EXPECT_EQ(early->status, 503);
  EXPECT_DOUBLE_EQ(nlohmann::json::parse(early->body)["progress"].get<double>(), 0.25);
  EXPECT_FALSE(nlohmann::json::parse(client.Get("/api/progress")->body)["ready"].get<bool>());
  const Scene scene = loadScene("cornell-spot");
  const std::unique_ptr<ViewerSession> session = patchSession(scene);
  server.serve(*session);
  EXPECT_EQ(client.Get("/api/scene")->status, 200);
  EXPECT_TRUE(nlohmann::json::parse(client.Get("/api/progress")->body)["ready"].get<bool>());
  server.stop();
  listener.join();
}

}  // namespace
}  // namespace rad
