#pragma once
// The shared shape of the stage executables (header-only; needs CLI11): parse with CLI11,
// run, and turn every demcal::Error into one "program: error: ..." line and
// exit code 2 (usage and input errors); every program has --version and
// lists its exit codes under --help.
#include <CLI/CLI.hpp>

#include <fstream>
#include <functional>
#include <iostream>
#include <string>

#include "demcal/core/error.hpp"
#include "demcal/core/log.hpp"
#include "demcal/core/table.hpp"
#include "demcal/core/version.hpp"

namespace demcal::cli {

// "demcal-dem 0.1.0 (commit 1a2b3c4d5e6f)".
inline std::string version_line(const std::string& program) {
  return program + " " + version() + " (commit " + commit() + ")";
}

// `more_exit_codes`: the program's codes beyond 0, 1 and 2 ("4 a point failed ..."),
// listed in --help with the common ones.
inline int run_main(CLI::App& app, int argc, char** argv, const std::function<int()>& body,
                    const std::string& more_exit_codes = "") {
  app.set_version_flag("--version", version_line(app.get_name()), "print the version and the commit built, then exit");
  const std::string codes = "Exit codes: 0 done; 2 bad input or usage (one line naming the file and field); " +
                            (more_exit_codes.empty() ? std::string() : more_exit_codes + "; ") +
                            "1 an unexpected failure (a bug: please report it).";
  app.footer(codes);
  for (CLI::App* sub : app.get_subcommands([](CLI::App*) { return true; })) sub->footer(codes);
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForVersion& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    std::cerr << log::program() << ": error: " << e.what() << " (see --help)\n";
    return 2;
  }
  try {
    return body();
  } catch (const Error& e) {
    log::error(e.what());
    return 2;
  } catch (const std::exception& e) {
    log::error(std::string("unexpected failure: ") + e.what());
    return 1;
  }
}

// Reads a data table. Rows of DEM batch responses whose status is not "ok"
// are left out, each with a warning naming the run and the reason, so a
// failed point never enters a fit as a number and never vanishes unseen.
inline Table read_data(const std::string& path) {
  if (path.empty()) throw Error("--data FILE is required");
  std::ifstream probe(path);
  if (!probe) throw Error(path + ": cannot open data file");
  Table table = Table::read(path);
  if (table.rows() == 0) throw Error(path + ": the data has no rows");
  if (table.statuses().empty()) return table;
  std::vector<std::size_t> ok;
  for (std::size_t i = 0; i < table.rows(); ++i)
    if (table.statuses()[i] == "ok") ok.push_back(i);
  if (ok.empty())
    throw Error(path + ": none of its " + std::to_string(table.rows()) + " rows has status ok; nothing to analyse");
  for (std::size_t i = 0; i < table.rows(); ++i) {
    if (table.statuses()[i] == "ok") continue;
    std::string seed = table.has_column("seed") ? " seed " + std::to_string(static_cast<long long>(table.column("seed")[i])) : "";
    log::warn(path + ": run " + std::to_string(table.run_ids()[i]) + seed + " left out (" + table.statuses()[i] + ")");
  }
  return table.select_rows(ok);
}

}  // namespace demcal::cli
