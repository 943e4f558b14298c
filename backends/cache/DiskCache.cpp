#include "DiskCache.h"

#include <unistd.h>

#include <algorithm>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <sstream>
#include <thread>

#include "rill/ir/Hash.h"

namespace rill::cache {

namespace fs = std::filesystem;

namespace {

constexpr char kMagic[8] = {'R', 'I', 'L', 'L', 'K', 'C', 'E', '\0'};
constexpr uint32_t kVersion = 1;
constexpr const char* kSuffix = ".rill";
constexpr const char* kTempMark = ".rill.tmp.";

struct Header {
  char magic[8];
  uint32_t version;
  uint32_t key_bytes;
  uint64_t payload_bytes;
  uint64_t checksum;
};
static_assert(sizeof(Header) == 32, "the entry header is 32 bytes, without padding");

std::string env(const char* name) {
  const char* v = std::getenv(name);
  return v ? std::string(v) : std::string();
}

uint64_t checksum(std::string_view payload) {
  return ir::hash_bytes(payload);
}

bool is_entry(const fs::path& p) {
  const std::string name = p.filename().string();
  return p.extension() == kSuffix && name.find('-') != std::string::npos;
}

// A shared object of the cpu backend's cache before this module: <16 hex digits>.so.
bool is_legacy_shared_object(const fs::path& p) {
  const std::string stem = p.stem().string();
  return p.extension() == ".so" && stem.size() == 16 &&
         stem.find_first_not_of("0123456789abcdef") == std::string::npos;
}

// Writes `bytes` to `path` through a temporary file renamed into place.
bool write_atomically(const fs::path& path, std::string_view head, std::string_view key,
                      std::string_view payload) {
  std::ostringstream tag;
  tag << path.filename().string() << ".tmp." << getpid() << "."
      << std::hash<std::thread::id>{}(std::this_thread::get_id());
  const fs::path tmp = path.parent_path() / tag.str();
  std::error_code ec;
  {
    std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
    out.write(head.data(), static_cast<std::streamsize>(head.size()));
    out.write(key.data(), static_cast<std::streamsize>(key.size()));
    out.write(payload.data(), static_cast<std::streamsize>(payload.size()));
    out.flush();
    if (!out) {
      out.close();
      fs::remove(tmp, ec);
      return false;
    }
  }
  fs::rename(tmp, path, ec);
  if (ec) {
    fs::remove(tmp, ec);
    return false;
  }
  return true;
}

}  // namespace

std::string directory() {
  std::string dir = env("RILL_CACHE_DIR");
  if (!dir.empty()) return dir;
  std::string xdg = env("XDG_CACHE_HOME"), home = env("HOME");
  if (!xdg.empty()) return xdg + "/rill";
  if (!home.empty()) return home + "/.cache/rill";
  return (fs::temp_directory_path() / "rill-cache").string();
}

uint64_t max_bytes() {
  const std::string mb = env("RILL_CACHE_MAX_MB");
  uint64_t n = 1024;
  if (!mb.empty()) {
    char* end = nullptr;
    unsigned long long v = std::strtoull(mb.c_str(), &end, 10);
    // A malformed value keeps the default rather than meaning "no cache" or "unbounded".
    if (end && *end == '\0' && v > 0) n = v;
  }
  return n << 20;
}

std::string source_line(std::string_view source) {
  return "source=" + ir::hex(ir::hash_bytes(source)) +
         ir::hex(ir::hash_bytes(source, 0x84222325cbf29ce4ull)) + "\n";
}

fs::path entry_path(const std::string& backend, const std::string& key_text) {
  return fs::path(directory()) / (backend + "-" + ir::hex(ir::hash_bytes(key_text)) + kSuffix);
}

std::optional<std::string> load(const std::string& backend, const std::string& key_text) {
  const fs::path path = entry_path(backend, key_text);
  std::ifstream in(path, std::ios::binary);
  if (!in) return std::nullopt;
  std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  in.close();
  Header h{};
  const bool valid = [&] {
    if (bytes.size() < sizeof h) return false;
    std::memcpy(&h, bytes.data(), sizeof h);
    if (std::memcmp(h.magic, kMagic, sizeof kMagic) != 0 || h.version != kVersion) return false;
    if (bytes.size() != sizeof h + uint64_t{h.key_bytes} + h.payload_bytes) return false;
    if (std::string_view(bytes).substr(sizeof h, h.key_bytes) != key_text) return false;
    return checksum(std::string_view(bytes).substr(sizeof h + h.key_bytes)) == h.checksum;
  }();
  std::error_code ec;
  if (!valid) {
    // Truncated, corrupt, an older format or another key: never used, rebuilt by the caller.
    fs::remove(path, ec);
    return std::nullopt;
  }
  fs::last_write_time(path, fs::file_time_type::clock::now(), ec);  // the LRU clock
  return bytes.substr(sizeof h + h.key_bytes);
}

bool store(const std::string& backend, const std::string& key_text, std::string_view payload) {
  const fs::path path = entry_path(backend, key_text);
  std::error_code ec;
  fs::create_directories(path.parent_path(), ec);
  if (ec) return false;
  Header h{};
  std::memcpy(h.magic, kMagic, sizeof kMagic);
  h.version = kVersion;
  h.key_bytes = static_cast<uint32_t>(key_text.size());
  h.payload_bytes = payload.size();
  h.checksum = checksum(payload);
  const bool written = write_atomically(
      path, std::string_view(reinterpret_cast<const char*>(&h), sizeof h), key_text, payload);
  evict(max_bytes());
  return written;
}

void remove(const std::string& backend, const std::string& key_text) {
  std::error_code ec;
  fs::remove(entry_path(backend, key_text), ec);
}

std::vector<Entry> list() {
  std::vector<Entry> entries;
  std::error_code ec;
  for (fs::directory_iterator it(directory(), ec), end; !ec && it != end; it.increment(ec)) {
    const fs::path& p = it->path();
    if (!is_entry(p)) continue;
    Entry e;
    std::error_code stat_ec;
    e.bytes = it->file_size(stat_ec);
    e.last_use = it->last_write_time(stat_ec);
    if (stat_ec) continue;  // removed meanwhile by another process
    const std::string name = p.filename().string();
    e.backend = name.substr(0, name.rfind('-'));
    e.path = p;
    entries.push_back(std::move(e));
  }
  std::sort(entries.begin(), entries.end(),
            [](const Entry& a, const Entry& b) { return a.last_use < b.last_use; });
  return entries;
}

size_t evict(uint64_t bound) {
  std::vector<Entry> entries = list();
  uint64_t total = 0;
  for (const Entry& e : entries) total += e.bytes;
  if (total <= bound) return 0;
  const uint64_t target = bound / 10 * 9;
  size_t removed = 0;
  std::error_code ec;
  for (const Entry& e : entries) {
    if (total <= target) break;
    if (fs::remove(e.path, ec)) ++removed;
    total -= e.bytes;
  }
  return removed;
}

size_t clear() {
  size_t removed = 0;
  std::error_code ec;
  for (fs::directory_iterator it(directory(), ec), end; !ec && it != end; it.increment(ec)) {
    const fs::path p = it->path();
    std::error_code rm;
    if (is_entry(p)) {
      if (fs::remove(p, rm)) ++removed;
    } else if (p.filename().string().find(kTempMark) != std::string::npos ||
               is_legacy_shared_object(p)) {
      fs::remove(p, rm);
    }
  }
  return removed;
}

}  // namespace rill::cache
