#pragma once
/// @file
/// Reading an input file whole, refusing what is not one: a folder, a FIFO, a device, a file
/// larger than kMaxInputBytes. Errors are CaseError lines naming the path.

#include <string>

namespace needle {

/// The largest input file read, bytes (64 MiB: a lift table of a million rows fits).
constexpr long long kMaxInputBytes = 64LL << 20;

/// The whole file; `what` names it in messages ("case file", "lift table").
std::string ReadInputFile(const std::string& path, const std::string& what);

}  // namespace needle
