// Compiling generated C into a shared object with the system C compiler, cached on disk.
//
// The shared objects live in Rill's disk cache (cache/DiskCache.h), keyed by the backend
// (cpu or simd), the compiler command with its flags ("driver=") and a hash of the source, so
// a kernel compiled once is loaded from disk by every later process (the first use in a
// fresh cache costs a compiler run, typically tens of milliseconds).
//
// Loading: a corrupt ELF file can crash the dynamic loader, so a shared object is never
// dlopen'ed from the cache file itself. The entry is read and its checksum verified first
// (DiskCache::load), then the verified bytes are written to an anonymous memory file
// (memfd_create) and loaded as /proc/self/fd/N: what is loaded is exactly what was checked,
// with no window in which another process could change the file between check and load.
// glibc recognizes an already loaded object by its path name, so the memory file stays
// open while the object is loaded (release() closes both): no two live kernels can have the
// same /proc/self/fd/N name. A fresh compile takes the same path, after storing the entry.
//
// Which compiler: $RILL_CC, else the C compiler Rill was built with, else `cc`.
//
// Profiling: with RILL_PROFILE_DIR set, each kernel is compiled with debug information into
// that directory instead, as BACKEND-KERNEL-HASH.c and .so, and dlopen'ed from there (files
// the user asked for, not the cache's). A profiler then maps samples in the kernel to lines
// of the generated C: perf report and annotate, valgrind --tool=callgrind, gdb. From a memory
// file they see only addresses. Unlike cache entries, these files carry no checksum: a later
// run reuses a .so whose .c matches its source, compiling it again only if the loader
// refuses it (the directory is the developer's own; deleting it starts afresh).
#pragma once

#include <string>
#include <vector>

namespace rill::cpu {

struct SharedObject {
  void* handle = nullptr;        // from dlopen
  void* symbol = nullptr;        // the requested entry point
  int fd = -1;                   // the memory file the object was loaded from (see above)
  bool from_disk_cache = false;  // or, when profiling, an earlier run's file
  std::string path;              // the cache entry, or the file when profiling
};

// Compiles `source` with `flags` (or finds it in the cache entries of `backend`), loads it
// and looks up `entry`. Throws rill::Error with the compiler's messages and the numbered
// source on failure. `kernel` (the program's name) names the files when profiling. units > 1:
// the source is that many translation units (CEmitter.h's c_units), compiled at the same
// time and linked (when profiling, as the one translation unit it also is); the last
// cold_units of them with -O1 in place of flags' -O2 (CEmitter.h's c_cold_units; the source,
// which says so, is in the cache key).
SharedObject compile_shared_object(const std::string& backend, const std::string& kernel,
                                   const std::string& source, const std::vector<std::string>& flags,
                                   const std::string& entry, int units = 1, int cold_units = 0);
// Unloads the object and closes its memory file.
void release(SharedObject& so);

std::string cache_directory();
// $RILL_PROFILE_DIR, or "" when kernels are not compiled for profiling.
std::string profile_directory();
std::string c_compiler();

}  // namespace rill::cpu
