#pragma once
/// @file
/// Plausible ranges of the physical inputs: every physical key of a case file and every
/// numeric command-line option has one, wide enough for any real engine (a marine two-stroke
/// at 60 rpm to a small high-speed engine) and narrow enough that a slip of unit or sign
/// (a stiffness of 5e-8 N/m, a mass of 1e-12 kg, a lift of 1e300 mm) is refused before it runs
/// for minutes or prints numbers 120 digits long. A value outside is one line naming the file
/// and key (or the option), the value and the range; exit 2.
///
/// This file is the one table of ranges. A case file's key names its range in its declaration
/// (apps/case/case_keys.h), which SectionReader::Finish checks as it finishes a section; the
/// command-line options are listed in kRangedOptions and check theirs with RangeValidator
/// (apps/cli/cli_checks.h). docs/ranges.md is generated from both (PlausibleRangesMarkdown) and
/// a test holds the two equal.

#include <optional>
#include <string>

#include "dynamics/simulation.h"
#include "dynamics/solver/integrator.h"

namespace needle {

/// One plausible range, closed: [lo, hi] in SI (speeds in rpm, as everywhere).
struct PlausibleRange {
  const char* quantity;  ///< what it is, for the docs ("moving mass")
  double lo, hi;         ///< the range, SI
  const char* unit;      ///< the unit shown in messages and docs ("kg", "mm")
  double unit_si;        ///< one shown unit in SI (1 mm = 1e-3 m)
  const char* reason;    ///< why these ends, short
};

/// Crank speed, rpm: [engine] speed, the sweep's ends, --rpm/--from/--to.
inline constexpr PlausibleRange kCrankSpeedRange{
    "crank speed",
    1.0,
    5e4,
    "rpm",
    1.0,
    "a large marine two-stroke turns at 60-100 rpm, a small high-speed engine at up to 20000; "
    "room for an overspeed sweep to 2.5 times that"};
/// The moving mass (needle, disks, the spring's third), kg.
inline constexpr PlausibleRange kMovingMassRange{
    "moving mass",
    1e-3,
    1e3,
    "kg",
    1.0,
    "a small injector's needle weighs grams, Basu's needle and disks 11.5 kg, a marine exhaust "
    "valve's train some 100 kg"};
/// The largest lift and each entry of a lift table (a table's entries: the upper end only; a
/// negative reading is the lift law's to judge, within its noise).
inline constexpr PlausibleRange kLiftRange{
    "lift",
    1e-6,
    0.2,
    "mm",
    1e-3,
    "a needle lifts tenths of a millimetre to a few millimetres (Basu: 3.67 mm), a marine exhaust "
    "valve about 100 mm"};
/// The rounding and the noise of a lift table's readings, m.
inline constexpr PlausibleRange kReadingRange{
    "lift reading's rounding or noise",
    1e-9,
    1e-3,
    "mm",
    1e-3,
    "Basu's table is rounded to 0.01 mm; a reading coarser than 1 mm is no lift table"};
/// The needle's (seat) diameter, m: the gas load's area.
inline constexpr PlausibleRange kNeedleDiameterRange{
    "needle diameter",
    5e-4,
    0.5,
    "mm",
    1e-3,
    "an injector's needle is 1-4 mm, Basu's 31 mm, a marine exhaust valve's disc some 400 mm"};
/// The gas load on the closed needle, N.
inline constexpr PlausibleRange kGasForceRange{
    "gas force", 0.0,
    1e7,         "N",
    1.0,         "not negative (it presses the needle shut); 250 bar on a 500 mm disc is 4.9 MN"};
/// The combustion pressure on the needle, Pa.
inline constexpr PlausibleRange kCombustionPressureRange{
    "combustion pressure",
    0.0,
    5e7,
    "bar",
    1e5,
    "the peak cylinder pressure of a modern diesel is about 250 bar"};
/// The spring's installed preload, N.
inline constexpr PlausibleRange kPreloadRange{
    "spring preload",
    0.0,
    1e6,
    "N",
    1.0,
    "Basu's 790 kgf is 7.7 kN; a marine exhaust valve's air spring holds some 100 kN"};
/// The spring's rate, N/m (shown in N/mm).
inline constexpr PlausibleRange kSpringRateRange{
    "spring rate", 0.0, 1e8,
    "N/mm",        1e3, "valve springs are 10-1000 N/mm; 0 is a constant force (an air spring)"};
/// Helical geometry: wire, mean coil diameter, free length, m.
inline constexpr PlausibleRange kWireRange{
    "wire diameter", 1e-4, 0.1, "mm", 1e-3, "EN 13906-1 springs are of 0.1-100 mm wire"};
inline constexpr PlausibleRange kCoilRange{
    "mean coil diameter",
    5e-4,
    2.0,
    "mm",
    1e-3,
    "the index D/d of 4-20 on a 0.1-100 mm wire; checked again by that index"};
inline constexpr PlausibleRange kFreeLengthRange{
    "free length", 1e-3, 5.0, "mm", 1e-3, "a valve spring is millimetres to a metre long"};
inline constexpr PlausibleRange kActiveCoilsRange{
    "active coils", 2.0, 200.0, "", 1.0, "EN 13906-1 asks for at least 2; no valve spring has 200"};
/// Spring material: shear modulus, tensile strength, density, Pa and kg/m³.
inline constexpr PlausibleRange kShearModulusRange{
    "shear modulus", 1e10, 1.5e11, "GPa", 1e9, "bronze about 40 GPa, titanium 42, steel 78-81"};
inline constexpr PlausibleRange kTensileRange{
    "tensile strength",
    1e8,
    5e9,
    "MPa",
    1e6,
    "spring wire is 1000-2500 MPa (EN 10270); a copper alloy some 500"};
inline constexpr PlausibleRange kDensityRange{
    "density", 1e3, 2e4, "kg/m3", 1.0, "titanium 4500, steel 7850, tungsten 19300 kg/m3"};
/// The design factors of the spring check: S and f, plain numbers.
inline constexpr PlausibleRange kSafetyFactorRange{
    "safety factor", 1.0, 10.0, "", 1.0, "Basu's S is 1.5; a factor beyond 10 is a typo"};
inline constexpr PlausibleRange kOverspeedFactorRange{
    "overspeed factor", 1.0, 5.0, "", 1.0, "the overspeed to check is 1.2 times the rated speed"};
/// Contact stiffness (cam–roller, seat, coil clash), N/m.
inline constexpr PlausibleRange kContactStiffnessRange{
    "contact stiffness",
    1e5,
    1e11,
    "N/m",
    1.0,
    "a steel line contact is 1e8-1e10 N/m; below 1e5 the preload would press the needle "
    "millimetres into its seat, above 1e11 a run takes minutes for nothing (and a sign slip "
    "such as 5e-8 is caught)"};
/// Damping ratios of the contacts and of the spring's surge, plain numbers.
inline constexpr PlausibleRange kDampingRatioRange{
    "damping ratio",
    0.0,
    1.0,
    "",
    1.0,
    "contacts are damped a few per cent; critical (1) is the most a contact law means "
    "(1e6 ran for minutes)"};
/// Newton's restitution of the rigid contacts.
inline constexpr PlausibleRange kRestitutionRange{
    "restitution", 0.0, 1.0, "", 1.0, "Newton's coefficient: 0 plastic, 1 elastic"};
/// The roller's play, m.
inline constexpr PlausibleRange kPlayRange{
    "roller play", 0.0, 0.01, "mm", 1e-3, "Basu gives 1 mm for a large engine"};
/// A linear ramp's length, rad (shown in degrees).
inline constexpr PlausibleRange kRampRange{
    "ramp length", 1.7453292519943295e-3, 1.5707963267948966,
    "deg",         1.7453292519943295e-2, "Basu's ramps take about 10 degrees of crank"};
/// The cam disk and its follower ([profile], the synthesis file's [checks]): radii, a flat
/// face's half-width, the least radius asked for, a roller's contact length, m.
inline constexpr PlausibleRange kProfileLengthRange{
    "cam profile length",
    0.0,
    2.0,
    "mm",
    1e-3,
    "Basu's cam has a 230 mm base circle and a 45 mm roller, the MATEC cam a 10 mm one; a large "
    "marine two-stroke's cam disk is under a metre across"};
/// The follower's offset from the cam's centre line, m (either side).
inline constexpr PlausibleRange kOffsetRange{
    "follower offset", -2.0, 2.0, "mm", 1e-3, "within the largest cam disk's radius, either side"};
/// [limits]: the largest seating and lash-impact speeds allowed, m/s.
inline constexpr PlausibleRange kImpactSpeedLimitRange{
    "impact speed limit",
    1e-3,
    20.0,
    "m/s",
    1.0,
    "valve trains hold seating speeds to about 0.3-1 m/s (0.5 m/s is needle's default); a limit "
    "of 20 m/s passes any impact"};
/// [limits]: the allowed Hertz stress of the cam-roller contact, Pa.
inline constexpr PlausibleRange kHertzStressLimitRange{
    "Hertz stress limit",
    2e8,
    5e9,
    "MPa",
    1e6,
    "hardened steel cams are allowed some 1000-2000 MPa of line-contact stress; no material "
    "takes 5000"};
/// [limits]: the cam and roller's elastic modulus, Pa.
inline constexpr PlausibleRange kElasticModulusRange{
    "elastic modulus",
    1e10,
    7e11,
    "GPa",
    1e9,
    "cast iron about 100-170 GPa, steel 206, tungsten carbide about 600"};
/// [limits]: the least gap between the spring's coils, m.
inline constexpr PlausibleRange kCoilGapRange{
    "coil gap", 0.0, 0.1, "mm", 1e-3, "tenths of a millimetre to a few millimetres"};
/// [tolerance]: a length's σ (the lift table's points, the play), m.
inline constexpr PlausibleRange kLengthSigmaRange{
    "tolerance σ of a length",
    0.0,
    1e-3,
    "mm",
    1e-3,
    "Basu's cam is ground to 0.01 mm; a σ of a millimetre is no tolerance"};
/// [tolerance]: a relative σ (mass, preload, rate, stiffness, speed), a fraction.
inline constexpr PlausibleRange kRelativeSigmaRange{
    "tolerance σ of a quantity", 0.0, 0.5, "%", 1e-2, "a σ of half the value is no tolerance"};
/// [tolerance]: the correlation length of the profile's error, rad.
inline constexpr PlausibleRange kCorrelationRange{
    "correlation length",  0.0,
    6.283185307179586,     "deg",
    1.7453292519943295e-2, "at most one revolution of the cam"};

/// The preload per needle area, P₀/(π d²/4), Pa: the pressure the spring holds the needle shut
/// with, an injector's opening pressure (checked where [needle] gives the diameter).
inline constexpr PlausibleRange kPreloadPressureRange{
    "preload per needle area",
    0.0,
    1e8,
    "bar",
    1e5,
    "injectors open at about 100-400 bar (Bosch, Diesel-Engine Management, 2005: 110-300 bar; "
    "Basu's needle 103 bar); 1000 bar is a preload in kgf typed for N, or a diameter in cm "
    "typed for mm"};

/// `needle tolerance --seed`: a 64-bit unsigned integer.
inline constexpr PlausibleRange kSeedRange{
    "seed", 0.0, 18446744073709551615.0,
    "",     1.0, "the generator's seed is 64 bits; a longer number would be cut silently"};
/// `--step` of the kinematics table, crank degrees.
inline constexpr PlausibleRange kTableStepRange{
    "table spacing", 1e-3, 90.0, "deg", 1.0, "at most 100000 rows; at least 4 rows on a cycle"};
/// `--step-rpm` of the overspeed scan, rpm.
inline constexpr PlausibleRange kSpeedStepRange{
    "speed step", 1e-3, 1e6, "rpm", 1.0, "any step; the sweep's budget bounds the runs"};
/// `--noise-mm` of a bare CSV table, mm (as typed).
inline constexpr PlausibleRange kNoiseOptionRange{
    "noise of a bare table", 1e-9, 10.0, "mm", 1.0, "a reading's σ, far below the lift"};

/// The counts and the tolerance of the options (not physical, listed so that every numeric
/// option has its range here): the relative tolerance, the revolutions run, the tolerance
/// study's samples and first sample, the threads.
inline constexpr PlausibleRange kRtolRange{"relative tolerance",
                                           kMinRtol,
                                           kMaxRtol,
                                           "",
                                           1.0,
                                           "the integrators' range (dynamics/solver/integrator.h)"};
inline constexpr PlausibleRange kCyclesRange{"cam revolutions",
                                             1.0,
                                             kMaxCycles,
                                             "",
                                             1.0,
                                             "a periodic state repeats within a few revolutions"};
inline constexpr PlausibleRange kSamplesRange{
    "tolerance samples", 1.0, 1e6, "", 1.0, "1e6 samples give a failure probability to 1e-5"};
inline constexpr PlausibleRange kFirstSampleRange{
    "first sample", 0.0, 1e9, "", 1.0, "a shard's start inside a study of at most 1e9 samples"};
inline constexpr PlausibleRange kThreadsRange{
    "threads", 0.0, 4096.0, "", 1.0, "0 is all cores; no machine has more than 4096"};

/// A command-line option's range (a case file's keys have theirs in their declarations,
/// apps/case/case_keys.h).
struct RangedOption {
  const char* name;  ///< the option, "--rpm"
  const PlausibleRange* range;
};

inline constexpr RangedOption kRangedOptions[] = {
    {"--rpm", &kCrankSpeedRange},
    {"--from", &kCrankSpeedRange},
    {"--to", &kCrankSpeedRange},
    {"--seed", &kSeedRange},
    {"--step", &kTableStepRange},
    {"--step-rpm", &kSpeedStepRange},
    {"--noise-mm", &kNoiseOptionRange},
    {"--rtol", &kRtolRange},
    {"--cycles", &kCyclesRange},
    {"--samples", &kSamplesRange},
    {"--first-sample", &kFirstSampleRange},
    {"--threads", &kThreadsRange},
};

/// A range of a quantity formed from several keys, checked once they are all read.
struct DerivedRange {
  const char* keys;  ///< how it is formed, for the docs
  const PlausibleRange* range;
};

inline constexpr DerivedRange kDerivedRanges[] = {
    {"`[spring] preload` / (π/4 · `[needle] diameter`²)", &kPreloadPressureRange},
};

/// "[lo, hi] unit" in the shown unit ("[0.001, 1000] kg").
std::string RangeText(const PlausibleRange& r);

/// A value in SI shown in the range's unit ("1e-12 kg").
std::string ShownValue(const PlausibleRange& r, double si);

/// Why a value above the range is refused: "300 mm is above the plausible range's end 200 mm
/// (docs/ranges.md)".
std::string AboveRangeEnd(const PlausibleRange& r, double si);

/// The table of docs/ranges.md: one row per range, with the keys and options it applies to.
std::string PlausibleRangesMarkdown();

/// "expected WHAT in [lo, hi], got V": the rule of every option range, stated once (the command
/// line's validators, apps/cli/cli_checks.h, and the jobs' own checks below).
std::string RangeRule(double lo, double hi, const std::string& what, const std::string& v);

/// The same rule where no parser stood in front (a job called from Python): throws CaseError
/// "OPTION: expected WHAT in [lo, hi], got V" when `v` is given and outside [lo, hi] or not finite.
void RequireIn(const std::string& option, const std::optional<double>& v, double lo, double hi,
               const std::string& what);
/// A crank speed option (`--rpm`, `--from`, `--to`): RequireIn over kCrankSpeedRange.
void RequireSpeed(const std::optional<double>& rpm, const std::string& option = "--rpm");

}  // namespace needle
