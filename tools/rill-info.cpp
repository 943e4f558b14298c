// rill-info: which backends this build has, whether each can run here, and on what.
//
//   $ rill-info
//   cpu     ok   cpu: generated C compiled by /usr/bin/cc, 2 threads (oneTBB), cache ...
//   opencl  ok   opencl: Portable Computing Language / pthread-haswell-... (OpenCL 3.0 PoCL)
//     OpenCL devices (choose with RILL_OPENCL_DEVICE=P:D or a name fragment):
//       0:0  Portable Computing Language / pthread-haswell-...  fp64
#include <cstdio>
#include <exception>

#include "rill/rill.h"
#ifdef RILL_HAVE_OPENCL
#include "opencl/OpenCLBackend.h"
#endif

int main() {
  try {
    for (rill::Backend* b : rill::backends()) {
      std::string why = b->unavailable_reason();
      std::printf("%-8s %-4s %s\n", b->name().c_str(), why.empty() ? "ok" : "--",
                  why.empty() ? b->description().c_str() : why.c_str());
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
    return 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "rill-info: %s\n", e.what());
    return 1;
  }
}
