#pragma once
/// @file
/// The writer of the spring sizing (apps/study/spring_sizing_scene.h): the JSON object or the
/// text (the spring, its rules with margins, the check's limits table, the next best springs,
/// the front between mass and fatigue safety factor), and the sized case when asked. Exit
/// status 1 when no spring fits.

#include <optional>
#include <string>

#include "apps/case/bound_case.h"
#include "apps/report/command_output.h"
#include "apps/study/spring_sizing_scene.h"

namespace needle {

struct SizeWriting {
  bool json = false;  ///< the JSON object (else the text)
  /// The case file's text: when given and a spring fits, the sized case (SizedCaseText) too.
  std::optional<std::string> case_text;
};

CommandOutput WriteSize(const BoundCase& c, const SizeResult& result, const SizeWriting& writing);

}  // namespace needle
