#pragma once
/// @file
/// `needle serve CASE [--port N] [--host ADDR]`: the design page (apps/serve/design_server.h):
/// the case live in a browser, every change recomputed through the library as `needle check`
/// computes it. Binds 127.0.0.1 by default; another --host is bound with a printed warning (the
/// page has no login). Runs until SIGINT or SIGTERM, then exits 0. Exit 2 on a bad case, port or
/// host.

#include <CLI/CLI.hpp>
#include <string>

#include "apps/report/output_format.h"

namespace needle {

struct ServeCommandOptions {
  std::string case_path;
  int port = 8080;                 ///< 0: any free port (printed)
  std::string host = "127.0.0.1";  ///< the address to bind
  bool json = false;               ///< (every command's; the server's replies are JSON anyway)
  OutputFormat format = OutputFormat::kText;
};

/// The command's one-line description (`needle --help`).
inline constexpr char kServeCommandSummary[] =
    "The design page: the case live in a browser, recomputed on every change";

CLI::App* AddServeCommand(CLI::App& app, ServeCommandOptions& options);
int RunServeCommand(const ServeCommandOptions& options);

}  // namespace needle
