#pragma once
// The command-line policy of every pmsim executable (pmsim, pmsim-render, pmsim-trace,
// pmsim-bench, pmsim-experiments, pmsim-ebsd-example), all parsed with CLI11: --help / -h prints
// the usage on stdout and exits 0; --version prints the version and exits 0; a usage error prints "<program>: <what is wrong>" and a pointer to --help on
// stderr and exits 2, the exit code of every bad input (scene, lens, key or value) in pmsim.
// Header-only, in core so that both the app/ executables and the ui library (ui/cli.cpp) share it
// without ui/ including app/ (app/pmsim includes ui/).
#include <CLI/CLI.hpp>

#include "core/base/version.h"

#include <algorithm>
#include <cstdlib>
#include <iostream>
#include <string>
#include <vector>

namespace pmsim::cli {

inline constexpr int kUsageErrorExitCode = 2;

// A usage error found after parsing (a value CLI11 accepted as text but the program does not):
// the same message and exit code as a parse error.
[[noreturn]] inline void usage_error(const std::string& program, const std::string& what) {
  std::cerr << program << ": " << what << "\n"
            << "Run '" << program << " --help' for usage.\n";
  std::exit(kUsageErrorExitCode);
}

// Parses argv with `app` (whose name is the program's); returns only when the command line is
// well-formed, else prints the help (exit 0) or the usage error (exit 2).
// --version prints "<program> <version>" (the CMake project version) on stdout and exits 0.
inline void parse_or_exit(CLI::App& app, int argc, char** argv) {
  app.set_version_flag("--version", app.get_name() + " " + pmsim_version(),
                       "print the program's name and pmsim's version, then exit");
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForVersion& e) {
    std::cout << e.what() << "\n";
    std::exit(0);
  } catch (const CLI::CallForHelp&) {
    std::cout << app.help();
    std::exit(0);
  } catch (const CLI::CallForAllHelp&) {
    std::cout << app.help("", CLI::AppFormatMode::All);
    std::exit(0);
  } catch (const CLI::ParseError& e) {
    // Unexpected arguments are named in command-line order (CLI11 2.1 lists positionals in
    // reverse) and before a missing required option: a misspelt option is often the required one.
    std::vector<std::string> unexpected = app.remaining();
    const bool name_unexpected = !unexpected.empty() && (dynamic_cast<const CLI::ExtrasError*>(&e) ||
                                                         dynamic_cast<const CLI::RequiredError*>(&e));
    std::reverse(unexpected.begin(), unexpected.end());  // ExtrasError joins them in reverse
    usage_error(app.get_name(), name_unexpected ? CLI::ExtrasError(unexpected).what() : e.what());
  }
}

// From here on, an option given several times keeps its last value (call before adding options).
inline void last_value_wins(CLI::App& app) {
  app.option_defaults()->multi_option_policy(CLI::MultiOptionPolicy::TakeLast);
}

// A repeatable option (--set key=value): one value per occurrence, every occurrence kept in
// command-line order; a following bare argument stays a positional (the scene file).
inline CLI::Option* add_repeatable(CLI::App& app, const std::string& name, std::vector<std::string>& values,
                                   const std::string& help) {
  return app.add_option(name, values, help)
      ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll)
      ->allow_extra_args(false);
}

}  // namespace pmsim::cli
