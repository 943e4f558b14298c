// Rill's disk cache of compiled kernels, shared by every backend (cpu and simd shared objects,
// OpenCL program binaries, GL program binaries) and by every process of the user.
//
// An entry is one file, <backend>-<hash of the key text>.rill, holding a header and the
// payload (the backend's binary):
//   magic "RILLKCE\0", format version (u32), key text length (u32), payload length (u64),
//   payload checksum (u64), the key text, the payload.
// The key text is the whole key, one "name=value" line each: the backend, the device and
// driver identity, the compile options and a 128-bit hash of the generated source. Keeping
// all of it in the entry means a file-name hash collision, or a file copied from another
// machine or driver, is detected by comparing the text rather than trusted. Every backend's
// key has a "driver=" line (the C compiler command, CL_DRIVER_VERSION, GL_VERSION).
//
// Robustness: load() checks the magic, version, key text, lengths against the file size and
// the payload checksum; a file that fails any check (truncated by a full disk, corrupted,
// another key) is removed and reported as a miss, so the caller rebuilds and stores afresh.
// Writes go to a temporary name unique to the process and thread and are renamed into place,
// so processes sharing the cache never read half a file.
//
// Bound: $RILL_CACHE_MAX_MB megabytes (default 1024). A hit refreshes the entry's
// modification time (its last use); after a store that takes the total over the bound, the
// least recently used entries are deleted until the total is at 90% of it.
//
// Where: $RILL_CACHE_DIR, else $XDG_CACHE_HOME/rill, else ~/.cache/rill.
#pragma once

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace rill::cache {

// The cache directory (not created).
std::string directory();
// The size bound in bytes ($RILL_CACHE_MAX_MB, default 1024 MB).
uint64_t max_bytes();

// "source=<32 hex digits>": a 128-bit hash of a generated source, for key texts.
std::string source_line(std::string_view source);

// The path of the entry for (backend, key text).
std::filesystem::path entry_path(const std::string& backend, const std::string& key_text);

// The payload stored for (backend, key text), after checking the whole entry; refreshes its
// last use. A missing entry is nullopt; a damaged or mismatched one is removed, then nullopt.
std::optional<std::string> load(const std::string& backend, const std::string& key_text);

// Stores a payload (atomically replacing any entry of that key), then evicts down to the
// bound. Failures to write (a read-only or full disk) are not errors: the kernel was built
// and works; it is just not cached. Returns whether the entry was written.
bool store(const std::string& backend, const std::string& key_text, std::string_view payload);

// Removes an entry (a binary the driver refused to load).
void remove(const std::string& backend, const std::string& key_text);

struct Entry {
  std::string backend;
  std::filesystem::path path;
  uint64_t bytes = 0;
  std::filesystem::file_time_type last_use;
};
// Every entry in the cache directory, least recently used first.
std::vector<Entry> list();

// Deletes least recently used entries while the total exceeds `bound` bytes, down to 90% of
// it. Returns the number deleted. store() calls it with max_bytes().
size_t evict(uint64_t bound);

// Deletes every entry (and temporary files left by interrupted writes, and the shared objects
// of the cpu backend's earlier cache format, <16 hex digits>.so); returns how many entries
// were deleted. Other files in the directory are left alone.
size_t clear();

}  // namespace rill::cache
