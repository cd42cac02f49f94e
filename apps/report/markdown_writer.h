#pragma once
/// @file
/// The Markdown writer (`--format markdown`): a command's JSON object as Markdown. Scalars of
/// an object form a two-column table (key, value); an array of objects forms a table with one
/// column per key; an array of numbers or strings is written as one line; a nested object is a
/// heading of its own, one level down. Numbers are written as the JSON writer writes them (the
/// shortest text that reads back the same double), so nothing is rounded.

#include <nlohmann/json.hpp>
#include <string>

namespace needle {

/// The object as Markdown, ending with a newline.
std::string MarkdownFromJson(const nlohmann::json& object);

}  // namespace needle
