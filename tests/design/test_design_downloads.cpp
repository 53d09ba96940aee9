#define BOOST_TEST_MODULE design_downloads
// The designer's downloads as a designer gets them: headless Chromium opens the page from file://
// with download=svg, then download=dxf, in its address (the page clicks that link once the design is
// computed) and saves the file as a browser does, into $HOME/Downloads. The SVG is the drawing with
// its dimensions and mm ticks; the DXF, read back by ezdxf (Debian's python3-ezdxf), holds the four
// streamlines with the points `chutelab estimate --format json` gives for the design the page
// exports. Our own main: without the page, Chromium or ezdxf, ctest shows the test skipped.
#define BOOST_TEST_NO_MAIN
#include <boost/test/unit_test.hpp>
#include <cmath>
#include <cstdlib>
#include <fmt/format.h>
#include <iostream>
#include <regex>

#include "../cli/cli_runner.h"
#include "dxf_points.h"

namespace chutelab::test {
namespace {
namespace fs = std::filesystem;

const fs::path kChromium = "/usr/bin/chromium";
const std::string kPython = "/usr/bin/python3";
const std::string kReader = std::string(CHUTELAB_SOURCE_DIR) + "/tests/design/read_dxf.py";

std::string html_unescape(std::string s) {
  for (auto [from, to] : {std::pair{"&lt;", "<"}, {"&gt;", ">"}, {"&quot;", "\""}, {"&#39;", "'"}, {"&amp;", "&"}}) {
    for (auto at = s.find(from); at != std::string::npos; at = s.find(from, at + 1)) s.replace(at, std::string(from).size(), to);
  }
  return s;
}

// The page in a browser whose home is `home` (downloads land in home/Downloads); returns the DOM.
std::string open_with_home(const fs::path& dir, const fs::path& home, const std::string& url) {
  fs::remove_all(dir / "profile");
  fs::create_directories(home);
  const std::string cmd = fmt::format(
      "HOME='{}' timeout 120 '{}' --headless --no-sandbox --disable-gpu --disable-quic --no-first-run "
      "--disable-background-networking --disable-component-update --disable-sync --disable-extensions "
      "--user-data-dir='{}' --window-size=1400,1900 --virtual-time-budget=60000 --dump-dom '{}' >'{}' 2>'{}' </dev/null",
      home.string(), kChromium.string(), (dir / "profile").string(), url, (dir / "dom.html").string(),
      (dir / "stderr.txt").string());
  std::system(cmd.c_str());
  return read_file(dir / "dom.html");
}

}  // namespace

BOOST_AUTO_TEST_CASE(page_downloads_the_svg_and_a_dxf_with_estimates_points) {
  const fs::path dir = fresh_dir("design-downloads");
  const auto built = run_chutelab("design --out '" + (dir / "page").string() + "'");
  BOOST_TEST_REQUIRE(built.exit_code == 0, built.err);
  const std::string url = "file://" + fs::absolute(dir / "page" / "design.html").string() +
                          "#belt_speed=4&mass_flow=35&plate_distance=450&belt.pulley_diameter_mm=500&name=D1&download=";
  std::string dom;
  for (const std::string what : {"svg", "dxf"}) {
    const fs::path home = dir / ("home-" + what);
    dom = open_with_home(dir, home, url + what);
    BOOST_TEST_REQUIRE(dom.find("<body data-state=\"ready\"") != std::string::npos,
                       "page not ready: " << read_file(dir / "stderr.txt").substr(0, 1500));
    BOOST_TEST_REQUIRE(fs::exists(home / "Downloads" / ("D1." + what)), "no download of D1." << what);
  }
  const std::string svg = read_file(dir / "home-svg" / "Downloads" / "D1.svg");
  BOOST_TEST(svg.rfind("<?xml", 0) == 0u);
  BOOST_TEST(svg.find("xmlns=\"http://www.w3.org/2000/svg\"") != std::string::npos);
  BOOST_TEST(svg.find("class=\"dimension\"") != std::string::npos);
  BOOST_TEST(svg.find("class=\"tick x\"") != std::string::npos);
  BOOST_TEST(svg.find("class=\"scale-bar\"") != std::string::npos);
  BOOST_TEST(svg.find(">Ø 500 mm<") != std::string::npos);

  // The design the page exports, through the native estimate: the reference points.
  std::smatch m;
  BOOST_REQUIRE(std::regex_search(dom, m, std::regex("<textarea id=\"export-conditions\"[^>]*>([^<]*)</textarea>")));
  write_file(dir / "exported" / "conditions.csv", html_unescape(m[1]));
  BOOST_REQUIRE(std::regex_search(dom, m, std::regex("<textarea id=\"export-setup\"[^>]*>([^<]*)</textarea>")));
  write_file(dir / "exported" / "setup.toml", html_unescape(m[1]));
  const auto cli = run_chutelab("estimate --dataset '" + (dir / "exported").string() + "' --condition D1 --format json");
  BOOST_TEST_REQUIRE(cli.exit_code == 0, cli.err);

  const fs::path dxf = dir / "home-dxf" / "Downloads" / "D1.dxf";
  const std::string cmd = "'" + kPython + "' '" + kReader + "' '" + dxf.string() + "' >'" + (dir / "listing.txt").string() +
                          "' 2>'" + (dir / "err.txt").string() + "'";
  BOOST_REQUIRE_MESSAGE(std::system(cmd.c_str()) == 0, read_file(dir / "err.txt"));
  const std::string listing = read_file(dir / "listing.txt");
  BOOST_TEST(listing.find("AUDIT_ERRORS 0\n") != std::string::npos);
  const auto got = dxf_streamline_points(listing);
  const auto want = json_streamline_points(cli.out);
  BOOST_REQUIRE_EQUAL(want.size(), 4u);
  std::size_t n = 0;
  double worst = 0.0;
  for (const auto& [layer, pts] : want) {
    BOOST_REQUIRE(got.count(layer));
    BOOST_REQUIRE_EQUAL(got.at(layer).size(), pts.size());
    for (std::size_t k = 0; k < pts.size(); ++k) {
      const auto [x, y] = got.at(layer)[k];
      // The page's numbers come from the same C++ compiled to WebAssembly, whose libm (musl) may
      // round a sine or an arctangent one ulp away from glibc's: equal to 2e-9 relative (the mm
      // coordinates are ~1e2..1e3, so ~1e-6 mm), as the page test's readout.
      const double dx = std::abs(x - pts[k].first) / std::max(1.0, std::abs(pts[k].first));
      const double dy = std::abs(y - pts[k].second) / std::max(1.0, std::abs(pts[k].second));
      worst = std::max({worst, dx, dy});
      BOOST_TEST((dx <= 2e-9 && dy <= 2e-9), layer << " point " << k << ": DXF " << x << ", " << y << "; estimate "
                                                << pts[k].first << ", " << pts[k].second);
      ++n;
    }
  }
  BOOST_TEST_MESSAGE(n << " streamline points of the page's DXF equal estimate's; largest relative difference " << worst);
}

// "PDF (print)": the browser prints the page with its print stylesheet, which keeps the drawing
// alone on one landscape A4 page, as vectors (no raster image in the file).
BOOST_AUTO_TEST_CASE(printing_the_page_gives_a_one_page_pdf_of_the_drawing) {
  const fs::path dir = fresh_dir("design-pdf");
  const auto built = run_chutelab("design --out '" + (dir / "page").string() + "'");
  BOOST_TEST_REQUIRE(built.exit_code == 0, built.err);
  const fs::path pdf = dir / "drawing.pdf";
  const std::string cmd = fmt::format(
      "HOME='{}' timeout 120 '{}' --headless --no-sandbox --disable-gpu --no-first-run --disable-extensions "
      "--user-data-dir='{}' --virtual-time-budget=60000 --no-pdf-header-footer --print-to-pdf='{}' '{}' >/dev/null 2>&1 </dev/null",
      (dir / "home").string(), kChromium.string(), (dir / "profile").string(), pdf.string(),
      "file://" + fs::absolute(dir / "page" / "design.html").string() + "#belt_speed=4&mass_flow=35&plate_distance=450");
  std::system(cmd.c_str());
  BOOST_REQUIRE(fs::exists(pdf));
  const std::string bytes = read_file(pdf);
  BOOST_TEST(bytes.rfind("%PDF-", 0) == 0u);
  BOOST_TEST(bytes.find("/Count 1") != std::string::npos);  // one page
  std::smatch m;
  BOOST_REQUIRE(std::regex_search(bytes, m, std::regex("/MediaBox \\[0 0 ([0-9.]+) ([0-9.]+)\\]")));
  BOOST_TEST(std::stod(m[1]) == 841.92, boost::test_tools::tolerance(0.01));  // A4 landscape, pt
  BOOST_TEST(std::stod(m[2]) == 595.0, boost::test_tools::tolerance(0.01));
  BOOST_TEST(bytes.find("/Subtype /Image") == std::string::npos);
  BOOST_TEST_MESSAGE("printed drawing: " << bytes.size() << " bytes, one A4 landscape page of vectors");
}

}  // namespace chutelab::test

int main(int argc, char* argv[]) {
  using chutelab::test::kChromium;
  if (!CHUTELAB_DESIGN_PAGE_BUILT) {
    std::cerr << "SKIPPED: this build has no designer's page (em++ from Debian's emscripten was not found).\n";
    return 77;
  }
  if (!std::filesystem::exists(kChromium)) {
    std::cerr << "SKIPPED: " << kChromium << " is not installed; the downloads were not checked.\n";
    return 77;
  }
  if (std::system(("'" + chutelab::test::kPython + "' -c 'import ezdxf' 2>/dev/null").c_str()) != 0) {
    std::cerr << "SKIPPED: " << chutelab::test::kPython << " has no ezdxf (python3-ezdxf; scripts/setup.sh installs it).\n";
    return 77;
  }
  return boost::unit_test::unit_test_main(&init_unit_test, argc, argv);
}
