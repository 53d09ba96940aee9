#pragma once
// What chutelab wrote in an output folder, kept in the folder itself (OUT/.chutelab-manifest), so
// that a later command replaces or removes only its own files: a file's name says nothing about who
// made it (a user's own dem/ folder or tolerances.toml inside --out is theirs, and so is a report
// they edited). Every file is recorded with the command that wrote it, its size, its modification
// time and a hash of its content; every folder chutelab created, with its command. A file is still
// chutelab's when its size and time are the recorded ones or, after a copy that changed its time,
// its content is (the hash). Anything the manifest does not list, or lists with another content, is
// the user's.
//
// The manifest is replaced as a whole, by rename, with the files it lists (core/output_folder.h). A
// manifest that cannot be read, or a line of it that cannot, counts as listing nothing: chutelab
// then takes nothing in the folder for its own, which can make it refuse, never remove.
#include <cstdint>
#include <filesystem>
#include <map>
#include <string>
#include <string_view>

namespace chutelab {

struct OutputRecord {
  std::string command;  // the command that wrote it: validate, diagnose, simulate, synthesize, ...
  bool folder = false;  // a folder chutelab created (removed with its command's files once empty)
  std::uint64_t size = 0;
  std::int64_t mtime_ns = 0;
  std::uint64_t hash = 0;
};

struct OutputManifest {
  static constexpr const char* kFileName = ".chutelab-manifest";
  // Relative paths inside the folder, components joined by '/'.
  std::map<std::string, OutputRecord> records;

  static OutputManifest read(const std::filesystem::path& folder);
  std::string text() const;
  // Whether the entry at `path` is the file (or folder) `r` records.
  static bool intact(const std::filesystem::path& path, const OutputRecord& r);
  // The record of a regular file as it is now.
  static OutputRecord of_file(const std::filesystem::path& path, std::string command);
};

// A 64-bit FNV-1a hash of a file's bytes (0 when it cannot be read). A check against edits and
// copies, not against an adversary: the folder is the user's own.
std::uint64_t content_hash(const std::filesystem::path& path);

}  // namespace chutelab
