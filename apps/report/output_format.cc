#include "apps/report/output_format.h"

#include <array>
#include <utility>

#include "apps/report/markdown_writer.h"
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
  const std::string names = NameList(kFormatNames);
  command
      ->add_option_function<std::string>(
          "--format",
          [&format, &json](const std::string& name) {
            format = *ParseOutputFormat(name);
            json = format != OutputFormat::kText;
          },
          "output format: " + names + " (--json is --format json)")
      ->check([](const std::string& name) {
        return ParseOutputFormat(name) ? std::string()
                                       : "expected text, json or markdown, got '" + name + "'";
      });
  command->parse_complete_callback([&format, &json] {
    if (json && format == OutputFormat::kText) format = OutputFormat::kJson;
  });
}

std::string FormatObject(const nlohmann::json& object, OutputFormat format) {
  if (format == OutputFormat::kMarkdown) return MarkdownFromJson(object);
  return object.dump(2) + "\n";
}

}  // namespace needle
