#include "usage_errors.hpp"

#include <iostream>
#include <vector>

#include "hba/core/did_you_mean.hpp"

namespace hba::cli {
namespace {

std::vector<std::string> commandNames(const CLI::App& app) {
  std::vector<std::string> names;
  for (const CLI::App* command : app.get_subcommands([](const CLI::App*) { return true; })) {
    names.push_back(command->get_name());
  }
  return names;
}

// Long flags ("--window") of `app`, with those of its parents (global flags).
std::vector<std::string> flagNames(const CLI::App* app) {
  std::vector<std::string> names;
  for (; app != nullptr; app = app->get_parent()) {
    for (const CLI::Option* option : app->get_options()) {
      for (const std::string& name : option->get_lnames()) names.push_back("--" + name);
    }
    for (const CLI::App* group :
         app->get_subcommands([](const CLI::App* a) { return a->get_name().empty(); })) {
      for (const CLI::Option* option : group->get_options()) {
        for (const std::string& name : option->get_lnames()) names.push_back("--" + name);
      }
    }
  }
  return names;
}

// The innermost subcommand the user chose, else the app.
const CLI::App* chosenCommand(const CLI::App& app) {
  for (const CLI::App* command : app.get_subcommands()) return command;
  return &app;
}

}  // namespace

std::optional<std::string> unknownCommand(const CLI::App& app, int argc, const char* const* argv) {
  // The first word that is neither a global option nor its value.
  const auto takesValue = [&](const std::string& word) {
    for (const CLI::Option* option : app.get_options()) {
      if (option->check_name(word) && option->get_items_expected_min() > 0) return true;
    }
    return false;
  };
  for (int i = 1; i < argc; ++i) {
    const std::string word = argv[i];
    if (!word.empty() && word.front() == '-') {
      if (takesValue(word)) ++i;
      continue;
    }
    const std::vector<std::string> names = commandNames(app);
    for (const std::string& name : names) {
      if (name == word) return std::nullopt;
    }
    std::string list;
    for (const std::string& name : names) list += (list.empty() ? "" : ", ") + name;
    return "'" + word + "' is not an hba command" + didYouMean(word, names) + "; the commands are " + list +
           " (hba --help)";
  }
  return std::nullopt;
}

int reportParseError(CLI::App& app, const CLI::ParseError& error, int argc, const char* const* argv) {
  if (error.get_exit_code() == static_cast<int>(CLI::ExitCodes::Success)) return app.exit(error);
  std::string message = error.what();
  if (dynamic_cast<const CLI::ExtrasError*>(&error) != nullptr) {
    const std::vector<std::string> flags = flagNames(chosenCommand(app));
    for (int i = 1; i < argc; ++i) {
      std::string word = argv[i];
      if (word.rfind("--", 0) != 0) continue;
      word = word.substr(0, word.find('='));
      bool known = false;
      for (const std::string& flag : flags) known = known || flag == word;
      if (!known) message += "\n'" + word + "' is not a flag here" + didYouMean(word, flags);
    }
  }
  std::cerr << "[error] " << message << "\nRun with --help for more information.\n";
  return kExitUsage;
}

}  // namespace hba::cli
