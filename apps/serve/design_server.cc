// `needle serve`'s HTTP server: design_server.h.
#include "apps/serve/design_server.h"

#include <httplib.h>
#include <pthread.h>
#include <signal.h>

#include <algorithm>
#include <atomic>
#include <fstream>
#include <map>
#include <memory>
#include <mutex>
#include <sstream>
#include <thread>

#include "lib/case_error.h"

namespace needle {

extern const char kDesignPageHtml[];  // apps/serve/web/index.html, built in (design_page.cc)

namespace {

constexpr size_t kMaxBody = 1 << 20;  // 1 MiB: a case's overrides are a few hundred bytes

std::mutex g_mutex;
httplib::Server* g_server = nullptr;  // the running server, for StopServing

std::string ReadFile(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return "";
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

void Reply(httplib::Response& res, const ApiReply& r) {
  res.status = r.status;
  res.set_content(r.body, "application/json");
}

// The page's changes, one page (X-Needle-Client, a random id per page load) at a time: its
// newest X-Needle-Seq, and one computation at a time, so a change that waited behind a running
// one is dropped when a newer change came meanwhile, never computed.
class Pages {
 public:
  struct Page {
    long newest = 0;
    std::mutex computing;
  };
  // The request's page (a shared one without the header) and its number (0: never dropped).
  std::pair<std::shared_ptr<Page>, long> Note(const httplib::Request& req) {
    const std::string id = req.get_header_value("X-Needle-Client");
    long n = 0;
    try {
      n = std::max(0L, std::stol(req.get_header_value("X-Needle-Seq")));
    } catch (...) {
      n = 0;
    }
    std::lock_guard<std::mutex> lock(mutex_);
    if (pages_.size() > kMaxPages && !pages_.count(id)) pages_.clear();  // a bound on memory
    std::shared_ptr<Page>& page = pages_[id];
    if (!page) page = std::make_shared<Page>();
    page->newest = std::max(page->newest, n);
    return {page, n};
  }
  bool Superseded(const Page& page, long n) {
    std::lock_guard<std::mutex> lock(mutex_);
    return n > 0 && n < page.newest;
  }

 private:
  static constexpr size_t kMaxPages = 1000;
  std::mutex mutex_;
  std::map<std::string, std::shared_ptr<Page>> pages_;
};

void Routes(httplib::Server& server, const DesignSession& session, const ServeOptions& o,
            Pages& pages) {
  server.Get("/", [](const httplib::Request&, httplib::Response& res) {
    res.set_content(DesignPageHtml(), "text/html; charset=utf-8");
  });
  const std::string chart = o.chart_js, licence = o.chart_js_licence;
  server.Get("/chart.js", [chart](const httplib::Request&, httplib::Response& res) {
    const std::string js = ReadFile(chart);
    if (js.empty()) {
      res.status = 500;
      res.set_content("Chart.js is not installed at " + chart +
                          " (apt-get install libjs-chart.js; scripts/install-deps.sh does)",
                      "text/plain");
      return;
    }
    res.set_content(js, "application/javascript");
  });
  server.Get("/chart.js/LICENSE", [licence](const httplib::Request&, httplib::Response& res) {
    res.set_content(ReadFile(licence), "text/plain; charset=utf-8");
  });
  server.Get("/api/case", [&session](const httplib::Request&, httplib::Response& res) {
    res.set_content(session.CaseJson(), "application/json");
  });
  server.Post("/api/check", [&session](const httplib::Request& req, httplib::Response& res) {
    Reply(res, session.Check(req.body));
  });
  server.Post("/api/design",
              [&session, &pages](const httplib::Request& req, httplib::Response& res) {
                const auto [page, n] = pages.Note(req);
                const auto dropped = [&res] {
                  Reply(res, {409, R"({"dropped": "superseded by a newer change"})"});
                };
                if (pages.Superseded(*page, n)) return dropped();
                std::lock_guard<std::mutex> one_at_a_time(page->computing);
                if (pages.Superseded(*page, n))
                  return dropped();  // a newer change came while it waited
                const ApiReply r = session.Design(req.body);
                if (pages.Superseded(*page, n)) return dropped();
                Reply(res, r);
              });
  server.Post("/api/case-text", [&session](const httplib::Request& req, httplib::Response& res) {
    Reply(res, session.SaveCase(req.body));
  });
}

}  // namespace

const std::string& DesignPageHtml() {
  static const std::string page = kDesignPageHtml;
  return page;
}

void StopServing() {
  std::lock_guard<std::mutex> lock(g_mutex);
  if (g_server) g_server->stop();
}

int Serve(const DesignSession& session, const ServeOptions& o) {
  httplib::Server server;
  server.set_payload_max_length(kMaxBody);
  server.set_read_timeout(5, 0);
  server.set_write_timeout(5, 0);
  Pages pages;
  Routes(server, session, o, pages);
  // Only SO_REUSEADDR: httplib's default also sets SO_REUSEPORT, which lets a second server
  // share a port in use, silently.
  server.set_socket_options([](socket_t sock) {
    int yes = 1;
    setsockopt(sock, SOL_SOCKET, SO_REUSEADDR, reinterpret_cast<const char*>(&yes), sizeof yes);
  });
  server.set_keep_alive_timeout(2);  // an idle connection holds a worker thread no longer
  server.new_task_queue = [] { return new httplib::ThreadPool(16); };
  // An error without a body (413, 404, 400 from the parser) still says what, in one JSON line.
  server.set_error_handler([](const httplib::Request& req, httplib::Response& res) {
    if (!res.body.empty()) return;
    const std::string what = res.status == 413   ? "the body is over the 1 MiB limit"
                             : res.status == 404 ? "no such page or API: " + req.path
                                                 : "a request the server could not read";
    res.set_content(nlohmann::json{{"error", what}}.dump(), "application/json");
  });
  server.set_exception_handler(
      [](const httplib::Request&, httplib::Response& res, std::exception_ptr ep) {
        std::string what = "unknown";
        try {
          std::rethrow_exception(ep);
        } catch (const std::exception& e) {
          what = e.what();
        } catch (...) {
        }
        res.status = 500;  // a bug: said, and the server goes on
        res.set_content(nlohmann::json{{"error", "internal error: " + what}}.dump(),
                        "application/json");
      });
  const int port = o.port == 0 ? server.bind_to_any_port(o.host)
                               : (server.bind_to_port(o.host, o.port) ? o.port : -1);
  if (port < 0)
    throw CaseError("--host/--port: cannot listen on " + o.host + ":" + std::to_string(o.port) +
                    " (the port in use, or the host not an address of this machine)");
  // SIGINT and SIGTERM go to one thread that stops the server: the pool's threads never see them.
  sigset_t signals, previous;
  sigemptyset(&signals);
  sigaddset(&signals, SIGINT);
  sigaddset(&signals, SIGTERM);
  pthread_sigmask(SIG_BLOCK, &signals, &previous);
  {
    std::lock_guard<std::mutex> lock(g_mutex);
    g_server = &server;
  }
  std::atomic<bool> done{false};
  std::thread watcher([&] {
    int signal = 0;
    sigwait(&signals, &signal);
    if (!done.load()) StopServing();
  });
  if (o.on_listening) o.on_listening(port);
  server.listen_after_bind();
  done = true;
  {
    std::lock_guard<std::mutex> lock(g_mutex);
    g_server = nullptr;
  }
  pthread_kill(watcher.native_handle(), SIGTERM);  // ends its sigwait if no signal came
  watcher.join();
  pthread_sigmask(SIG_SETMASK, &previous, nullptr);
  return 0;
}

}  // namespace needle
