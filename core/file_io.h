// Reading whole files and writing outputs atomically.
//
// Nothing is lost and no partial output is left: every output is written to a temporary file in the
// target folder and renamed over the target only once it is complete. The path "-" means standard
// output (data only ever goes to stdout when asked for).
#pragma once

#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

namespace cinepath {

// Whole file as bytes; InputError("<path>: cannot read: <reason>") when it cannot be opened.
std::string ReadFileToString(const std::filesystem::path& path);

// Atomically replaces `path` with `contents` ("-" writes to stdout). RuntimeError on I/O failure;
// the target is then left untouched.
void WriteFileAtomic(const std::filesystem::path& path, std::string_view contents);

// Several outputs that land together: each is staged as a temporary file beside its target as it is
// added; Commit() renames them all. If Commit() is never reached (an exception), the destructor
// removes the staged files, so a failed run leaves nothing behind.
class AtomicOutputs {
 public:
  AtomicOutputs() = default;
  AtomicOutputs(const AtomicOutputs&) = delete;
  AtomicOutputs& operator=(const AtomicOutputs&) = delete;
  ~AtomicOutputs();

  void Add(const std::filesystem::path& path, std::string_view contents);
  void Commit();

 private:
  struct Staged {
    std::filesystem::path temp;
    std::filesystem::path target;
  };
  std::vector<Staged> staged_;
  std::vector<std::pair<std::string, std::string>> to_stdout_;
};

// Creates the folder (and parents) for an output directory; RuntimeError when impossible.
void EnsureDirectory(const std::filesystem::path& dir);

}  // namespace cinepath
