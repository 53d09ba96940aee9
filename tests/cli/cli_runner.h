#pragma once
// Runs the real chutelab binary the way a user would, capturing exit code and output.
#include <filesystem>
#include <string>

namespace chutelab::test {

struct RunResult {
  int exit_code = -1;
  std::string out, err;
};

RunResult run_chutelab(const std::string& args);
std::filesystem::path fresh_dir(const std::string& name);  // empty temporary folder
void write_file(const std::filesystem::path& p, const std::string& text);
std::string read_file(const std::filesystem::path& p);
int count_lines(const std::string& s);

}  // namespace chutelab::test
