// Compiling generated C into a shared object with the system C compiler, cached on disk.
//
// The cache key is a hash of the source and of the compiler command, so a kernel compiled
// once is loaded from disk by every later process (the first use in a fresh cache costs a
// compiler run, typically tens of milliseconds). Files are written under a temporary name
// and renamed into place, so concurrent processes sharing the cache never see half a file.
//
// Where: $RILL_CACHE_DIR, else $XDG_CACHE_HOME/rill, else ~/.cache/rill.
// Which compiler: $RILL_CC, else the C compiler Rill was built with, else `cc`.
#pragma once

#include <string>
#include <vector>

namespace rill::cpu {

struct SharedObject {
  void* handle = nullptr;  // from dlopen
  void* symbol = nullptr;  // the requested entry point
  bool from_disk_cache = false;
  std::string path;
};

// Compiles `source` with `flags` (or finds it in the cache), loads it and looks up `entry`.
// Throws rill::Error with the compiler's messages and the numbered source on failure.
SharedObject compile_shared_object(const std::string& source, const std::vector<std::string>& flags,
                                   const std::string& entry);

std::string cache_directory();
std::string c_compiler();

}  // namespace rill::cpu
