#include "apps/cli/serve_command.h"

#include <iostream>

#include "apps/serve/design_api.h"
#include "apps/serve/design_server.h"

namespace needle {

CLI::App* AddServeCommand(CLI::App& app, ServeCommandOptions& o) {
  CLI::App* cmd = app.add_subcommand("serve", kServeCommandSummary);
  cmd->add_option("CASE", o.case_path, "case file (TOML)")->required();
  cmd->add_option("--port", o.port, "TCP port (default 8080; 0: any free port)")
      ->check(CLI::Range(0, 65535));
  cmd->add_option("--host", o.host,
                  "address to bind (default 127.0.0.1: this machine only; another address is "
                  "reachable by others, with no login)")
      ->check(CLI::Validator(
          [](std::string& host) -> std::string {
            return host.find_first_not_of(" \t") == std::string::npos
                       ? "expected an address to bind, such as 127.0.0.1 or 0.0.0.0, got '" + host +
                             "'"
                       : std::string();
          },
          "ADDRESS", ""));
  return cmd;
}

int RunServeCommand(const ServeCommandOptions& o) {
  const DesignSession session(o.case_path);  // a bad case: one line, exit 2, before binding
  ServeOptions so;
  so.host = o.host;
  so.port = o.port;
  so.on_listening = [&o](int port) {
    if (o.host != "127.0.0.1" && o.host != "localhost" && o.host != "::1") {
      std::cerr << "needle serve: warning: bound to " << o.host
                << ": the page has no login; anyone who reaches this address can use it\n";
    }
    const std::string host = o.host == "0.0.0.0"                     ? "127.0.0.1"
                             : o.host.find(':') != std::string::npos ? "[" + o.host + "]"
                                                                     : o.host;
    std::cout << "needle serve: " << o.case_path << " at http://" << host << ":" << port
              << "/ (Ctrl-C stops)" << std::endl;
  };
  return Serve(session, so);
}

}  // namespace needle
