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

std::filesystem::path tiny_station_dataset(const std::string& name, bool with_t4) {
  const std::filesystem::path dir = fresh_dir(name);
  write_file(dir / "setup.toml",
             "name = \"tiny\"\nsource = \"test\"\n"
             "[belt]\npulley_diameter_mm = 250.0\nbelt_thickness_mm = 5.0\nbelt_width_mm = 200.0\n"
             "loaded_width_mm = 120.0\nincline_deg = 0.0\n"
             "[plate]\nwidth_mm = 600.0\nheight_mm = 400.0\nangle_deg = 0.0\n"
             "[material]\nparticle_diameter_mm = 9.0\nsolid_density_kgm3 = 1000.0\nbulk_density_kgm3 = 558.0\n"
             "youngs_modulus_Pa = 2.5e7\npoisson_ratio = 0.38\nfriction_particle = 0.3\nfriction_plate = 0.27\n"
             "friction_belt = 0.7\nrolling_friction_particle = 0.1\nrestitution_particle = 0.7\n"
             "restitution_plate = 0.66\n"
             "[dem]\nmax_time_s = 0.4\nmin_window_s = 0.1\n");
  write_file(dir / "conditions.csv",
             std::string("condition,belt_speed_mps,mass_flow_tph,plate_distance_mm,plate_top_mm,stream_thickness_mm\n"
                         "T3,3.0,9.0,350.0,250.0,\n") +
                 (with_t4 ? "T4,4.0,9.0,350.0,250.0,\n" : ""));
  write_file(dir / "measurements.csv",
             std::string("condition,quantity,value,uncertainty\nT3,normal_force_N,7.5,0.1\nT3,impact_point_y_mm,90,1\n") +
                 (with_t4 ? "T4,normal_force_N,9.5,0.1\nT4,impact_point_y_mm,80,1\n" : ""));
  return dir;
}

}  // namespace chutelab::test
