#pragma once
// What a folder holds, to prove a command changed nothing it should not have: the tests of outputs,
// hardening and reliability compare a tree before and after a run.
#include <filesystem>
#include <map>
#include <string>
#include <system_error>

#include "cli_runner.h"

namespace chutelab::test {

// Every entry under `root` (relative path -> bytes; folders "<dir>", links "<link>target"), the
// subtree `skip` left out. An absent root is an empty tree.
inline std::map<std::string, std::string> snapshot(const std::filesystem::path& root,
                                                   const std::filesystem::path& skip = {}) {
  namespace fs = std::filesystem;
  std::map<std::string, std::string> s;
  std::error_code ec;
  if (!fs::exists(fs::symlink_status(root, ec))) return s;
  for (auto it = fs::recursive_directory_iterator(root, fs::directory_options::none, ec);
       it != fs::recursive_directory_iterator(); it.increment(ec)) {
    if (!skip.empty() && it->path() == skip) {
      it.disable_recursion_pending();
      continue;
    }
    const auto rel = fs::relative(it->path(), root).string();
    if (it->is_symlink()) s[rel] = "<link>" + fs::read_symlink(it->path()).string();
    else if (it->is_directory()) s[rel] = "<dir>";
    else s[rel] = read_file(it->path());
  }
  return s;
}

// Whether a command left a staged output (core/output_folder.h's ".partial" names) anywhere under root.
inline bool staging_left(const std::filesystem::path& root) {
  namespace fs = std::filesystem;
  std::error_code ec;
  for (auto it = fs::recursive_directory_iterator(root, ec); !ec && it != fs::recursive_directory_iterator();
       it.increment(ec))
    if (it->path().filename().string().find(".partial") != std::string::npos) return true;
  return false;
}

}  // namespace chutelab::test
