#include "cli_options.h"

#include <algorithm>
#include <iostream>

#include "cli_common.h"
#include "stitchsim/common/edit_distance.h"

namespace stitchsim::app {
namespace {

std::string UnitWord(LengthUnit unit) {
  switch (unit) {
    case LengthUnit::kInch:
      return "inches";
    case LengthUnit::kMetre:
      return "metres";
    case LengthUnit::kMillimetre:
      break;
  }
  return "millimetres";
}

// How the help names a length option's units: " (a bare number is in millimetres; ...)".
std::string UnitHelp(LengthUnit default_unit) {
  return " (a bare number is in " + UnitWord(default_unit) +
         "; a unit may follow: 2.5mm, 0.1in, 1m)";
}

double ReadLength(const std::string& name, const std::string& text, LengthUnit default_unit,
                  LengthRange range) {
  const std::optional<double> mm = ParseLengthMm(text, default_unit);
  if (!mm) {
    throw CLI::ValidationError(name, "'" + text +
                                         "' is not a length (a finite number with an optional "
                                         "unit: mm, in, m; a bare number is " +
                                         std::string(UnitName(default_unit)) + ")");
  }
  if ((range == LengthRange::kPositive && !(*mm > 0.0)) ||
      (range == LengthRange::kNonNegative && *mm < 0.0)) {
    throw CLI::ValidationError(
        name, "'" + text + "' must be " + (range == LengthRange::kPositive ? "> 0" : ">= 0"));
  }
  return *mm;
}

}  // namespace

CLI::Option* AddLengthOption(CLI::App* app, const std::string& name,
                             std::function<void(double)> store, LengthUnit default_unit,
                             LengthRange range, const std::string& description,
                             const std::string& default_text) {
  CLI::Option* option = app->add_option(
      name,
      [name, store = std::move(store), default_unit, range](const CLI::results_t& results) {
        store(ReadLength(name, results.front(), default_unit, range));
        return true;
      },
      description + UnitHelp(default_unit));
  option->type_name("LENGTH")->expected(1);
  if (!default_text.empty()) option->default_str(default_text);
  return option;
}

CLI::Option* AddLengthListOption(CLI::App* app, const std::string& name, std::size_t count,
                                 std::vector<double>& store_mm, LengthUnit default_unit,
                                 const std::string& description) {
  CLI::Option* option = app->add_option(
      name,
      [name, &store_mm, default_unit](const CLI::results_t& results) {
        store_mm.clear();
        for (const std::string& r : results) {
          store_mm.push_back(ReadLength(name, r, default_unit, LengthRange::kAny));
        }
        return true;
      },
      description + UnitHelp(default_unit));
  option->type_name("LENGTH")->delimiter(',')->expected(static_cast<int>(count));
  return option;
}

std::optional<std::string> NearestName(const std::string& word,
                                       const std::vector<std::string>& candidates) {
  std::optional<std::string> best;
  std::size_t best_distance = 3;  // more than 2 edits: not a typo
  for (const std::string& c : candidates) {
    std::size_t d = EditDistance(word, c);
    if (!word.empty() && c.rfind(word, 0) == 0) d = std::min<std::size_t>(d, 1);
    if (d < best_distance) {
      best_distance = d;
      best = c;
    }
  }
  return best;
}

std::optional<int> PreDispatch(const CLI::App& app, const std::vector<std::string>& args) {
  const CLI::App* level = &app;
  std::string path = app.get_name();
  for (std::size_t i = 0;; ++i) {
    const auto subcommands = level->get_subcommands([](const CLI::App*) { return true; });
    if (subcommands.empty() || level->get_require_subcommand_min() == 0) return std::nullopt;
    if (i == args.size()) {
      // A bare command at a level that needs a subcommand: its help, not an error.
      std::cout << level->help(path == app.get_name() ? "" : path.substr(0, path.rfind(' ')));
      return kExitOk;
    }
    if (!args[i].empty() && args[i].front() == '-') return std::nullopt;  // --help, --version
    std::vector<std::string> names;
    const CLI::App* next = nullptr;
    for (const CLI::App* s : subcommands) {
      names.push_back(s->get_name());
      if (s->get_name() == args[i]) next = s;
    }
    if (next == nullptr) {
      std::string message = "unknown command '" + args[i] + "' for '" + path + "'";
      if (const auto nearest = NearestName(args[i], names)) {
        message += "; did you mean '" + *nearest + "'?";
      } else {
        std::string list;
        for (const std::string& n : names) list += (list.empty() ? "" : ", ") + n;
        message += " (commands: " + list + ")";
      }
      PrintError("cli-unknown-command", message + " (see '" + path + " --help')");
      return kExitBadInput;
    }
    level = next;
    path += " " + next->get_name();
  }
}

}  // namespace stitchsim::app
