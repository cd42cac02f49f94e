#pragma once
/// @file
/// The plain values of a case's sections that the bound case (apps/case/bound_case.h) carries
/// as read: [engine], [paper], [train], [overspeed], [tolerance], [profile], [limits]. The file
/// model (case_file.h) reads them; the study and report floors read them through BoundCase.
/// Each field's unit is in its name; every field has its default.

#include <optional>
#include <string>
#include <vector>

#include "apps/case/sizing_section.h"
#include "dynamics/model/needle_train.h"
#include "lib/engine_cycle.h"
#include "lib/follower.h"
#include "spring/spring_parameters.h"

namespace needle {

struct EngineSection {
  double speed_rpm = 0.0;                        ///< rated crank speed, rpm, > 0
  EngineCycle cycle = EngineCycle::kFourStroke;  ///< the crank-to-cam rule (lib/engine_cycle.h)
};

struct PaperSection {
  std::vector<double> crank_rad;     ///< angles of the published velocities, rad
  std::vector<double> velocity_m_s;  ///< published velocity magnitudes, m/s
  std::optional<double> max_acceleration_m_s2;
  std::optional<double> inertia_force_N;
  std::optional<double> mean_lift_m;
  std::optional<double> spring_preload_N;  ///< the preload Basu's formula gave
};

/// [train]: contacts and roller play of the dynamic model (docs/model.md §3–4): the contact
/// laws' own parameters (dynamics/model/needle_train.h), read straight into them, and the
/// roller's play on its ramps (the cam input's).
struct TrainSection : ContactParameters {
  double play_m = 0.0;       ///< roller play δ, ≥ 0
  bool linear_ramp = false;  ///< `ramp_deg` given (else tangent ramps)
  double ramp_rad = 0.0;     ///< ramp length when linear
};

/// [overspeed]: the lift-off sweep.
struct OverspeedSection {
  std::optional<double> from_rpm, to_rpm;
  bool steady_state = false;  ///< judge lift-off on the steady revolutions (needs cycles ≥ 2)
};

/// [tolerance]: how the inputs scatter in a tolerance study (`needle tolerance`): each is one
/// standard deviation of a normal scatter about the nominal value; 0 leaves the input alone.
struct ToleranceSection {
  /// lift_mm: the error of each lift-table point inside the open lift, m (default 0.01 mm:
  /// Basu, NACA TM 477, "the cam is made to 0.01 mm"); [0, 1 mm].
  double lift_sigma_m = 1e-5;
  /// lift_correlation_deg: correlation length of that error along the crank angle, rad (a
  /// Gaussian kernel exp(−Δθ²/2ℓ²), tapering to zero where the lift is zero); 0: independent
  /// points; [0, 360°]. Not given: a quarter of the open lift (EffectiveTolerance), a smooth
  /// grinding error.
  double lift_correlation_rad = 0.0;
  bool lift_correlation_given = false;  ///< `lift_correlation_deg` stated
  bool given = false;                   ///< the case has the section
  double mass_fraction = 0.0;           ///< mass_percent: the moving mass, [0, 50 %]
  double preload_fraction = 0.0;        ///< preload_percent: P₀, [0, 50 %]
  double rate_fraction = 0.0;           ///< rate_percent: k (G, when k comes from the geometry)
  double stiffness_fraction = 0.0;      ///< stiffness_percent: k_c and k_s, [0, 50 %]
  double play_sigma_m = 0.0;            ///< play_mm: the roller play, m (a play below 0 is 0)
  double speed_fraction = 0.0;          ///< speed_percent: the rated speed, [0, 50 %]
};

/// [profile]: the cam that drives the needle, for `needle profile`.
struct ProfileSection {
  /// `follower` (roller, flat or curved), base_radius, roller_radius or face_radius,
  /// face_half_width, offset, lever_ratio: the library's geometry, validated as read.
  FollowerGeometry follower;
  int points = 720;  ///< points over one cam revolution
};

/// [limits]: the design limits `needle check` judges, one row each (docs/springs.md "The limits
/// table" gives the source of every default).
struct LimitsSection {
  /// Largest landing speed of the needle on its seat, m/s: the top of Blair's optimum ramp
  /// velocity range, 1.0–1.5 m/s at the highest operating speed.
  double seating_velocity_m_s = 1.5;
  /// Largest speed at which the cam strikes the roller as it takes up the play (the lash
  /// impact), m/s: the opening ramp's velocity, the same Blair range as the seating velocity.
  double lash_impact_velocity_m_s = 1.5;
  /// Largest secondary opening after closing (the needle seats, rebounds and reopens: a
  /// secondary injection), as a fraction of the largest lift.
  double secondary_opening_fraction = 0.01;
  /// Least cam contact force while the cam lifts the needle, as a fraction of the static load
  /// holding it on the cam there (P₀ + k y − F_g); absent: 1 − 1/f², f = [spring]
  /// overspeed_factor (the share the inertia of f·n would take, so at least 30.6 % at f = 1.2).
  std::optional<double> min_contact_force_fraction;
  /// n_dyn at least (1 + this)·f·n (0: the model contract's passing check, n_dyn > f·n).
  double separation_margin_fraction = 0.0;
  /// Largest Hertz stress cam–roller, Pa: ISO 6336-5's σ_Hlim of case-hardened steel, MQ.
  double hertz_stress_Pa = 1500e6;
  std::optional<double> contact_length_m;  ///< the roller's width in contact (needs [profile])
  double elastic_modulus_Pa = 210e9;       ///< E of cam and roller (steel)
  double poisson = 0.3;                    ///< ν (steel)
  /// Least fatigue safety factor of the spring by its criterion ([spring] fatigue_criterion):
  /// the design factor of Shigley's fatigue-design example (§10-12), 1.5.
  double fatigue_safety_factor = 1.5;
  /// Least coil gap at full lift, m; absent: EN 13906-1's S_a of the spring.
  std::optional<double> coil_gap_m;
  /// A cam harmonic is significant when its acceleration reaches this fraction of the largest
  /// (the resonance map's orders; information, no verdict).
  double harmonic_threshold = 0.05;
};

/// The sections a case carries as read, from the file model (case_file.h, `Case`) into the
/// bound case (bound_case.h, `BoundCase`) whole: all but [lift] and [solver], which are bound.
struct CaseSections {
  std::string path;   ///< the file it came from, for messages
  std::string title;  ///< optional one-line description
  EngineSection engine;
  std::optional<NeedleParameters> needle;  ///< [needle]: the spring module's parameters
  std::optional<SpringParameters> spring;  ///< [spring]: likewise
  std::optional<TrainSection> train;
  std::optional<OverspeedSection> overspeed;
  std::optional<ProfileSection> profile;
  std::optional<ToleranceSection> tolerance;
  std::optional<PaperSection> paper;
  LimitsSection limits;                 ///< [limits], defaults when absent
  std::optional<SizingSection> sizing;  ///< [sizing] (`needle size`, sizing_section.h)
};

}  // namespace needle
