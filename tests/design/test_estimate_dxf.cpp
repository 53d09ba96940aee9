#define BOOST_TEST_MODULE estimate_dxf
// `estimate --dxf` read back by a DXF library as CAD reads it (ezdxf, Debian's python3-ezdxf): an
// R12 file the auditor finds no error in, the pulley and belt circles, the plate, and one polyline
// per streamline whose vertices are estimate's JSON points_mm bit for bit (both print the shortest
// text that reads back as the same double). Our own main: without ezdxf ctest shows it skipped.
#define BOOST_TEST_NO_MAIN
#include <boost/test/unit_test.hpp>
#include <cstdlib>
#include <iostream>

#include "../cli/cli_runner.h"
#include "dxf_points.h"

using namespace chutelab::test;
namespace fs = std::filesystem;

namespace {
const std::string kPython = "/usr/bin/python3";  // Debian's, where python3-ezdxf installs
const std::string kReader = std::string(CHUTELAB_SOURCE_DIR) + "/tests/design/read_dxf.py";
}  // namespace

BOOST_AUTO_TEST_CASE(dxf_streamlines_are_estimates_points) {
  for (const std::string design : {"--belt-speed 4 --mass-flow 35 --plate-distance 450",
                                   "--condition V2-26", "--belt-speed 1.2 --mass-flow 20 --plate-distance 300 --effect air_drag=0.6"}) {
    const fs::path dir = fresh_dir("estimate-dxf");
    const auto r = run_chutelab("estimate " + design + " --format json --dxf '" + (dir / "d.dxf").string() + "'");
    BOOST_REQUIRE_MESSAGE(r.exit_code == 0, r.err);
    const std::string cmd = "'" + kPython + "' '" + kReader + "' '" + (dir / "d.dxf").string() + "' >'" +
                            (dir / "listing.txt").string() + "' 2>'" + (dir / "err.txt").string() + "'";
    BOOST_REQUIRE_MESSAGE(std::system(cmd.c_str()) == 0, read_file(dir / "err.txt"));
    const std::string listing = read_file(dir / "listing.txt");
    BOOST_TEST(listing.find("AUDIT_ERRORS 0\n") != std::string::npos, listing.substr(listing.size() > 200 ? listing.size() - 200 : 0));
    BOOST_TEST(listing.find("DXFVERSION AC1009\n") != std::string::npos);
    BOOST_TEST(listing.find("CIRCLE PULLEY ") != std::string::npos);
    BOOST_TEST(listing.find("CIRCLE BELT ") != std::string::npos);
    BOOST_TEST(listing.find("LINE PLATE ") != std::string::npos);
    const auto dxf = dxf_streamline_points(listing);
    const auto json = json_streamline_points(r.out);
    BOOST_REQUIRE_EQUAL(json.size(), 4u);
    BOOST_REQUIRE_EQUAL(dxf.size(), 4u);
    std::size_t points = 0;
    for (const auto& [layer, pts] : json) {
      BOOST_REQUIRE(dxf.count(layer));
      BOOST_TEST((dxf.at(layer) == pts), layer << ": DXF vertices differ from estimate's points_mm");
      points += pts.size();
    }
    BOOST_TEST_MESSAGE(design << ": " << points << " streamline points equal in the DXF and the JSON");
  }
}

int main(int argc, char* argv[]) {
  if (std::system(("'" + kPython + "' -c 'import ezdxf' 2>/dev/null").c_str()) != 0) {
    std::cerr << "SKIPPED: " << kPython << " has no ezdxf (Debian's python3-ezdxf; scripts/setup.sh installs it): the "
                 "DXF was not read back.\n";
    return 77;
  }
  return boost::unit_test::unit_test_main(&init_unit_test, argc, argv);
}
