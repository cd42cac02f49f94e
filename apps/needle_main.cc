// The `needle` command: a thin layer over the libraries. Exit status: 0 success,
// 1 a check that fails, 2 bad input (case file, options) — one line on stderr.
#include <CLI/CLI.hpp>
#include <iostream>

#include "apps/cam_command.h"
#include "apps/check_command.h"
#include "apps/dynamics_command.h"
#include "apps/kinematics_command.h"
#include "apps/spring_command.h"
#include "lib/case_file.h"

int main(int argc, char** argv) {
  CLI::App app{"needle: cam-driven needle valves — kinematics, spring sizing, dynamics"};
  app.require_subcommand(1);
  needle::CheckCommandOptions check;
  CLI::App* check_cmd = needle::AddCheckCommand(app, check);
  needle::KinematicsCommandOptions kinematics;
  CLI::App* kinematics_cmd = needle::AddKinematicsCommand(app, kinematics);
  needle::SpringCommandOptions spring;
  CLI::App* spring_cmd = needle::AddSpringCommand(app, spring);
  needle::DesignCommandOptions design;
  CLI::App* design_cmd = needle::AddDesignCommand(app, design);
  needle::SimulateCommandOptions simulate;
  CLI::App* simulate_cmd = needle::AddSimulateCommand(app, simulate);
  needle::OverspeedCommandOptions overspeed;
  CLI::App* overspeed_cmd = needle::AddOverspeedCommand(app, overspeed);
  needle::SynthCommandOptions synth;
  CLI::App* synth_cmd = needle::AddSynthCommand(app, synth);
  needle::ProfileCommandOptions profile;
  CLI::App* profile_cmd = needle::AddProfileCommand(app, profile);
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    std::cerr << "needle: " << e.what() << " (see needle --help)\n";
    return 2;
  }
  try {
    if (check_cmd->parsed()) return needle::RunCheckCommand(check);
    if (kinematics_cmd->parsed()) return needle::RunKinematicsCommand(kinematics);
    if (spring_cmd->parsed()) return needle::RunSpringCommand(spring);
    if (design_cmd->parsed()) return needle::RunDesignCommand(design);
    if (simulate_cmd->parsed()) return needle::RunSimulateCommand(simulate);
    if (overspeed_cmd->parsed()) return needle::RunOverspeedCommand(overspeed);
    if (synth_cmd->parsed()) return needle::RunSynthCommand(synth);
    if (profile_cmd->parsed()) return needle::RunProfileCommand(profile);
  } catch (const needle::CaseError& e) {
    std::cerr << "needle: " << e.what() << '\n';
    return 2;
  } catch (const std::invalid_argument& e) {
    std::cerr << "needle: " << e.what() << '\n';
    return 2;
  } catch (const std::exception& e) {
    std::cerr << "needle: error: " << e.what() << '\n';
    return 3;
  }
  return 0;
}
