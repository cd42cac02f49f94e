#include "apps/report/output_format.h"

#include <array>
#include <memory>
#include <utility>
#include <vector>

#include "apps/report/markdown_writer.h"
#include "lib/case_error.h"
#include "lib/name_table.h"

namespace needle {
namespace {

// The one name table of the formats.
constexpr NameRow<OutputFormat> kFormatNames[] = {
    {OutputFormat::kText, "text"},
    {OutputFormat::kJson, "json"},
    {OutputFormat::kMarkdown, "markdown"},
};

}  // namespace

const char* OutputFormatName(OutputFormat format) { return NameOf(kFormatNames, format); }

std::optional<OutputFormat> ParseOutputFormat(const std::string& name) {
  return ValueOf(kFormatNames, name);
}

void AddFormatOption(CLI::App* command, OutputFormat& format, bool& json) {
  // Every --format given, in order: --json (set by its flag) and each of them must agree.
  auto given = std::make_shared<std::vector<std::string>>();
  command
      ->add_option("--format", *given,
                   "output format: " + NameList(kFormatNames) + " (--json is --format json)")
      ->type_size(1)
      ->allow_extra_args(false)
      ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll)
      ->option_text("TEXT")
      ->check([](const std::string& name) {
        return ParseOutputFormat(name)
                   ? std::string()
                   : "expected " + NameChoice(kFormatNames, false) + ", got '" + name + "'";
      });
  command->parse_complete_callback([&format, &json, given] {
    std::string chosen_by = json ? "--json" : "";
    format = json ? OutputFormat::kJson : OutputFormat::kText;
    for (const std::string& name : *given) {
      const OutputFormat f = *ParseOutputFormat(name);
      if (!chosen_by.empty() && f != format)
        throw CLI::ValidationError(
            "--format", name + " conflicts with " + chosen_by + "; expected one output format");
      format = f;
      chosen_by = "--format " + name;
    }
    json = format != OutputFormat::kText;
  });
}

std::string FormatObject(const nlohmann::json& object, OutputFormat format) {
  if (format == OutputFormat::kMarkdown) return EscapeControls(MarkdownFromJson(object), true);
  return object.dump(2) + "\n";
}

}  // namespace needle
