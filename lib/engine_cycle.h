#pragma once
/// @file
/// The engine's working cycle and the one crank-to-cam rule: the fuel cam turns once per
/// working cycle, so at half the crank speed in a four-stroke engine (one cycle is two crank
/// turns) and at the crank speed in a two-stroke engine,
///   ω_cam = ω_crank / CrankTurnsPerCycle(cycle).

#include <optional>
#include <string>

namespace needle {

/// The engine's working cycle.
enum class EngineCycle {
  kFourStroke,  ///< "four-stroke": a cycle is two crank turns; the cam turns at half speed
  kTwoStroke,   ///< "two-stroke": a cycle is one crank turn; the cam turns with the crank
};

/// The cycle's name in a case file ("four-stroke", "two-stroke").
const char* EngineCycleName(EngineCycle cycle);
/// The cycle of a name, or nullopt.
std::optional<EngineCycle> ParseEngineCycle(const std::string& name);
/// The names, for messages: "\"four-stroke\" or \"two-stroke\"".
std::string EngineCycleList();

/// Crank turns per working cycle (and per cam turn): 2 four-stroke, 1 two-stroke.
double CrankTurnsPerCycle(EngineCycle cycle);

}  // namespace needle
