// The `needle` command: a thin layer over the libraries. Exit status: 0 success,
// 1 a check that fails, 2 bad input (case file, options) — one line on stderr, 3 an internal
// error. Built twice (apps/CMakeLists.txt): `needle`, which hands `fit` and `serve` to
// `needle-fit-serve`, and that program (NEEDLE_FIT_SERVE), which runs every command.
#include <CLI/CLI.hpp>
#if defined(__GLIBC__)
#include <malloc.h>
#endif
#include <cstring>
#include <functional>
#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include "apps/case/case_file.h"
#include "apps/cli/cam_command.h"
#include "apps/cli/check_command.h"
#include "apps/cli/compare_command.h"
#include "apps/cli/dynamics_command.h"
#include "apps/cli/fit_command.h"
#include "apps/cli/kinematics_command.h"
#include "apps/cli/program_start.h"
#include "apps/cli/serve_command.h"
#include "apps/cli/size_command.h"
#include "apps/cli/spring_command.h"
#include "apps/cli/tolerance_command.h"
#include "apps/report/output_format.h"
#include "apps/report/output_paths.h"
#include "lib/case_error.h"

namespace {

// A subcommand: its parsed flag and how to run it with the options it filled in.
struct Command {
  CLI::App* app;
  std::function<int()> run;
};

template <typename Options>
Command Register(CLI::App& app, CLI::App* (*add)(CLI::App&, Options&), int (*run)(const Options&)) {
  auto options = std::make_shared<Options>();
  CLI::App* sub = add(app, *options);
  needle::AddFormatOption(sub, options->format, options->json);  // every command, once
  return {sub, [options, run] { return run(*options); }};
}

#if !defined(NEEDLE_FIT_SERVE)
// A command run by needle-fit-serve: named in `needle --help`, its arguments left to that
// program (main hands it over before parsing; the callback is for a parse that gets here).
Command Elsewhere(CLI::App& app, const char* name, const char* summary, char** argv) {
  CLI::App* sub = app.add_subcommand(name, summary);
  sub->allow_extras();
  sub->prefix_command();
  return {sub, [argv] { return needle::RunInFitServe(argv); }};
}
#endif

}  // namespace

int main(int argc, char** argv) {
#if !defined(NEEDLE_FIT_SERVE)
  if (argc > 1 && (std::strcmp(argv[1], "fit") == 0 || std::strcmp(argv[1], "serve") == 0))
    return needle::RunInFitServe(argv);
#endif
#if defined(__GLIBC__)
  needle::RestartWithHugePages(argc, argv);
  // A dense table's reading allocates and frees vectors of its length again and again; glibc
  // hands freed top-of-heap memory and large blocks back to the kernel at once, and each new
  // vector pays its page faults afresh (1e6 rows: 81,000 faults, half of `kinematics`' 1.8 s).
  // Freed memory is kept for reuse instead (blocks up to 32 MB from the heap, trimmed past
  // 256 MB). A refusal only costs that time, so mallopt's result is not acted on.
  static_cast<void>(mallopt(M_MMAP_THRESHOLD, 32 << 20));
  static_cast<void>(mallopt(M_TRIM_THRESHOLD, 256 << 20));
#endif
  CLI::App app{"needle: cam-driven needle valves — kinematics, spring sizing, dynamics"};
  app.require_subcommand(1);
  const std::vector<Command> commands = {
    Register(app, needle::AddCheckCommand, needle::RunCheckCommand),
    Register(app, needle::AddCompareCommand, needle::RunCompareCommand),
    Register(app, needle::AddKinematicsCommand, needle::RunKinematicsCommand),
    Register(app, needle::AddSpringCommand, needle::RunSpringCommand),
    Register(app, needle::AddSizeCommand, needle::RunSizeCommand),
    Register(app, needle::AddDesignCommand, needle::RunDesignCommand),
    Register(app, needle::AddSimulateCommand, needle::RunSimulateCommand),
    Register(app, needle::AddOverspeedCommand, needle::RunOverspeedCommand),
    Register(app, needle::AddSynthCommand, needle::RunSynthCommand),
    Register(app, needle::AddProfileCommand, needle::RunProfileCommand),
    Register(app, needle::AddToleranceCommand, needle::RunToleranceCommand),
#if defined(NEEDLE_FIT_SERVE)
    Register(app, needle::AddServeCommand, needle::RunServeCommand),
    Register(app, needle::AddFitCommand, needle::RunFitCommand),
#else
    Elsewhere(app, "serve", needle::kServeCommandSummary, argv),
    Elsewhere(app, "fit", needle::kFitCommandSummary, argv),
#endif
  };
  // An unknown first word is named as such, with the commands there are (CLI11 would say only
  // "A subcommand is required").
  if (argc > 1 && argv[1][0] != '-') {
    bool known = false;
    std::string names;
    for (const Command& c : commands) {
      known = known || c.app->get_name() == argv[1];
      names += (names.empty() ? "" : ", ") + c.app->get_name();
    }
    if (!known) {
      std::cerr << "needle: unknown command '" << needle::EscapeControls(argv[1], false)
                << "'; expected one of " << names << " (see needle --help)\n";
      return 2;
    }
  }
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    std::cerr << "needle: " << needle::EscapeControls(e.what(), false) << " (see needle --help)\n";
    return 2;
  }
  const auto run = [&commands]() -> int {
    try {
      for (const Command& c : commands) {
        if (!c.app->parsed()) continue;
        const int status = c.run();
        // What was printed must have reached its place (a full disk: it was exit 0, silent).
        std::cout.flush();
        if (!std::cout) {
          std::cerr << "needle: standard output: the result could not be written (a full disk?)\n";
          return 2;
        }
        return status;
      }
    } catch (const needle::CaseError& e) {
      std::cerr << "needle: " << needle::EscapeControls(e.what(), false) << '\n';
      return 2;
    } catch (const std::invalid_argument& e) {
      std::cerr << "needle: " << needle::EscapeControls(e.what(), false) << '\n';
      return 2;
    } catch (const std::exception& e) {
      std::cerr << "needle: error: " << needle::EscapeControls(e.what(), false) << '\n';
      return 3;
    }
    return 0;
  };
  const int status = run();
  needle::RemoveEmptyMadeFolders();  // an --out folder made for a report never written
  return status;
}
