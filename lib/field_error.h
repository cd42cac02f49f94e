#pragma once
/// @file
/// The error of an options or parameters struct's Validate() (the one place its rules are
/// stated, as Ceres' Solver::Options::IsValid): the struct, the field, its value and the rule
/// it breaks. what() reads "Owner.field = value: rule"; a reader of an input file catches it and
/// names the field as its user wrote it (apps/case/section_reader.h, SectionReader::Validated).
/// FieldRules states a struct's rules.

#include <stdexcept>
#include <string>
#include <utility>

namespace needle {

struct FieldError : std::invalid_argument {
  /// `shown`: the value as what() prints it (std::to_string of the member's own type).
  FieldError(const std::string& owner, std::string field_name, const std::string& shown,
             double field_value, std::string broken_rule)
      : std::invalid_argument(owner + "." + field_name + " = " + shown + ": " + broken_rule),
        field(std::move(field_name)),
        value(field_value),
        rule(std::move(broken_rule)) {}

  std::string field;  ///< the member, as named in the struct ("contact_stiffness_N_m")
  double value;       ///< its value, in the member's unit (SI, or as its name says)
  std::string rule;   ///< what it must be ("must be positive", "must be in [0, 1]")
};

/// The rules of one struct's Validate(), naming the struct in what():
///     const FieldRules require{"SpringParameters"};
///     require(preload_N >= 0.0, "preload_N", preload_N, "must not be negative");
struct FieldRules {
  const char* owner;
  /// Throws FieldError unless `ok`: a real-valued member (what() shows std::to_string of it).
  void operator()(bool ok, const std::string& field, double value, const std::string& rule) const {
    if (!ok) throw FieldError(owner, field, std::to_string(value), value, rule);
  }
  /// The same for a whole-numbered member (a count, a budget).
  void operator()(bool ok, const std::string& field, long value, const std::string& rule) const {
    if (!ok)
      throw FieldError(owner, field, std::to_string(value), static_cast<double>(value), rule);
  }
};

}  // namespace needle
