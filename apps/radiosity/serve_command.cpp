// `radiosity serve SCENE`: solves the scene (or loads a saved solution) and serves the browser
// viewer: the lit scene, its lights to move and dim, the bounce following (src/server:
// ViewerSession, ViewerServer). A method that does not relight has its solution shown and its
// light groups dimmed, not relit.
#include <fmt/format.h>
#include <radiosity/radiosity_method.h>
#include <radiosity/viewer_server.h>
#include <radiosity/viewer_session.h>

#include <CLI/CLI.hpp>
#include <atomic>
#include <chrono>
#include <cmath>
#include <csignal>
#include <memory>
#include <thread>

#include "command_support.h"
#include "commands.h"
#include "method_options.h"

#ifndef RADIOSITY_WEB_DIR
#define RADIOSITY_WEB_DIR "web"
#endif

namespace rad::cli {

namespace {

struct ServeOptions {
  // No pictures; the page dims and switches the light groups (a voxel solution's solved apart).
  explicit ServeOptions(CLI::App& command)
      : method(command,
               {&MethodCapabilities::surfaceSolution, "patch", {"spp", "light_groups"}, false}) {}
  MethodOptions method;
  std::string scene, solution, host = "127.0.0.1", webDir = RADIOSITY_WEB_DIR, allowOrigin;
  int port = 8080;
  double time = 0.0;
  float displayEdge = 0.0f;
  CLI::Option* allowOriginOption = nullptr;  ///< given, even as "" (refused then)
};

// SIGTERM (a service manager's stop, `kill PID`) is taken as Ctrl-C for the guard's lifetime:
// the solve stops, or the server stops listening, answers the requests it has read and exits 0
// (by default SIGTERM killed it mid-answer).
extern "C" void takeTerminateAsInterrupt(int) {
  std::raise(SIGINT);  // async-signal-safe; InterruptGuard's handler takes it from there
}

class TerminateAsInterrupt {
 public:
  TerminateAsInterrupt() { std::signal(SIGTERM, takeTerminateAsInterrupt); }
  ~TerminateAsInterrupt() { std::signal(SIGTERM, SIG_DFL); }
  TerminateAsInterrupt(const TerminateAsInterrupt&) = delete;
  TerminateAsInterrupt& operator=(const TerminateAsInterrupt&) = delete;
};

// The session: the method's relighting, or a solution shown and dimmed by group.
std::unique_ptr<ViewerSession> startSession(const ServeOptions& o, const Scene& scene,
                                            Console& console,
                                            const std::function<void(double)>& report) {
  const MethodCapabilities can = o.method.chosen().capabilities();
  MethodSettings settings = o.method.settings();
  // Without relighting: shown and its groups dimmed, so solved with its groups apart.
  if (!can.relight) settings.lightGroups = can.lightGroups;
  auto engine = std::make_unique<const RadiosityEngine>(scene, settings);
  auto edgeOf = [&](const SurfaceSolution& solution) {
    return o.displayEdge > 0.0f ? o.displayEdge : solution.report().detailEdge;
  };
  if (can.relight) {
    std::unique_ptr<Relighting> relighting =
        startRelighting(*engine, scene.lights, o.solution, {}, console, report);
    const float edge = edgeOf(relighting->solution());
    return std::make_unique<ViewerSession>(std::move(engine), scene.lights, std::move(relighting),
                                           edge);
  }
  const ProgressCallback bar = console.progress(engine->model().solveLabel());
  std::unique_ptr<SurfaceSolution> solution = o.solution.empty()
                                                  ? engine->solve(scene.lights, o.time,
                                                                  [&](double f) {
                                                                    report(f);
                                                                    return !bar || bar(f);
                                                                  })
                                                  : engine->load(o.solution);
  console.finishProgress();
  for (const std::string& w : solution->report().warnings) console.warn(w);
  const float edge = edgeOf(*solution);
  return std::make_unique<ViewerSession>(std::move(engine), scene.lights, std::move(solution),
                                         edge);
}

int runServe(ServeOptions& o, Console& console) {
  RunStats stats;
  const Scene scene = loadSceneForCommand(o.scene, o.time, console, stats);
  o.method.resolve(scene, o.solution, console);
  // Listening from the start: the page shows the solve's progress until the session is there.
  ViewerServer server(o.webDir);
  if (o.allowOriginOption->count() > 0) server.allowOrigin(o.allowOrigin);
  const int port = server.bind(o.host, o.port);
  console.info(fmt::format("serving {} at http://{}:{}/ (solving first; Ctrl-C stops)", o.scene,
                           o.host, port));
  if (o.host != "127.0.0.1" && o.host != "localhost" && o.host != "::1")
    console.warn(fmt::format(
        "--host {}: the viewer listens beyond this machine, and anyone who reaches {}:{} can "
        "move and dim its lights (requests must name it in their Host as {} or localhost); a "
        "page served from elsewhere drives it only with --allow-origin and that page's origin",
        o.host, o.host, port, o.host));
  InterruptGuard interruptible;
  const TerminateAsInterrupt terminable;  // after the guard: its SIGINT handler must be there
  std::thread listener([&] { server.run(); });
  server.waitUntilRunning();
  std::atomic<bool> done = false;
  std::thread watcher([&] {
    while (!done && !InterruptGuard::interrupted())
      std::this_thread::sleep_for(std::chrono::milliseconds(100));
    server.stop();
  });
  std::unique_ptr<ViewerSession> session;
  try {
    session = startSession(o, scene, console, [&](double f) { server.setProgress(f); });
  } catch (...) {
    done = true;
    watcher.join();
    listener.join();
    throw;
  }
  server.serve(*session);
  console.info("ready");
  listener.join();  // until Ctrl-C stops it
  done = true;
  watcher.join();
  console.info("stopped");
  return 0;
}

}  // namespace

void addServeCommand(CLI::App& app, Console& console, CommandAction& action) {
  CLI::App* sub = app.add_subcommand(
      "serve", "Serve the lit scene to a browser: move and dim its lights, the bounce follows");
  auto o = std::make_shared<ServeOptions>(*sub);
  addSceneArgument(*sub, o->scene);
  sub->add_option("--port", o->port, "TCP port (default 8080; 0: any free one)")
      ->check(CLI::Range(0, 65535));
  sub->add_option("--host", o->host, "Address to listen on (default 127.0.0.1: this machine only)");
  o->allowOriginOption =
      sub->add_option(
             "--allow-origin", o->allowOrigin,
             "Let the page served from ORIGIN (e.g. http://localhost:5173) drive the server "
             "too: CORS headers for it alone (default: none, only the server's own page)")
          ->type_name("ORIGIN");
  sub->add_option("--solution", o->solution,
                  "Start from the solution a .rad file keeps (solve --save) instead of solving")
      ->check(nonEmptyPath());
  sub->add_option("--display-edge", o->displayEdge,
                  "Longest edge of the displayed triangles (default: half the patch size)")
      ->check(finiteNumberIn(1e-30, HUGE_VAL));
  sub->add_option("--web-dir", o->webDir, "The page's folder (default: the source tree's web/)");
  addTimeOption(*sub, o->time);
  sub->callback(
      [o, &console, &action] { action = [o, &console] { return runServe(*o, console); }; });
}

}  // namespace rad::cli
