#pragma once
// A cpp-httplib server whose workers never wait on a client. cpp-httplib 0.11 gives each
// connection a worker thread of a pool of 8 from accept to close, reading with a timeout per
// recv() and no bound on header count: 12 clients dribbling a header a byte at a time starved a
// plain GET for 25 s, 8 idle connections delayed every request by 4.7 s, and 400,000 headers
// were read (+44 MB). Here one thread reads every connection without blocking, a request whole
// (head and body) under the limits below before a worker sees it, and writes the answers back;
// the workers only compute them (Server::process_request over the bytes in memory). The routes,
// handlers and the rest of httplib::Server's settings work as usual.

#include <httplib.h>
#include <sys/socket.h>

#include <chrono>
#include <cstddef>
#include <memory>

namespace rad {

/// What a connection may take of the server (docs/ARCHITECTURE.md, "The viewer's server").
struct HttpLimits {
  size_t workers = 4;             ///< threads that answer requests read whole
  size_t maxQueued = 64;          ///< requests read and waiting for a worker; more: 503
  size_t maxConnections = 64;     ///< open at once; a new one closes the oldest that is reading
  size_t maxHeadBytes = 32768;    ///< request line and headers; more: 431
  size_t maxHeaderCount = 100;    ///< header lines; more: 431
  size_t maxBodyBytes = 1 << 20;  ///< Content-Length; more: 413 (a body without one: 411)
  size_t maxRequestsPerConnection = 100;  ///< then the answer says Connection: close
  /// A request must arrive whole within this of the connection opening or its last answer (an
  /// idle connection is closed then, one that sent part of a request gets 408).
  std::chrono::milliseconds requestTime{10000};
  /// An answer must be taken within this, or the connection is closed.
  std::chrono::milliseconds answerTime{30000};
};

class BoundedHttpServer : public httplib::Server {
 public:
  explicit BoundedHttpServer(const HttpLimits& limits = {});
  ~BoundedHttpServer() override;
  const HttpLimits& limits() const { return limits_; }
  /// After a bind: lets the kernel hold `connections` not yet accepted (httplib listens with 5,
  /// and a burst of new connections beyond them waits out a SYN retry: 1 s, then 3 s, ...).
  void widenBacklog(int connections = SOMAXCONN);

 private:
  class Reception;
  // Called by httplib's accept loop (on its own thread): hands the socket to the reception.
  bool process_and_close_socket(socket_t sock) override;
  // A request's bytes, read whole, answered by httplib's routing; the bytes of the answer.
  std::string answer(int socket, const std::string& request, bool lastOnConnection,
                     bool& closeAfter);

  HttpLimits limits_;
  Reception* reception_ = nullptr;  ///< while listening (owned by httplib's task queue)
};

}  // namespace rad
