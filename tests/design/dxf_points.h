#pragma once
// Shared by the designer's tests: the streamline points of `estimate --format json` and of a DXF
// read back by ezdxf (read_dxf.py), keyed by the DXF layer of each streamline.
#include <cstdlib>
#include <map>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

namespace chutelab::test {

using Points = std::vector<std::pair<double, double>>;

// "lower" -> "STREAMLINE_LOWER" (reports/dxf.h).
inline std::string dxf_layer_of(std::string name) {
  for (auto& c : name) c = c == '-' ? '_' : static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
  return "STREAMLINE_" + name;
}

// points_mm of each streamline in estimate's JSON.
inline std::map<std::string, Points> json_streamline_points(const std::string& json) {
  std::map<std::string, Points> out;
  const auto block = json.find("\"streamlines\": {");
  if (block == std::string::npos) return out;
  for (const char* name : {"lower", "upper", "cema_centroid", "korzen_centroid"}) {
    const auto at = json.find(std::string("\"") + name + "\": {", block);
    if (at == std::string::npos) continue;
    auto p = json.find("\"points_mm\": [", at);
    if (p == std::string::npos) continue;
    p += 14;
    Points pts;
    const char* c = json.c_str() + p;
    while (*c == '[' || *c == ' ' || *c == ',') {
      if (*c != '[') { ++c; continue; }
      char* end = nullptr;
      const double x = std::strtod(c + 1, &end);
      c = end + 1;  // ", "
      const double y = std::strtod(c, &end);
      pts.emplace_back(x, y);
      c = end + 1;  // past ']'
    }
    out[dxf_layer_of(name)] = pts;
  }
  return out;
}

// Polyline vertices per layer from read_dxf.py's listing.
inline std::map<std::string, Points> dxf_streamline_points(const std::string& listing) {
  std::map<std::string, Points> out;
  std::istringstream in(listing);
  std::string layer;
  while (in >> layer) {
    if (layer.rfind("STREAMLINE_", 0) == 0) {
      std::string x, y;
      in >> x >> y;
      out[layer].emplace_back(std::stod(x), std::stod(y));
    } else {
      std::string rest;
      std::getline(in, rest);
    }
  }
  return out;
}

}  // namespace chutelab::test
