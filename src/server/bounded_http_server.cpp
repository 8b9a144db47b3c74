// One thread reads and writes every connection without blocking; workers answer requests read
// whole. The reading is the part cpp-httplib 0.11 does with a worker per connection.
#include "server/bounded_http_server.h"

#include <arpa/inet.h>
#include <fcntl.h>
#include <fmt/format.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <condition_variable>
#include <cstring>
#include <deque>
#include <map>
#include <mutex>
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <string_view>
#include <thread>
#include <vector>

namespace rad {

namespace {

using Clock = std::chrono::steady_clock;

// The address at either end of a socket, as httplib's own stream gives it.
void addressOf(int socket, bool peer, std::string& ip, int& port) {
  sockaddr_storage address{};
  socklen_t length = sizeof address;
  auto* a = reinterpret_cast<sockaddr*>(&address);
  if ((peer ? getpeername(socket, a, &length) : getsockname(socket, a, &length)) != 0) return;
  char text[INET6_ADDRSTRLEN] = "";
  if (address.ss_family == AF_INET) {
    const auto* v4 = reinterpret_cast<const sockaddr_in*>(&address);
    inet_ntop(AF_INET, &v4->sin_addr, text, sizeof text);
    port = ntohs(v4->sin_port);
  } else if (address.ss_family == AF_INET6) {
    const auto* v6 = reinterpret_cast<const sockaddr_in6*>(&address);
    inet_ntop(AF_INET6, &v6->sin6_addr, text, sizeof text);
    port = ntohs(v6->sin6_port);
  }
  ip = text;
}

// A request read whole, as httplib's routing reads it; the answer it writes, kept.
class MemoryStream final : public httplib::Stream {
 public:
  MemoryStream(int socket, const std::string& request) : socket_(socket), request_(request) {}
  bool is_readable() const override { return at_ < request_.size(); }
  bool is_writable() const override { return true; }
  ssize_t read(char* ptr, size_t size) override {
    const size_t n = std::min(size, request_.size() - at_);
    std::memcpy(ptr, request_.data() + at_, n);
    at_ += n;
    return ssize_t(n);
  }
  ssize_t write(const char* ptr, size_t size) override {
    answer.append(ptr, size);
    return ssize_t(size);
  }
  void get_remote_ip_and_port(std::string& ip, int& port) const override {
    addressOf(socket_, true, ip, port);
  }
  void get_local_ip_and_port(std::string& ip, int& port) const override {
    addressOf(socket_, false, ip, port);
  }
  socket_t socket() const override { return socket_; }

  std::string answer;

 private:
  int socket_;
  const std::string& request_;
  size_t at_ = 0;
};

// An answer the reception gives itself, closing the connection after it.
std::string refusal(int status, const char* reason, const std::string& message) {
  const std::string body = nlohmann::json{{"error", message}}.dump();
  return fmt::format(
      "HTTP/1.1 {} {}\r\nContent-Type: application/json\r\nContent-Length: {}\r\n"
      "Connection: close\r\n\r\n{}",
      status, reason, body.size(), body);
}

bool namedAs(std::string_view line, std::string_view name) {
  return line.size() > name.size() && line[name.size()] == ':' &&
         std::equal(name.begin(), name.end(), line.begin(), [](char a, char b) {
           return std::tolower(static_cast<unsigned char>(a)) ==
                  std::tolower(static_cast<unsigned char>(b));
         });
}

// What the bytes read so far hold: not yet a request, a request of `length` bytes, or one to
// refuse with `answer`.
struct Verdict {
  enum Kind { Partial, Whole, Refused } kind = Partial;
  size_t length = 0;
  std::string answer;
};

Verdict refused(int status, const char* reason, const std::string& message) {
  return {Verdict::Refused, 0, refusal(status, reason, message)};
}

// The body's length its head declares (Content-Length; none: 0), or a refusal.
Verdict bodyLength(std::string_view head, const HttpLimits& limits) {
  size_t length = 0;
  bool declared = false;
  for (size_t at = head.find("\r\n") + 2; at < head.size();) {
    const size_t end = head.find("\r\n", at);
    const std::string_view line = head.substr(at, end - at);
    at = end + 2;
    if (namedAs(line, "transfer-encoding"))
      return refused(411, "Length Required",
                     "a body in chunks (Transfer-Encoding) is not taken: send Content-Length");
    if (!namedAs(line, "content-length")) continue;
    std::string_view value = line.substr(15);
    while (!value.empty() && (value.front() == ' ' || value.front() == '\t'))
      value.remove_prefix(1);
    while (!value.empty() && (value.back() == ' ' || value.back() == '\t')) value.remove_suffix(1);
    const bool digits =
        !value.empty() && value.size() <= 18 &&
        std::all_of(value.begin(), value.end(), [](char c) { return c >= '0' && c <= '9'; });
    const size_t n = digits ? std::stoull(std::string(value)) : 0;
    if (!digits || (declared && n != length))
      return refused(400, "Bad Request", "Content-Length is not one number of bytes");
    length = n;
    declared = true;
  }
  if (length > limits.maxBodyBytes)
    return refused(413, "Payload Too Large",
                   fmt::format("body of {} bytes; at most {}", length, limits.maxBodyBytes));
  return {Verdict::Whole, length, {}};
}

Verdict examine(const std::string& in, const HttpLimits& limits) {
  // Looked for within the limit only: a body arriving in pieces is not searched again and again.
  const std::string_view start = std::string_view(in).substr(0, limits.maxHeadBytes + 4);
  const size_t end = start.find("\r\n\r\n");
  const std::string_view head = end == std::string::npos ? start : start.substr(0, end + 4);
  // Lines ended so far, less the request line (and the blank line that ends the head).
  const auto lines = std::count(head.begin(), head.end(), '\n');
  const size_t headers =
      size_t(std::max<std::ptrdiff_t>(0, lines - (end == std::string::npos ? 1 : 2)));
  if ((end == std::string::npos && in.size() > limits.maxHeadBytes) ||
      head.size() > limits.maxHeadBytes || headers > limits.maxHeaderCount)
    return refused(431, "Request Header Fields Too Large",
                   fmt::format("the request line and headers take at most {} bytes and {} headers",
                               limits.maxHeadBytes, limits.maxHeaderCount));
  if (end == std::string::npos) return {};
  Verdict v = bodyLength(head, limits);
  if (v.kind == Verdict::Whole) {
    v.length += head.size();
    if (in.size() < v.length) v.kind = Verdict::Partial;
  }
  return v;
}

void setNonBlocking(int socket) {
  fcntl(socket, F_SETFL, fcntl(socket, F_GETFL, 0) | O_NONBLOCK);
}

}  // namespace

class BoundedHttpServer::Reception final : public httplib::TaskQueue {
 public:
  explicit Reception(BoundedHttpServer& server) : server_(server), limits_(server.limits_) {
    if (::pipe(wake_) != 0)
      throw std::runtime_error(fmt::format("the server's wake-up pipe: {}", std::strerror(errno)));
    setNonBlocking(wake_[0]);
    setNonBlocking(wake_[1]);
    loop_ = std::thread([this] { loop(); });
    for (size_t k = 0; k < std::max<size_t>(1, limits_.workers); ++k)
      workers_.emplace_back([this] { work(); });
  }
  ~Reception() override {
    if (loop_.joinable()) shutdown();
    ::close(wake_[0]);
    ::close(wake_[1]);
  }

  // httplib's accept loop hands each connection here through process_and_close_socket.
  void enqueue(std::function<void()> fn) override { fn(); }

  // Stops reading requests; answers the ones workers hold, then returns.
  void shutdown() override {
    {
      std::lock_guard lock(mutex_);
      stopping_ = true;
    }
    wake();
    loop_.join();
    {
      std::lock_guard lock(mutex_);
      workersStop_ = true;
    }
    jobReady_.notify_all();
    for (std::thread& t : workers_) t.join();
    server_.reception_ = nullptr;  // httplib deletes this queue next
  }

  void add(int socket) {
    {
      std::lock_guard lock(mutex_);
      arrivals_.push_back(socket);
    }
    wake();
  }

 private:
  enum class State { Reading, Working, Writing, Draining };
  struct Connection {
    State state = State::Reading;
    std::string in, out;
    size_t sent = 0;
    Clock::time_point opened, deadline;
    size_t served = 0;
    bool closeAfter = false;
  };
  struct Job {
    int socket;
    std::string request;
    bool last;
  };
  struct Done {
    int socket;
    std::string answer;
    bool close;
  };

  void wake() {
    const char byte = 1;
    [[maybe_unused]] const ssize_t n = ::write(wake_[1], &byte, 1);  // full: a wake is pending
  }

  void work() {
    for (;;) {
      Job job;
      {
        std::unique_lock lock(mutex_);
        jobReady_.wait(lock, [&] { return !jobs_.empty() || workersStop_; });
        if (jobs_.empty()) return;
        job = std::move(jobs_.front());
        jobs_.pop_front();
      }
      bool close = true;
      std::string answer;
      try {
        answer = server_.answer(job.socket, job.request, job.last, close);
      } catch (...) {  // httplib's own handler takes the routes' exceptions; anything else
        answer = refusal(500, "Internal Server Error", "the answer failed");
        close = true;
      }
      {
        std::lock_guard lock(mutex_);
        done_.push_back({job.socket, std::move(answer), close});
      }
      wake();
    }
  }

  void loop() {
    std::vector<pollfd> polled;
    for (;;) {
      const bool stopping = takeArrivalsAndAnswers();
      if (stopping) stopReading();
      if (stopping && connections_.empty()) return;
      const Clock::time_point now = Clock::now();
      expire(now);
      polled.assign(1, pollfd{wake_[0], POLLIN, 0});
      Clock::time_point next = now + std::chrono::seconds(1);
      for (const auto& [socket, c] : connections_) {
        if (c.state == State::Working) continue;
        polled.push_back({socket, short(c.state == State::Writing ? POLLOUT : POLLIN), 0});
        next = std::min(next, c.deadline);
      }
      const auto wait = std::chrono::duration_cast<std::chrono::milliseconds>(next - now);
      if (::poll(polled.data(), polled.size(), int(std::max<int64_t>(1, wait.count() + 1))) <= 0)
        continue;
      if (polled[0].revents) drainWake();
      for (size_t k = 1; k < polled.size(); ++k)
        if (polled[k].revents) serve(polled[k].fd, polled[k].revents);
    }
  }

  // New connections and the workers' answers; whether the server is stopping.
  bool takeArrivalsAndAnswers() {
    std::vector<int> arrivals;
    std::vector<Done> done;
    bool stopping = false;
    {
      std::lock_guard lock(mutex_);
      arrivals.swap(arrivals_);
      done.swap(done_);
      stopping = stopping_;
    }
    for (int socket : arrivals) admit(socket, stopping);
    for (Done& d : done) {
      Connection& c = connections_.at(d.socket);
      answerWith(d.socket, c, std::move(d.answer), d.close);
    }
    return stopping;
  }

  void admit(int socket, bool stopping) {
    if (stopping) return (void)::close(socket);
    setNonBlocking(socket);
    if (connections_.size() >= limits_.maxConnections && !evictOldestReading()) {
      const std::string busy =
          refusal(503, "Service Unavailable",
                  fmt::format("{} connections are being answered; try again", connections_.size()));
      [[maybe_unused]] const ssize_t n = ::send(socket, busy.data(), busy.size(), MSG_NOSIGNAL);
      return (void)::close(socket);
    }
    Connection& c = connections_[socket];
    c.opened = Clock::now();
    c.deadline = c.opened + limits_.requestTime;
  }

  // Room for a new connection: the oldest one that holds no request being answered goes.
  bool evictOldestReading() {
    auto oldest = connections_.end();
    for (auto it = connections_.begin(); it != connections_.end(); ++it)
      if (it->second.state == State::Reading &&
          (oldest == connections_.end() || it->second.opened < oldest->second.opened))
        oldest = it;
    if (oldest == connections_.end()) return false;
    close(oldest->first);
    return true;
  }

  void stopReading() {
    for (auto it = connections_.begin(); it != connections_.end();) {
      const int socket = it->first;
      Connection& c = it->second;
      ++it;
      if (c.state == State::Reading || c.state == State::Draining)
        close(socket);
      else if (c.state == State::Writing)
        c.deadline = std::min(c.deadline, Clock::now() + std::chrono::seconds(2));
    }
  }

  void expire(Clock::time_point now) {
    for (auto it = connections_.begin(); it != connections_.end();) {
      const int socket = it->first;
      Connection& c = it->second;
      ++it;
      if (c.state == State::Working || now < c.deadline) continue;
      if (c.state == State::Reading && !c.in.empty())
        answerWith(socket, c,
                   refusal(408, "Request Timeout",
                           fmt::format("the request did not arrive whole within {} ms",
                                       limits_.requestTime.count())),
                   true);
      else
        close(socket);
    }
  }

  void serve(int socket, short events) {
    const auto found = connections_.find(socket);
    if (found == connections_.end()) return;
    Connection& c = found->second;
    if (c.state == State::Writing) return send(socket, c);
    if (c.state != State::Reading && c.state != State::Draining) return;
    char buffer[16384];
    const ssize_t n = ::recv(socket, buffer, sizeof buffer, 0);
    if (n == 0 || (n < 0 && errno != EAGAIN && errno != EINTR) || (events & POLLERR))
      return close(socket);  // the client left (or after our last answer, finished)
    if (n < 0 || c.state == State::Draining) return;
    c.in.append(buffer, size_t(n));
    advance(socket, c);
  }

  // A request read whole goes to a worker; one over the limits is refused.
  void advance(int socket, Connection& c) {
    Verdict v = examine(c.in, limits_);
    if (v.kind == Verdict::Partial) return;
    if (v.kind == Verdict::Refused) return answerWith(socket, c, std::move(v.answer), true);
    std::string request = c.in.substr(0, v.length);
    c.in.erase(0, v.length);
    {
      std::lock_guard lock(mutex_);
      if (jobs_.size() < limits_.maxQueued) {
        jobs_.push_back(
            {socket, std::move(request), c.served + 1 >= limits_.maxRequestsPerConnection});
        c.state = State::Working;
      }
    }
    if (c.state == State::Working) return jobReady_.notify_one();
    answerWith(socket, c,
               refusal(503, "Service Unavailable",
                       fmt::format("{} requests wait for an answer; try again", limits_.maxQueued)),
               true);
  }

  void answerWith(int socket, Connection& c, std::string answer, bool closeAfter) {
    c.state = State::Writing;
    c.out = std::move(answer);
    c.sent = 0;
    c.closeAfter = closeAfter;
    c.deadline = Clock::now() + limits_.answerTime;
    send(socket, c);
  }

  void send(int socket, Connection& c) {
    while (c.sent < c.out.size()) {
      const ssize_t n = ::send(socket, c.out.data() + c.sent, c.out.size() - c.sent, MSG_NOSIGNAL);
      if (n < 0 && (errno == EAGAIN || errno == EINTR)) return;  // the rest when it can take it
      if (n <= 0) return close(socket);
      c.sent += size_t(n);
    }
    c.out = std::string();
    ++c.served;
    if (c.closeAfter) {
      // Closed with unread bytes, the connection would be reset and the client might lose the
      // answer: read what it still sends (dropped) for a second first.
      ::shutdown(socket, SHUT_WR);
      c.state = State::Draining;
      c.deadline = Clock::now() + std::chrono::seconds(1);
      return;
    }
    c.state = State::Reading;
    c.deadline = Clock::now() + limits_.requestTime;
    if (!c.in.empty()) advance(socket, c);  // a request sent before this answer
  }

  void close(int socket) {
    ::close(socket);
    connections_.erase(socket);
  }

  void drainWake() {
    char bytes[64];
    while (::read(wake_[0], bytes, sizeof bytes) > 0) {
    }
  }

  BoundedHttpServer& server_;
  const HttpLimits limits_;
  int wake_[2] = {-1, -1};  ///< a byte in it wakes the loop's poll()
  std::thread loop_;
  std::vector<std::thread> workers_;
  std::map<int, Connection> connections_;  ///< the loop's alone

  std::mutex mutex_;  ///< guards what follows, shared by the loop, the workers and the acceptor
  std::condition_variable jobReady_;
  std::vector<int> arrivals_;
  std::deque<Job> jobs_;
  std::vector<Done> done_;
  bool stopping_ = false, workersStop_ = false;
};

BoundedHttpServer::BoundedHttpServer(const HttpLimits& limits) : limits_(limits) {
  new_task_queue = [this] {
    reception_ = new Reception(*this);  // httplib owns it and shuts it down when it stops
    return reception_;
  };
  // What its answers' Keep-Alive header says.
  set_keep_alive_max_count(limits_.maxRequestsPerConnection);
  set_keep_alive_timeout(
      std::chrono::duration_cast<std::chrono::seconds>(limits_.requestTime).count());
  set_payload_max_length(limits_.maxBodyBytes);
}

BoundedHttpServer::~BoundedHttpServer() = default;

void BoundedHttpServer::widenBacklog(int connections) {
  ::listen(svr_sock_, connections);  // on a listening socket, Linux takes the new length
}

bool BoundedHttpServer::process_and_close_socket(socket_t sock) {
  reception_->add(sock);
  return true;
}

std::string BoundedHttpServer::answer(int socket, const std::string& request, bool lastOnConnection,
                                      bool& closeAfter) {
  MemoryStream stream(socket, request);
  bool closed = false;
  const bool answered = process_request(stream, lastOnConnection, closed, nullptr);
  closeAfter = !answered || closed || lastOnConnection;
  return std::move(stream.answer);
}

}  // namespace rad
