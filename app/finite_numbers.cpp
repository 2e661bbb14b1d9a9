// The finite check applied to every numeric option (app/finite_numbers.h).
#include "app/finite_numbers.h"

#include <fmt/core.h>

#include <cmath>
#include <cstdlib>
#include <limits>
#include <string_view>

namespace pathlab::app {

namespace {

// CLI11 names the type of an int, unsigned or floating-point option INT, UINT or FLOAT, followed
// by ":" and its validators' descriptions.
bool hasType(const CLI::Option& option, std::string_view name) {
  const std::string type = option.get_type_name();
  return type.starts_with(name) && (type.size() == name.size() || type[name.size()] == ':');
}

bool isNumber(const CLI::Option& option) {
  if (option.get_expected_max() == 0 || option.get_positional()) return false;  // flags take no value
  return hasType(option, "INT") || hasType(option, "UINT") || hasType(option, "FLOAT");
}

// No option needs a value beyond float's range, and most are stored as float, where it becomes inf.
// CLI11 reads "-1" into an unsigned option as 2^64 - 1: a negative value is refused there too.
CLI::Validator finiteNumber(bool isUnsigned) {
  return CLI::Validator(
      [isUnsigned](std::string& text) -> std::string {
        char* end = nullptr;
        const double v = std::strtod(text.c_str(), &end);
        if (end == text.c_str()) return {};  // not a number at all: CLI11's conversion names it
        if (!std::isfinite(v) || std::abs(v) > static_cast<double>(std::numeric_limits<float>::max()))
          return fmt::format("{} is not a finite number", text);
        if (isUnsigned && v < 0) return fmt::format("{} is negative", text);
        return {};
      },
      "", "finite");
}

}  // namespace

void requireFiniteNumbers(CLI::App& app) {
  for (CLI::Option* option : app.get_options())
    if (isNumber(*option)) option->check(finiteNumber(hasType(*option, "UINT")));
  for (CLI::App* sub : app.get_subcommands([](CLI::App*) { return true; })) requireFiniteNumbers(*sub);
}

}  // namespace pathlab::app
