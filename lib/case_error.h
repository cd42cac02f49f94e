#pragma once
/// @file
/// The one error type of bad input: what() is one line naming the file (or the option), the
/// key and what was expected. Commands turn it into exit status 2.

#include <stdexcept>

namespace needle {

/// A case-file or option problem; what() is one line naming the file, the key and what was
/// expected.
class CaseError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

}  // namespace needle
