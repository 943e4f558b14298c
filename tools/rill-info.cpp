// rill-info: which backends this build has, whether each can run here, and on what.
//
//   $ rill-info
//   cpu     ok   cpu: generated C compiled by /usr/bin/cc, 2 threads (oneTBB), cache ...
//   opencl  ok   opencl: Portable Computing Language / pthread-haswell-... (OpenCL 3.0 PoCL)
//     OpenCL devices (choose with RILL_OPENCL_DEVICE=P:D or a name fragment):
//       0:0  Portable Computing Language / pthread-haswell-...  fp64
//     Vulkan devices (choose with RILL_VULKAN_DEVICE=N or a name fragment):
//       0  llvmpipe (LLVM 15.0.6, 256 bits)  CPU  Vulkan 1.3.230  subgroups of 8  <- used: ...
//
//   $ rill-info --cache           the kernel disk cache: directory, bound, entries per backend
//   $ rill-info --cache --clear   empties it
#include <cstdio>
#include <cstring>
#include <exception>
#include <map>
#include <string>

#include "cache/DiskCache.h"
#include "rill/rill.h"
#ifdef RILL_HAVE_OPENCL
#include "opencl/OpenCLBackend.h"
#endif
#ifdef RILL_HAVE_VULKAN
#include "vulkan/VulkanBackend.h"
#endif

namespace {

const char* kHelp =
    "usage: rill-info [--cache [--clear]]\n"
    "\n"
    "Without options: the backends of this build, whether each can run here, and on what.\n"
    "\n"
    "  --cache   show Rill's disk cache of compiled kernels (shared objects for cpu and simd,\n"
    "            program binaries for opencl and glsl): its directory, its size bound and\n"
    "            each backend's entries. An entry is keyed by the generated source, the\n"
    "            backend, the device and driver identity and the compile options.\n"
    "  --clear   with --cache: delete every entry\n"
    "  --help    this text\n"
    "\n"
    "Environment:\n"
    "  RILL_CACHE_DIR      the cache directory (default $XDG_CACHE_HOME/rill, else\n"
    "                      ~/.cache/rill)\n"
    "  RILL_CACHE_MAX_MB   the size bound in MB (default 1024); the least recently used\n"
    "                      entries are deleted beyond it\n";

std::string megabytes(uint64_t bytes) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.1f MB", static_cast<double>(bytes) / (1 << 20));
  return buf;
}

int show_cache(bool clear) {
  std::printf("cache    %s\n", rill::cache::directory().c_str());
  std::printf("bound    %s (RILL_CACHE_MAX_MB)\n", megabytes(rill::cache::max_bytes()).c_str());
  if (clear) {
    size_t n = rill::cache::clear();
    std::printf("cleared  %zu entr%s\n", n, n == 1 ? "y" : "ies");
    return 0;
  }
  struct Total {
    size_t entries = 0;
    uint64_t bytes = 0;
  };
  std::map<std::string, Total> per_backend;
  Total all;
  for (const rill::cache::Entry& e : rill::cache::list()) {
    Total& t = per_backend[e.backend];
    ++t.entries;
    t.bytes += e.bytes;
    ++all.entries;
    all.bytes += e.bytes;
  }
  for (const auto& [backend, t] : per_backend)
    std::printf("  %-12s %6zu entries  %10s\n", backend.c_str(), t.entries,
                megabytes(t.bytes).c_str());
  std::printf("  %-12s %6zu entries  %10s\n", "total", all.entries, megabytes(all.bytes).c_str());
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  bool cache = false, clear = false;
  for (int i = 1; i < argc; ++i) {
    if (!std::strcmp(argv[i], "--cache")) {
      cache = true;
    } else if (!std::strcmp(argv[i], "--clear")) {
      clear = true;
    } else if (!std::strcmp(argv[i], "--help") || !std::strcmp(argv[i], "-h")) {
      std::fputs(kHelp, stdout);
      return 0;
    } else {
      std::fprintf(stderr, "rill-info: unknown option '%s'\n%s", argv[i], kHelp);
      return 2;
    }
  }
  if (clear && !cache) {
    std::fprintf(stderr, "rill-info: --clear goes with --cache (rill-info --cache --clear)\n");
    return 2;
  }
  try {
    if (cache) return show_cache(clear);
    for (rill::Backend* b : rill::backends()) {
      std::string why = b->unavailable_reason();
      std::printf("%-12s %-4s %s\n", b->name().c_str(), why.empty() ? "ok" : "--",
                  why.empty() ? b->description().c_str() : why.c_str());
      if (why.empty())
        for (rill::Accuracy a :
             {rill::Accuracy::Strict, rill::Accuracy::Fast, rill::Accuracy::Double})
          if (std::string note = b->accuracy_note(a); !note.empty() && b->supports(a))
            std::printf("%-12s      %s: %s\n", "", rill::accuracy_name(a), note.c_str());
    }
#ifdef RILL_HAVE_OPENCL
    auto devices = rill::opencl::list_devices();
    if (!devices.empty()) {
      std::printf("  OpenCL devices (choose with RILL_OPENCL_DEVICE=P:D or a name fragment):\n");
      for (const auto& d : devices)
        std::printf("    %d:%d  %s / %s  %s%s\n", d.platform, d.device, d.platform_name.c_str(),
                    d.device_name.c_str(), d.version.c_str(), d.fp64 ? "  fp64" : "");
    }
#endif
#ifdef RILL_HAVE_VULKAN
    const std::vector<std::string> vulkan = rill::vk::device_lines();
    for (size_t i = 0; i < vulkan.size(); ++i)
      std::printf("%s%s\n", i ? "    " : "  ", vulkan[i].c_str());
#endif
    return 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "rill-info: %s\n", e.what());
    return 1;
  }
}
