// The options several subcommands share are registered once (app/shared_options.h): on every
// command that has one, --max-triangles, --time and the environment options read alike, --spp
// and --time exclude each other, and --width / --height of an image say the same but for the
// command's default. A command that declared one of them again by hand would drift and fail here.
#include "tests/cli/test_cli.h"

#include <gtest/gtest.h>

#include <set>

#include <map>
#include <string>
#include <vector>

namespace pathlab::app {
namespace {

// "--time" -> (command, help text and type with its range) of every command that declares it.
std::map<std::string, std::vector<std::pair<std::string, std::string>>> optionsByName(TestCli& cli) {
  std::map<std::string, std::vector<std::pair<std::string, std::string>>> byName;
  for (CLI::App* sub : cli.subcommands())
    for (const CLI::Option* o : sub->get_options())
      byName[o->get_name()].emplace_back(sub->get_name(), o->get_description() + " | " + o->get_type_name());
  return byName;
}

TEST(SharedOptions, ReadAlikeOnEveryCommand) {
  TestCli cli;
  const auto byName = optionsByName(cli);
  for (const std::string name : {"--max-triangles", "--time", "--environment", "--environment-strength",
                                 "--light-sampler", "--no-default-light"}) {
    const auto& uses = byName.at(name);
    EXPECT_GE(uses.size(), 3u) << name;
    for (const auto& [command, text] : uses)
      if (name != "--time")
        EXPECT_EQ(text, uses.front().second) << name << " of " << command << " differs from " << uses.front().first;
      else  // the help says what the time is spent on; the range is one
        EXPECT_EQ(text.substr(text.find(" | ")), uses.front().second.substr(uses.front().second.find(" | ")))
            << name << " of " << command;
  }
}

TEST(SharedOptions, SppAndTimeExcludeEachOther) {
  TestCli cli;
  int commands = 0;
  for (CLI::App* sub : cli.subcommands()) {
    const CLI::Option* time = sub->get_option_no_throw("--time");
    if (!time) continue;
    ++commands;
    // --spp, and render's Metropolis synonym of it, --mutations-per-pixel.
    std::set<std::string> names;
    for (const CLI::Option* o : time->get_excludes()) names.insert(o->get_name());
    const std::set<std::string> expected = sub->get_name() == "render" ? std::set<std::string>{"--spp", "--mutations-per-pixel"}
                                                                        : std::set<std::string>{"--spp"};
    EXPECT_EQ(names, expected) << sub->get_name();
  }
  EXPECT_EQ(commands, 3);  // render, check, converge
}

TEST(SharedOptions, ImageSizeSaysTheSameButTheDefault) {
  TestCli cli;
  const auto byName = optionsByName(cli);
  int commands = 0;
  for (const std::string side : {"width", "height"})
    for (const auto& [command, text] : byName.at("--" + side)) {
      if (command == "view") continue;  // the window's size, not the image's
      ++commands;
      EXPECT_EQ(text.rfind("Image " + side + " in pixels (default: ", 0), 0u) << command << ": " << text;
      EXPECT_NE(text.find("the camera's shape, longest side "), std::string::npos) << command << ": " << text;
    }
  EXPECT_EQ(commands, 10);  // render, check, inspect, outliers, converge
}

}  // namespace
}  // namespace pathlab::app
