#include "core/output_manifest.h"

#include <fmt/format.h>
#include <sys/stat.h>

#include <array>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <vector>

namespace chutelab {
namespace fs = std::filesystem;

namespace {

constexpr const char* kHeader =
    "# chutelab output manifest 1: the files and folders chutelab wrote here, so that it replaces or removes\n"
    "# only these. A file changed since (other size and content) is no longer chutelab's. Do not edit.\n";
// Far above any real folder's list (a simulate with VTK frames lists a few hundred files).
constexpr std::uintmax_t kMaxBytes = std::uintmax_t{64} << 20;

// Bytes a line could not hold as they are: controls, space, DEL, '%' itself.
std::string escaped(std::string_view s) {
  std::string o;
  for (unsigned char c : s) {
    if (c <= 0x20 || c == 0x7F || c == '%') o += fmt::format("%{:02X}", c);
    else o += static_cast<char>(c);
  }
  return o;
}

int hex(char c) {
  if (c >= '0' && c <= '9') return c - '0';
  if (c >= 'A' && c <= 'F') return c - 'A' + 10;
  if (c >= 'a' && c <= 'f') return c - 'a' + 10;
  return -1;
}

bool unescaped(std::string_view s, std::string& o) {
  o.clear();
  for (std::size_t i = 0; i < s.size(); ++i) {
    if (s[i] != '%') {
      o += s[i];
      continue;
    }
    if (i + 2 >= s.size()) return false;
    const int a = hex(s[i + 1]), b = hex(s[i + 2]);
    if (a < 0 || b < 0) return false;
    o += static_cast<char>(a * 16 + b);
    i += 2;
  }
  return true;
}

// A path of plain components below the folder: never absolute, never "..", never empty parts, so a
// line of the manifest (which anyone who can write in the folder can edit) never names a file
// outside it.
bool plain_relative(const std::string& p) {
  if (p.empty() || p.front() == '/') return false;
  std::size_t start = 0;
  while (start <= p.size()) {
    const auto end = p.find('/', start);
    const std::string_view c = std::string_view(p).substr(start, end == std::string::npos ? std::string::npos : end - start);
    if (c.empty() || c == "." || c == "..") return false;
    if (end == std::string::npos) break;
    start = end + 1;
  }
  return true;
}

bool whole_number(std::string_view s, std::uint64_t& v, bool hexadecimal = false) {
  if (s.empty() || s.size() > 20) return false;
  v = 0;
  for (char c : s) {
    const int d = hexadecimal ? hex(c) : (c >= '0' && c <= '9' ? c - '0' : -1);
    if (d < 0) return false;
    v = v * (hexadecimal ? 16 : 10) + static_cast<unsigned>(d);
  }
  return true;
}

std::vector<std::string_view> fields(std::string_view line) {
  std::vector<std::string_view> f;
  std::size_t start = 0;
  while (true) {
    const auto end = line.find('\t', start);
    f.push_back(line.substr(start, end == std::string_view::npos ? std::string_view::npos : end - start));
    if (end == std::string_view::npos) break;
    start = end + 1;
  }
  return f;
}

bool lstat_of(const fs::path& p, struct stat& st) { return ::lstat(p.c_str(), &st) == 0; }

std::int64_t mtime_ns(const struct stat& st) {
  return static_cast<std::int64_t>(st.st_mtim.tv_sec) * 1000000000 + static_cast<std::int64_t>(st.st_mtim.tv_nsec);
}

}  // namespace

std::uint64_t content_hash(const fs::path& path) {
  std::FILE* f = std::fopen(path.c_str(), "rb");
  if (!f) return 0;
  std::uint64_t h = 1469598103934665603ull;
  std::array<unsigned char, 1 << 16> buf;
  for (std::size_t n; (n = std::fread(buf.data(), 1, buf.size(), f)) > 0;)
    for (std::size_t i = 0; i < n; ++i) h = (h ^ buf[i]) * 1099511628211ull;
  std::fclose(f);
  return h;
}

OutputManifest OutputManifest::read(const fs::path& folder) {
  OutputManifest m;
  const fs::path file = folder / kFileName;
  struct stat st {};
  // Only a plain file of a sane size: a link, a FIFO or a device there lists nothing.
  if (!lstat_of(file, st) || !S_ISREG(st.st_mode) || static_cast<std::uintmax_t>(st.st_size) > kMaxBytes) return m;
  std::ifstream in(file, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  const std::string text = ss.str();
  std::size_t start = 0;
  std::string path;
  while (start < text.size()) {
    auto end = text.find('\n', start);
    if (end == std::string::npos) break;  // a last line without its end was cut short: not trusted
    const std::string_view line = std::string_view(text).substr(start, end - start);
    start = end + 1;
    if (line.empty() || line.front() == '#') continue;
    const auto f = fields(line);
    OutputRecord r;
    if (f.size() == 6 && f[0] == "file") {
      std::uint64_t mt = 0;
      if (!whole_number(f[2], r.size) || !whole_number(f[3], mt) || !whole_number(f[4], r.hash, true) ||
          f[4].size() != 16 || !unescaped(f[5], path))
        continue;
      r.mtime_ns = static_cast<std::int64_t>(mt);
    } else if (f.size() == 3 && f[0] == "folder") {
      r.folder = true;
      if (!unescaped(f[2], path)) continue;
    } else {
      continue;
    }
    if (f[1].empty() || !plain_relative(path) || path == kFileName) continue;
    r.command = std::string(f[1]);
    m.records[path] = std::move(r);
  }
  return m;
}

std::string OutputManifest::text() const {
  std::string o = kHeader;
  for (const auto& [path, r] : records) {
    if (r.folder) o += fmt::format("folder\t{}\t{}\n", escaped(r.command), escaped(path));
    else
      o += fmt::format("file\t{}\t{}\t{}\t{:016x}\t{}\n", escaped(r.command), r.size, r.mtime_ns, r.hash, escaped(path));
  }
  return o;
}

bool OutputManifest::intact(const fs::path& path, const OutputRecord& r) {
  struct stat st {};
  if (!lstat_of(path, st)) return false;
  if (r.folder) return S_ISDIR(st.st_mode);
  if (!S_ISREG(st.st_mode) || static_cast<std::uint64_t>(st.st_size) != r.size) return false;
  return mtime_ns(st) == r.mtime_ns || content_hash(path) == r.hash;
}

OutputRecord OutputManifest::of_file(const fs::path& path, std::string command) {
  OutputRecord r;
  r.command = std::move(command);
  struct stat st {};
  if (lstat_of(path, st)) {
    r.size = static_cast<std::uint64_t>(st.st_size);
    r.mtime_ns = mtime_ns(st);
  }
  r.hash = content_hash(path);
  return r;
}

}  // namespace chutelab
