// The shared runner of the CLI-level tests.
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <sys/wait.h>
#include <unistd.h>

#include "cli_runner.h"

namespace chutelab::test {
namespace fs = std::filesystem;

std::string read_file(const fs::path& p) {
  std::ifstream in(p);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

void write_file(const fs::path& p, const std::string& text) {
  fs::create_directories(p.parent_path());
  std::ofstream(p) << text;
}

fs::path fresh_dir(const std::string& name) {
  const fs::path d = fs::temp_directory_path() / ("chutelab-test-" + std::to_string(::getpid())) / name;
  fs::remove_all(d);
  fs::create_directories(d);
  return d;
}

RunResult run_chutelab(const std::string& args) {
  static int counter = 0;
  const fs::path d = fresh_dir("run" + std::to_string(counter++));
  const std::string cmd = std::string("'") + CHUTELAB_BINARY + "' " + args + " >'" +
                          (d / "out").string() + "' 2>'" + (d / "err").string() + "' </dev/null";
  const int status = std::system(cmd.c_str());
  RunResult r;
  r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  r.out = read_file(d / "out");
  r.err = read_file(d / "err");
  return r;
}

int count_lines(const std::string& s) {
  int n = 0;
  for (char c : s) n += c == '\n';
  return n;
}

}  // namespace chutelab::test
