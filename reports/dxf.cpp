#include "reports/dxf.h"

#include <cmath>
#include <fmt/format.h>


namespace chutelab::reports {
namespace {

// A group: its code on one line, its value on the next (DXF's whole grammar).
void group(std::string& o, int code, std::string_view value) { o += fmt::format("{:>3}\n{}\n", code, value); }
// Shortest text that reads back as the same double (as estimate's JSON writes numbers).
void number(std::string& o, int code, double v) { group(o, code, fmt::format("{}", v)); }

struct Layer {
  std::string name;
  int colour;  // AutoCAD colour index
};

}  // namespace

std::string dxf_layer(Streamline s) {
  switch (s) {
    case Streamline::upper: return "STREAMLINE_UPPER";
    case Streamline::lower: return "STREAMLINE_LOWER";
    case Streamline::cema_centroid: return "STREAMLINE_CEMA_CENTROID";
    case Streamline::korzen_centroid: return "STREAMLINE_KORZEN_CENTROID";
  }
  return "STREAMLINE";
}

std::string design_dxf(const DesignDrawing& d) {
  const auto& st = d.station;
  std::vector<Layer> layers = {{"PULLEY", 8}, {"BELT", 7}, {"PLATE", 7}, {"IMPACT_ZONE", 30}};
  const int colours[] = {1, 5, 3, 6};  // lower red, upper blue, CEMA green, Korzen magenta (as drawn)
  for (Streamline s : kAllStreamlines) layers.push_back({dxf_layer(s), colours[static_cast<int>(s)]});

  std::string o;
  group(o, 999, fmt::format("chutelab design {}: millimetres, origin at the head pulley's centre, x towards the plate, y up",
                            st.condition));
  group(o, 0, "SECTION");
  group(o, 2, "HEADER");
  group(o, 9, "$ACADVER");
  group(o, 1, "AC1009");
  group(o, 0, "ENDSEC");
  group(o, 0, "SECTION");
  group(o, 2, "TABLES");
  group(o, 0, "TABLE");
  group(o, 2, "LTYPE");
  group(o, 70, "1");
  group(o, 0, "LTYPE");
  group(o, 2, "CONTINUOUS");
  group(o, 70, "0");
  group(o, 3, "Solid line");
  group(o, 72, "65");
  group(o, 73, "0");
  group(o, 40, "0.0");
  group(o, 0, "ENDTAB");
  group(o, 0, "TABLE");
  group(o, 2, "LAYER");
  group(o, 70, std::to_string(layers.size()));
  for (const auto& l : layers) {
    group(o, 0, "LAYER");
    group(o, 2, l.name);
    group(o, 70, "0");
    group(o, 62, std::to_string(l.colour));
    group(o, 6, "CONTINUOUS");
  }
  group(o, 0, "ENDTAB");
  group(o, 0, "ENDSEC");

  group(o, 0, "SECTION");
  group(o, 2, "ENTITIES");
  auto circle = [&](const char* layer, double r) {
    group(o, 0, "CIRCLE");
    group(o, 8, layer);
    number(o, 10, 0.0);
    number(o, 20, 0.0);
    number(o, 30, 0.0);
    number(o, 40, r);
  };
  auto line = [&](const char* layer, const Eigen::Vector2d& p, const Eigen::Vector2d& q) {
    group(o, 0, "LINE");
    group(o, 8, layer);
    number(o, 10, p.x());
    number(o, 20, p.y());
    number(o, 30, 0.0);
    number(o, 11, q.x());
    number(o, 21, q.y());
    number(o, 31, 0.0);
  };
  circle("PULLEY", 0.5 * st.belt.pulley_diameter * 1e3);
  circle("BELT", st.belt.belt_radius() * 1e3);
  const Eigen::Vector2d top(st.plate_distance * 1e3, st.plate_top * 1e3);
  const Eigen::Vector2d down(std::sin(st.plate.angle), -std::cos(st.plate.angle));
  line("PLATE", top, top + st.plate.height * 1e3 * down);
  const auto& zone = d.zone;
  line("IMPACT_ZONE", top + zone.top_along * 1e3 * down, top + zone.bottom_along * 1e3 * down);
  for (Streamline s : kAllStreamlines) {
    group(o, 0, "POLYLINE");
    group(o, 8, dxf_layer(s));
    group(o, 66, "1");
    number(o, 10, 0.0);
    number(o, 20, 0.0);
    number(o, 30, 0.0);
    group(o, 70, "0");
    for (const auto& p : d.line(s).path) {
      group(o, 0, "VERTEX");
      group(o, 8, dxf_layer(s));
      number(o, 10, p.x() * 1e3);
      number(o, 20, p.y() * 1e3);
      number(o, 30, 0.0);
    }
    group(o, 0, "SEQEND");
    group(o, 8, dxf_layer(s));
  }
  group(o, 0, "ENDSEC");
  group(o, 0, "EOF");
  return o;
}

}  // namespace chutelab::reports
