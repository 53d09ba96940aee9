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
// The tiny station of the dem-station tests as a dataset (9 t/h, 13.6 mm quick spheres, each run
// kept to 0.4 s simulated by its [dem] table), in a fresh folder: condition T3 (3 m/s), and with
// `with_t4` also T4 (4 m/s), each with a measured R_n and impact point.
std::filesystem::path tiny_station_dataset(const std::string& name, bool with_t4 = false);
std::string read_file(const std::filesystem::path& p);
int count_lines(const std::string& s);

}  // namespace chutelab::test
