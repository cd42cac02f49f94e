// `needle serve`'s HTTP server: design_server.h.
#include "apps/serve/design_server.h"

#include <httplib.h>
#include <pthread.h>
#include <signal.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <filesystem>
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
// newest X-Needle-Seq, and one computation at a time. A change waiting behind the running one
// is woken and dropped (409) as soon as a newer change of its page arrives: at most one waits,
// none is computed behind a newer one.
class Pages {
 public:
  struct Page {
    long newest = 0;
    bool busy = false;
    std::condition_variable changed;
  };
  // The request's page (a shared one without the header) and its number (0: never dropped),
  // noted as its page's newest.
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
    page->changed.notify_all();
    return {page, n};
  }
  // Waits for the page's running computation to end; false when the request is superseded
  // (before or while waiting), true when it may compute now (the page is then busy).
  bool Begin(Page& page, long n) {
    std::unique_lock<std::mutex> lock(mutex_);
    page.changed.wait(lock, [&] { return !page.busy || Stale(page, n); });
    if (Stale(page, n)) return false;
    page.busy = true;
    return true;
  }
  // Ends the page's computation; true when its result is still the newest.
  bool End(Page& page, long n) {
    std::lock_guard<std::mutex> lock(mutex_);
    page.busy = false;
    page.changed.notify_all();
    return !Stale(page, n);
  }

 private:
  static bool Stale(const Page& page, long n) { return n > 0 && n < page.newest; }
  static constexpr size_t kMaxPages = 1000;
  std::mutex mutex_;
  std::map<std::string, std::shared_ptr<Page>> pages_;
};

void Routes(httplib::Server& server, const DesignSession& session, const ServeOptions& o,
            Pages& pages) {
  server.Get("/", [](const httplib::Request&, httplib::Response& res) {
    res.set_content(DesignPageHtml(), "text/html; charset=utf-8");
  });
  // uPlot's files, from the install (ServeOptions::uplot_dir).
  const std::pair<const char*, const char*> files[] = {{"/uplot.js", "dist/uPlot.iife.min.js"},
                                                       {"/uplot.css", "dist/uPlot.min.css"},
                                                       {"/uplot/LICENSE", "LICENSE"}};
  for (const auto& [route, file] : files) {
    const std::string path = o.uplot_dir + "/" + file;
    const std::string type = std::string(route) == "/uplot.js"    ? "application/javascript"
                             : std::string(route) == "/uplot.css" ? "text/css"
                                                                  : "text/plain; charset=utf-8";
    server.Get(route, [path, type](const httplib::Request&, httplib::Response& res) {
      const std::string content = ReadFile(path);
      if (content.empty()) {
        res.status = 500;
        res.set_content(
            "uPlot is not installed at " + path + " (scripts/install-deps.sh installs it with npm)",
            "text/plain");
        return;
      }
      res.set_content(content, type);
    });
  }
  server.Get("/api/case", [&session](const httplib::Request&, httplib::Response& res) {
    res.set_content(session.CaseJson(), "application/json");
  });
  server.Post("/api/check", [&session](const httplib::Request& req, httplib::Response& res) {
    Reply(res, session.Check(req.body));
  });
  server.Post("/api/design",
              [&session, &pages](const httplib::Request& req, httplib::Response& res) {
                const auto [page, n] = pages.Note(req);
                const ApiReply dropped{409, R"({"dropped": "superseded by a newer change"})"};
                if (!pages.Begin(*page, n)) return Reply(res, dropped);
                ApiReply r;
                try {
                  r = session.Design(req.body);
                } catch (...) {
                  pages.End(*page, n);
                  throw;
                }
                Reply(res, pages.End(*page, n) ? r : dropped);
              });
  server.Post("/api/case-text", [&session](const httplib::Request& req, httplib::Response& res) {
    Reply(res, session.SaveCase(req.body));
  });
}

}  // namespace

std::string DefaultUplotDir() {
  const std::string installed = NEEDLE_UPLOT_INSTALLED, source = NEEDLE_UPLOT_SOURCE;
  return std::filesystem::exists(installed + "/dist/uPlot.iife.min.js") ? installed : source;
}

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
  // Before any route: a chunked body has no length to hold to the 1 MiB limit (411), and a
  // Host that is not this server's (a page of another site rebinding its name to 127.0.0.1)
  // is refused (403), unless the server was bound to every address (--host 0.0.0.0 or ::).
  server.set_pre_routing_handler([&o](const httplib::Request& req, httplib::Response& res) {
    using R = httplib::Server::HandlerResponse;
    if (req.has_header("Transfer-Encoding")) {
      res.status = 411;
      res.set_content(
          nlohmann::json{{"error", "a body needs its Content-Length (no chunked bodies)"}}.dump(),
          "application/json");
      return R::Handled;
    }
    const bool any = o.host == "0.0.0.0" || o.host == "::";
    std::string host = req.get_header_value("Host");
    const size_t colon = host.rfind(':');
    if (colon != std::string::npos && host.back() != ']') host.resize(colon);
    if (!any && !host.empty() && host != o.host && host != "localhost" && host != "127.0.0.1" &&
        host != "[::1]") {
      res.status = 403;
      res.set_content(nlohmann::json{{"error", "this server answers for " + o.host +
                                                   " only, not for Host " + host}}
                          .dump(),
                      "application/json");
      return R::Handled;
    }
    return R::Unhandled;
  });
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
    // A signal before the server runs would be lost (stop() does nothing until it listens).
    while (!done.load() && !server.is_running())
      std::this_thread::sleep_for(std::chrono::milliseconds(1));
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
