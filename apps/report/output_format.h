#pragma once
/// @file
/// The output formats of every command, in one table: `--format text|json|markdown` is added
/// to each command once, by the `needle` binary (needle_main.cc), and `--json` stays the
/// shorthand of `--format json`. The JSON and Markdown formats are both written from the
/// command's JSON object (the field tables as the commands build them), so a format added here
/// and in its writer reaches every command.

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>

namespace needle {

/// How a command prints its result.
enum class OutputFormat {
  kText,      ///< the command's own text report
  kJson,      ///< one JSON object
  kMarkdown,  ///< the JSON object as Markdown tables (markdown_writer.h)
};

/// The format's name as the option takes it ("text", "json", "markdown").
const char* OutputFormatName(OutputFormat format);
/// The format of a name, or nullopt.
std::optional<OutputFormat> ParseOutputFormat(const std::string& name);

/// Adds `--format` to a command; `json` is the command's --json flag: after parsing, a
/// command asked for JSON or Markdown has `json` set (it builds its JSON object) and `format`
/// says which of the two to print.
void AddFormatOption(CLI::App* command, OutputFormat& format, bool& json);

/// The command's JSON object printed in `format` (kJson or kMarkdown), with its final newline.
std::string FormatObject(const nlohmann::json& object, OutputFormat format);

}  // namespace needle
