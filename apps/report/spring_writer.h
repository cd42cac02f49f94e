#pragma once
/// @file
/// The writers of the spring jobs (apps/study/spring_job.h): the spring check's JSON object and
/// text (exit status 1 when it fails), and the design chain's, with the case `design --case`
/// writes (apps/case/case_writer.h) when `case_out` names its file.

#include <optional>
#include <string>

#include "apps/report/command_output.h"
#include "apps/study/spring_job.h"

namespace needle {

CommandOutput WriteSpring(const CaseSpringCheck& spring, bool json);

CommandOutput WriteDesign(const DesignInputs& in, const DesignResult& r, bool json,
                          const std::optional<std::string>& case_out);

}  // namespace needle
