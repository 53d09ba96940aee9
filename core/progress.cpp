#include "core/progress.h"

#include <sys/ioctl.h>
#include <unistd.h>

#include <atomic>
#include <cstdio>
#include <map>
#include <mutex>
#include <thread>
#include <utility>

namespace chutelab::progress {
namespace {

std::atomic<bool> g_quiet{false};
FieldNames g_mention_names;
thread_local bool t_in_job = false;

struct Screen {
  std::mutex m;
  std::string prefix;
  std::map<std::thread::id, std::string> parts;  // in thread-id order: stable while they run
  std::size_t shown = 0;                          // characters of the status line on screen
};

Screen& screen() {
  static Screen s;
  return s;
}

std::size_t columns() {
  winsize w{};
  if (ioctl(2, TIOCGWINSZ, &w) == 0 && w.ws_col > 10) return w.ws_col;
  return 80;
}

// Characters, not bytes: the line must fit the terminal's width or "\r" no longer returns to it.
std::string fit(const std::string& s, std::size_t width) {
  std::string o;
  std::size_t chars = 0;
  for (char c : s) {
    const bool starts = (static_cast<unsigned char>(c) & 0xC0) != 0x80;
    if (starts && ++chars > width) break;
    o += c;
  }
  return o;
}

std::size_t chars(const std::string& s) {
  std::size_t n = 0;
  for (char c : s) n += (static_cast<unsigned char>(c) & 0xC0) != 0x80;
  return n;
}

void erase(Screen& s) {
  if (s.shown == 0) return;
  std::fprintf(stderr, "\r%*s\r", static_cast<int>(s.shown), "");
  s.shown = 0;
}

void draw(Screen& s) {
  std::string text = s.prefix;
  for (const auto& [id, part] : s.parts) {
    if (part.empty()) continue;
    text += text.empty() ? part : "  |  " + part;
  }
  text = fit(text, columns() - 1);
  const std::size_t n = chars(text);
  std::fprintf(stderr, "\r%s", text.c_str());
  if (n < s.shown) std::fprintf(stderr, "%*s\r%s", static_cast<int>(s.shown - n), "", text.c_str());
  s.shown = n;
  std::fflush(stderr);
}

}  // namespace

Mode mode() {
  if (g_quiet) return Mode::quiet;
  static const bool tty = isatty(2) != 0;
  return tty ? Mode::terminal : Mode::log;
}

void set_quiet(bool q) { g_quiet = q; }
bool quiet() { return g_quiet; }

void set_mention_names(FieldNames names) { g_mention_names = std::move(names); }

void line(const std::string& text) {
  if (mode() == Mode::quiet) return;
  const std::string shown = said_text(text, g_mention_names);
  Screen& s = screen();
  const std::lock_guard<std::mutex> lock(s.m);
  erase(s);
  std::fprintf(stderr, "%s\n", shown.c_str());
  if (mode() == Mode::terminal && (!s.prefix.empty() || !s.parts.empty())) draw(s);
  std::fflush(stderr);
}

void status(const std::string& text) {
  if (mode() != Mode::terminal) return;
  Screen& s = screen();
  const std::lock_guard<std::mutex> lock(s.m);
  if (text.empty()) s.parts.erase(std::this_thread::get_id());
  else s.parts[std::this_thread::get_id()] = text;
  draw(s);
}

void status_prefix(const std::string& text) {
  if (mode() != Mode::terminal) return;
  Screen& s = screen();
  const std::lock_guard<std::mutex> lock(s.m);
  s.prefix = text;
  draw(s);
}

void clear() {
  if (mode() != Mode::terminal) return;
  Screen& s = screen();
  const std::lock_guard<std::mutex> lock(s.m);
  s.prefix.clear();
  s.parts.clear();
  erase(s);
  std::fflush(stderr);
}

bool in_campaign_job() { return t_in_job; }

CampaignJobScope::CampaignJobScope() : was_(t_in_job) { t_in_job = true; }
CampaignJobScope::~CampaignJobScope() { t_in_job = was_; }

}  // namespace chutelab::progress
