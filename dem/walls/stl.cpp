#include "dem/walls/stl.h"

#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <sstream>

#include <fmt/format.h>

#include "core/input_error.h"

namespace chutelab::dem {
namespace {

std::string lower(std::string s) {
  for (auto& ch : s) ch = static_cast<char>(std::tolower(static_cast<unsigned char>(ch)));
  return s;
}

void check_triangle(const std::string& path, long where, const std::array<Vec3, 3>& t, bool binary) {
  for (const auto& v : t)
    if (!v.allFinite())
      throw InputError(path, binary ? 0 : where, binary ? fmt::format("byte {}", where) : "vertex",
                       "vertex coordinate is not a finite number");
  if ((t[1] - t[0]).cross(t[2] - t[0]).squaredNorm() == 0.0)
    throw InputError(path, binary ? 0 : where, binary ? fmt::format("byte {}", where) : "facet",
                     "degenerate triangle (zero area)");
}

TriangleMesh read_ascii(const std::string& path, const std::string& text, double scale) {
  std::istringstream in(text);
  std::string line;
  long lineno = 0;
  std::vector<std::array<Vec3, 3>> soup;
  std::array<Vec3, 3> tri;
  int nvert = -1;  // -1: outside a facet
  long facet_line = 0;
  bool solid = false, ended = false;
  while (std::getline(in, line)) {
    ++lineno;
    std::istringstream ls(line);
    std::string word;
    if (!(ls >> word)) continue;
    word = lower(word);
    if (word == "solid") {
      solid = true;
    } else if (word == "facet") {
      if (!solid) throw InputError(path, lineno, "facet", "'facet' before 'solid'");
      if (nvert != -1) throw InputError(path, lineno, "facet", "'facet' inside another facet");
      nvert = 0;
      facet_line = lineno;
    } else if (word == "outer" || word == "endloop") {
      if (nvert == -1) throw InputError(path, lineno, word, "outside a facet");
    } else if (word == "vertex") {
      if (nvert < 0) throw InputError(path, lineno, "vertex", "vertex outside a facet");
      if (nvert >= 3) throw InputError(path, lineno, "vertex", "more than 3 vertices in a facet");
      double c[3];
      for (double& v : c)
        if (!(ls >> v)) throw InputError(path, lineno, "vertex", "expected three numbers after 'vertex'");
      tri[static_cast<std::size_t>(nvert++)] = Vec3(c[0], c[1], c[2]) * scale;
    } else if (word == "endfacet") {
      if (nvert != 3)
        throw InputError(path, lineno, "endfacet", fmt::format("facet has {} vertices, expected 3", std::max(nvert, 0)));
      check_triangle(path, facet_line, tri, false);
      soup.push_back(tri);
      nvert = -1;
    } else if (word == "endsolid") {
      ended = true;
      break;
    } else {
      throw InputError(path, lineno, word, "unknown keyword in ASCII STL");
    }
  }
  if (nvert != -1) throw InputError(path, lineno, "facet", "file ends inside a facet");
  if (!ended) throw InputError(path, lineno, "endsolid", "missing 'endsolid' (truncated file?)");
  if (soup.empty()) throw InputError(path, lineno, "facet", "no triangles in file");
  return TriangleMesh::from_soup(soup, path);
}

float read_f32(const char* p) {
  float f;
  std::memcpy(&f, p, 4);
  return f;
}

TriangleMesh read_binary(const std::string& path, const std::string& data, double scale) {
  if (data.size() < 84)
    throw InputError(path, 0, "header", fmt::format("binary STL shorter than its 84-byte header ({} bytes)", data.size()));
  std::uint32_t n;
  std::memcpy(&n, data.data() + 80, 4);
  const std::size_t expected = 84 + static_cast<std::size_t>(n) * 50;
  if (data.size() != expected)
    throw InputError(path, 0, "triangle count",
                     fmt::format("header says {} triangles ({} bytes) but the file has {} bytes", n, expected, data.size()));
  if (n == 0) throw InputError(path, 0, "triangle count", "no triangles in file");
  std::vector<std::array<Vec3, 3>> soup;
  soup.reserve(n);
  for (std::uint32_t k = 0; k < n; ++k) {
    const char* p = data.data() + 84 + static_cast<std::size_t>(k) * 50 + 12;  // skip normal
    std::array<Vec3, 3> tri;
    for (int v = 0; v < 3; ++v)
      tri[static_cast<std::size_t>(v)] =
          Vec3(read_f32(p + 12 * v), read_f32(p + 12 * v + 4), read_f32(p + 12 * v + 8)) * scale;
    check_triangle(path, 84 + static_cast<long>(k) * 50, tri, true);
    soup.push_back(tri);
  }
  return TriangleMesh::from_soup(soup, path);
}

}  // namespace

TriangleMesh read_stl(const std::string& path, double scale) {
  if (!(scale > 0.0) || !std::isfinite(scale)) throw InputError(path, 0, "scale", "scale must be > 0");
  require_readable_file(path);  // a folder or a symlink loop is said as such, not as "empty"
  std::ifstream f(path, std::ios::binary);
  if (!f) throw InputError(path, 0, "", "cannot open STL file");
  std::string data((std::istreambuf_iterator<char>(f)), std::istreambuf_iterator<char>());
  if (data.empty()) throw InputError(path, 0, "", "STL file is empty");
  // Binary files may also begin with "solid"; they are recognised by the exact size their count implies.
  bool binary = true;
  if (data.size() >= 84) {
    std::uint32_t n;
    std::memcpy(&n, data.data() + 80, 4);
    binary = data.size() == 84 + static_cast<std::size_t>(n) * 50;
  }
  std::size_t first = data.find_first_not_of(" \t\r\n");
  const bool looks_ascii = first != std::string::npos && lower(data.substr(first, 5)) == "solid";
  if (binary && !(looks_ascii && data.find("facet") != std::string::npos && data.find("endsolid") != std::string::npos))
    return read_binary(path, data, scale);
  if (looks_ascii) return read_ascii(path, data, scale);
  return read_binary(path, data, scale);  // reports the size mismatch
}

void write_stl_binary(const std::string& path, const TriangleMesh& mesh) {
  std::ofstream f(path, std::ios::binary);
  if (!f) throw InputError(path, 0, "", "cannot write STL file");
  char header[80] = {};
  std::strncpy(header, "chutelab binary STL", sizeof header - 1);
  f.write(header, 80);
  const auto n = static_cast<std::uint32_t>(mesh.triangles.size());
  f.write(reinterpret_cast<const char*>(&n), 4);
  for (const auto& t : mesh.triangles) {
    const Vec3& a = mesh.vertices[static_cast<std::size_t>(t[0])];
    const Vec3& b = mesh.vertices[static_cast<std::size_t>(t[1])];
    const Vec3& c = mesh.vertices[static_cast<std::size_t>(t[2])];
    Vec3 nrm = (b - a).cross(c - a);
    if (nrm.norm() > 0) nrm.normalize();
    float buf[12];
    const Vec3* vs[4] = {&nrm, &a, &b, &c};
    for (int k = 0; k < 4; ++k)
      for (int d = 0; d < 3; ++d) buf[3 * k + d] = static_cast<float>((*vs[k])[d]);
    f.write(reinterpret_cast<const char*>(buf), sizeof buf);
    const std::uint16_t attr = 0;
    f.write(reinterpret_cast<const char*>(&attr), 2);
  }
}

}  // namespace chutelab::dem
