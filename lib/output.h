#pragma once
/// @file
/// Output at the edges: files are written atomically (a temporary file beside the target,
/// flushed, then renamed over it), so an interrupted or failed run leaves either the old
/// file or the complete new one, never half a file.

#include <string>

namespace needle {

/// Writes `content` to `path` atomically. Throws std::runtime_error naming the path and
/// the failing system call.
void WriteFileAtomically(const std::string& path, const std::string& content);

/// `value` with `decimals` digits after the point ("-0.000" is printed as "0.000").
std::string Fixed(double value, int decimals);

}  // namespace needle
