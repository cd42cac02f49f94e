#pragma once
/// @file
/// The writers of the dynamics jobs (apps/study/dynamics_jobs.h): a run's JSON object, text
/// and series columns (exit status 1 when the needle lifts off), and the overspeed search's
/// (exit status 1 when n_dyn is at or below the rated speed), with its rows as columns.

#include "apps/report/command_output.h"
#include "apps/study/dynamics_jobs.h"

namespace needle {

CommandOutput WriteSimulate(const CaseRun& run, bool json);

CommandOutput WriteOverspeed(const CaseOverspeed& search, bool json);

}  // namespace needle
