#include "lib/engine_cycle.h"

#include "lib/name_table.h"

namespace needle {
namespace {

// The one name table.
constexpr NameRow<EngineCycle> kCycleNames[] = {
    {EngineCycle::kFourStroke, "four-stroke"},
    {EngineCycle::kTwoStroke, "two-stroke"},
};

}  // namespace

const char* EngineCycleName(EngineCycle cycle) { return NameOf(kCycleNames, cycle); }

std::optional<EngineCycle> ParseEngineCycle(const std::string& name) {
  return ValueOf(kCycleNames, name);
}

std::string EngineCycleList() { return NameChoice(kCycleNames); }

double CrankTurnsPerCycle(EngineCycle cycle) {
  return cycle == EngineCycle::kFourStroke ? 2.0 : 1.0;
}

}  // namespace needle
