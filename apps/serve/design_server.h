#pragma once
/// @file
/// `needle serve`'s HTTP server (cpp-httplib, Debian's libcpp-httplib-dev): the design page and
/// its API over a DesignSession (design_api.h).
///
///     GET  /                the page (apps/serve/web/index.html, built in)
///     GET  /uplot.js, /uplot.css, /uplot/LICENSE  uPlot (npm, pinned) and its licence, served
///                           from the install: no CDN, it works offline
///     GET  /api/case        the case file as JSON
///     POST /api/check       overrides → `needle check --json`'s object; a bad one: 400, one line
///     POST /api/design      overrides → {"check", "series"} for the page; one computation at
///                           a time per page (X-Needle-Client), and a request whose X-Needle-Seq
///                           is below its page's newest is dropped (409) before, while waiting
///                           for, and after its computation: superseded work is never queued
///                           behind a newer change, nor drawn
///     POST /api/case-text   overrides → {"toml": the merged case file} (Save as case)
///
/// Requests run on the server's thread pool: a slow check never blocks the page's other
/// requests (16 threads; an idle connection is closed after 2 s). Bodies over 1 MiB are refused
/// (413; a form-encoded body over 8 KiB, httplib's). A request overriding a file key (`[lift]
/// csv`) is refused: the page does not open files. SIGINT or SIGTERM stops the server and Serve
/// returns 0.

#include <functional>
#include <string>

#include "apps/serve/design_api.h"

namespace needle {

/// Where uPlot is: the installed copy, else the source tree's (ServeOptions::uplot_dir).
std::string DefaultUplotDir();

struct ServeOptions {
  std::string host = "127.0.0.1";  ///< the address to bind; anything else prints a warning
  int port = 8080;                 ///< 0: any free port
  /// Called once with the port bound, before serving (tests read it; the CLI prints the URL).
  std::function<void(int)> on_listening;
  /// The folder of uPlot (the page's charts, pinned in apps/serve/web/package.json): its
  /// dist/uPlot.iife.min.js, dist/uPlot.min.css and LICENSE. Default: the installed copy
  /// (share/needle/uplot) when there is one, else the one scripts/install-deps.sh put in the
  /// source tree (apps/serve/web/node_modules/uplot).
  std::string uplot_dir = DefaultUplotDir();
};

/// The design page built into the binary.
const std::string& DesignPageHtml();

/// Serves `session` until SIGINT/SIGTERM (or `stop` is set and polled, for tests). Returns 0 when
/// stopped; throws CaseError naming --host/--port when the address cannot be bound.
int Serve(const DesignSession& session, const ServeOptions& options);

/// Stops a running Serve from another thread (tests; SIGINT does it for the CLI).
void StopServing();

}  // namespace needle
