#pragma once
/// @file
/// The writers of the cam jobs: a synthesized law (apps/study/synthesis_scene.h) — its JSON
/// object, text, CSV (cam_deg, S and its derivatives) and the case it makes; exit status 1 when
/// a check fails — and a case's cam profile (apps/study/profile_job.h) — its JSON object, text
/// and the CAD coordinates as CSV; exit status 1 when it undercuts or runs off the face.

#include "apps/case/bound_case.h"
#include "apps/report/command_output.h"
#include "apps/study/profile_job.h"
#include "apps/study/synthesis_scene.h"

namespace needle {

struct CamWriting {
  bool json = false;       ///< the JSON object (else the text)
  bool csv = false;        ///< the CSV file's content too
  bool case_file = false;  ///< synth: the case file's text too (SynthesizedCaseText)
};

CommandOutput WriteSynth(const SynthesisFile& spec, const SynthesisResult& result,
                         const CamWriting& writing);

CommandOutput WriteProfile(const CaseCamProfile& profile, const CamWriting& writing);

}  // namespace needle
