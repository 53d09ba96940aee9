// chutelab: how far are transfer-station models from the measurements, and why.
#include <CLI/CLI.hpp>
#include <fmt/format.h>
#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <iostream>
#include <optional>

#include "app/commands.h"
#include "app/flag_names.h"
#include "app/option_checks.h"
#include "core/campaign.h"
#include "core/input_error.h"
#include "core/message.h"
#include "core/output_folder.h"
#include "core/progress.h"
#include "api/files.h"

namespace chutelab::app {
std::vector<std::string> split_list(const std::string& s) {
  std::vector<std::string> out;
  if (s.empty()) return out;
  std::size_t start = 0;
  while (start <= s.size()) {
    const auto end = s.find(',', start);
    out.push_back(s.substr(start, end == std::string::npos ? std::string::npos : end - start));
    if (end == std::string::npos) break;
    start = end + 1;
  }
  return out;
}

namespace {
std::size_t edit_distance(std::string_view a, std::string_view b) {
  std::vector<std::size_t> prev(b.size() + 1), cur(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j) prev[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    cur[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j)
      cur[j] = std::min({prev[j] + 1, cur[j - 1] + 1, prev[j - 1] + (a[i - 1] == b[j - 1] ? 0 : 1)});
    std::swap(prev, cur);
  }
  return prev[b.size()];
}

// The closest of `names` to `typed`, when it is close enough to be a typo (or a prefix of it).
std::optional<std::string> closest(std::string_view typed, const std::vector<std::string>& names) {
  std::optional<std::string> best;
  std::size_t best_d = std::max<std::size_t>(2, typed.size() / 3) + 1;
  for (const auto& n : names) {
    const std::size_t d = n.rfind(typed, 0) == 0 && typed.size() >= 3 ? 1 : edit_distance(typed, n);
    if (d < best_d) {
      best_d = d;
      best = n;
    }
  }
  return best;
}
}  // namespace

std::optional<std::string> misspelt(CLI::App& app, int argc, char** argv) {
  std::vector<std::string> commands;
  for (const auto* sub : app.get_subcommands([](const CLI::App*) { return true; })) commands.push_back(sub->get_name());
  CLI::App* sub = nullptr;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--") break;
    if (a.size() > 1 && a[0] == '-') {
      if (!sub) continue;
      // A negative number is a value (--plate-top -50), not a flag.
      if (std::isdigit(static_cast<unsigned char>(a[1])) || a[1] == '.') continue;
      const std::string flag = a.substr(0, a.find('='));
      std::vector<std::string> flags;
      bool known = false;
      for (const auto* o : sub->get_options()) {
        for (const auto& l : o->get_lnames()) {
          flags.push_back("--" + l);
          known = known || flags.back() == flag;
        }
        for (const auto& n : o->get_snames()) known = known || "-" + n == flag;
      }
      if (known) continue;
      if (auto c = closest(flag, flags))
        return fmt::format("{}: unknown option {}; did you mean {}?", sub->get_name(), flag, *c);
      return fmt::format("{}: unknown option {} (see chutelab {} --help)", sub->get_name(), flag, sub->get_name());
    }
    if (!sub) {
      try {
        sub = app.get_subcommand(a);
      } catch (const CLI::OptionNotFound&) {
        if (auto c = closest(a, commands)) return fmt::format("unknown command '{}'; did you mean '{}'?", a, *c);
        return fmt::format("unknown command '{}' (commands: {})", a, fmt::join(commands, ", "));
      }
    }
  }
  return std::nullopt;
}

std::vector<std::filesystem::path> dataset_inputs(const std::filesystem::path& dir) {
  return api::dataset_files(dir);
}

void check_entries(const OutputFolder& out, std::initializer_list<const char*> files) {
  for (const char* f : files) out.check_entry(f, false);
}

std::filesystem::path default_dataset() {
  return std::filesystem::path(CHUTELAB_DATASETS_DIR) / "grima2010";
}
}  // namespace chutelab::app

int main(int argc, char** argv) {
  using namespace chutelab;
  // Before any thread exists (MPI's included), so every worker inherits the mask (core/output_folder.h).
  install_interrupt_cleanup();
  progress::set_mention_names(app::flag_for);  // progress lines name other inputs by their flags
  // Last resort for an exception that cannot reach the barrier below (a worker thread, a noexcept
  // path): one line and its own exit code, never an abort and its core dump.
  std::set_terminate([] {
    std::string what = "unknown error";
    if (auto e = std::current_exception()) {
      try {
        std::rethrow_exception(e);
      } catch (const std::exception& x) {
        what = x.what();
      } catch (...) {
      }
    }
    std::cerr << "chutelab: internal error: " << one_line(what) << "\n";
    std::_Exit(kExitInternalError);
  });
  // Under mpirun every rank runs the command; rank 0 alone prints and writes (core/campaign.h).
  campaign::Session session(argc, argv);
  if (!session.refusal().empty()) {
    std::cerr << "chutelab: " << session.refusal() << "\n";
    return kExitBadInput;
  }
  CLI::App app{"chutelab: conveyor transfer-station models against measurements"};
  app.require_subcommand(1);
  app.set_version_flag("--version", "chutelab 0.1.0");
  app::Action action;
  app::add_estimate(app, action);
  app::add_validate(app, action);
  app::add_diagnose(app, action);
  app::add_synthesize(app, action);
  app::add_simulate(app, action);
  app::add_calibrate(app, action);
  app::add_sensitivity(app, action);
  app::add_import_digitised(app, action);
  app::add_import_logs(app, action);
  app::add_synthesize_logs(app, action);
  app::add_design(app, action);
  app::add_init(app, action);
  app::check_every_option(app);  // after every command's own rules (core/option_check.h)
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForVersion& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    // A misspelt command or flag is the cause of whatever CLI11 says next ("--dataset is required"
    // after --datset): name it first, with the nearest real one.
    if (auto m = app::misspelt(app, argc, argv)) std::cerr << "chutelab: " << one_line(*m) << "\n";
    else std::cerr << "chutelab: " << one_line(e.what()) << " (see --help)\n";
    return kExitBadInput;
  }
  // The one exception barrier: bad input is exit 2 with file:line:field; a file-system failure on a
  // path the user gave is exit 2 naming it; anything else is a bug, said in one line, exit 3.
  try {
    const int code = action ? action() : kExitBadInput;
    // Results that never reached their reader are no success (a full disk behind `> FILE`, /dev/full).
    errno = 0;
    const bool flushed = std::fflush(stdout) == 0;
    const int err = errno;
    if (!flushed || std::ferror(stdout) || std::cout.bad()) {
      quiet_interrupts();
      std::cerr << "chutelab: standard output: cannot write the results: "
                << (!flushed && err != 0 ? std::strerror(err) : "a write failed") << "\n";
      return kExitBadInput;
    }
    return code;
  } catch (...) {
    quiet_interrupts();  // the one line below is the whole story, however the process then ends
    try {
      throw;
    } catch (const InputError& e) {
      std::cerr << "chutelab: " << app::said(e) << "\n";
      return kExitBadInput;
    } catch (const std::filesystem::filesystem_error& e) {
      std::string where = e.path1().string();
      if (!e.path2().empty()) where += " -> " + e.path2().string();
      std::cerr << "chutelab: " << one_line((where.empty() ? "" : where + ": ") + e.code().message()) << "\n";
      return kExitBadInput;
    } catch (const std::bad_alloc&) {
      std::cerr << "chutelab: internal error: out of memory\n";
      return kExitInternalError;
    } catch (const std::exception& e) {
      std::cerr << "chutelab: internal error: " << one_line(e.what()) << "\n";
      return kExitInternalError;
    } catch (...) {
      std::cerr << "chutelab: internal error: unknown exception\n";
      return kExitInternalError;
    }
  }
}
