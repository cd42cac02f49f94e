#pragma once
/// @file
/// Internal to the report floor: the parts of the check's HTML report (check_writers.h
/// CheckReportWriter) that are tables or figures of one section each, so that Finish reads as
/// the report's order of sections.

#include <string>

#include "apps/case/bound_case.h"
#include "apps/report/html_report.h"
#include "apps/study/check_scene.h"
#include "lib/lift_law.h"

namespace needle::check_report {

/// A row of a two-column table, its name escaped and its value HTML as given.
std::string Row(const std::string& name, const std::string& value);
/// "pass" or "FAIL", styled.
std::string Verdict(bool ok);

/// The scene: the case, speed, cycle, lift law and its choice, open lift, extremes (with bands).
std::string SceneTable(const BoundCase& c, const LiftLaw& law, const LiftLawChoice& choice,
                       double rpm, const KinematicsSummary& sum);
/// The spring check's table (result.spring set).
std::string SpringTable(const BoundCase& c, const CheckResult& result);
/// The cam profile's table (result.profile set).
std::string ProfileTable(const BoundCase& c, const CheckResult& result);
/// The limits table, every row (judged or not).
std::string LimitsTable(const CheckResult& result);
/// The surge figure (the contact force with coil masses against the massless spring's at the
/// rated speed) filled into the report's place `place`, or why it is not drawn.
void AddSurgeFigure(Report& report, size_t place, const LiftLaw& law, const CheckResult& result,
                    double rpm);
/// The overspeed sweep's figure and table (result.sweep set).
void AddOverspeed(Report& report, const CheckResult& result);
/// The resonance map's table and figure (result.harmonics and the spring's modes set).
void AddResonanceMap(Report& report, const BoundCase& c, const CheckResult& result, double rpm);

}  // namespace needle::check_report
