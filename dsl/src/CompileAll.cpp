// compile_all(): several compile() calls at once (see Kernel.h).
//
// Most of a compile is waiting: the cpu and simd backends run the C compiler as a separate
// process, OpenCL drivers build programs on threads of their own. oneTBB runs the requests as
// tasks; backends that must stay on one thread (a GL context, Backend::single_threaded) are
// compiled on the calling thread meanwhile, one at a time, so they still overlap with the rest.
// The kernel cache (Kernel.cpp) makes identical requests build once.
#include <tbb/task_group.h>

#include <exception>

#include "CompileProgress.h"
#include "rill/Kernel.h"

namespace rill {

std::vector<Kernel> compile_all(const std::vector<CompileRequest>& requests) {
  std::vector<Kernel> kernels(requests.size());
  std::vector<std::exception_ptr> errors(requests.size());
  // One batch for the compile observer (Kernel.h): every request counts as done when its
  // compile returns or fails, whether it was built or came from a cache.
  std::string driver;
  if (!requests.empty()) {
    try {
      driver = backend(requests[0].backend).driver_label();
    } catch (...) {  // an unknown backend fails below, as a compile
    }
  }
  detail::CompileBatch batch(requests.empty() ? std::string() : requests[0].backend, driver,
                             static_cast<int>(requests.size()));
  auto one = [&](size_t i) {
    bool& in_batch = detail::in_compile_batch();
    const bool outer = in_batch;
    in_batch = true;
    try {
      kernels[i] = compile(requests[i].program, requests[i].backend, requests[i].options);
    } catch (...) {
      errors[i] = std::current_exception();
    }
    in_batch = outer;
    batch.done();
  };
  // Backends are looked up here, on one thread, so an unknown name fails like a compile.
  std::vector<size_t> here;
  tbb::task_group tasks;
  for (size_t i = 0; i < requests.size(); ++i) {
    bool single_threaded = false;
    try {
      single_threaded = backend(requests[i].backend).single_threaded();
    } catch (...) {
      errors[i] = std::current_exception();
      batch.done();
      continue;
    }
    if (single_threaded)
      here.push_back(i);
    else
      tasks.run([&one, i] { one(i); });
  }
  for (size_t i : here) one(i);
  tasks.wait();
  batch.finish();

  for (size_t i = 0; i < requests.size(); ++i) {
    if (!errors[i]) continue;
    const Program& p = requests[i].program;
    const std::string what = "compile_all(): program '" + (p.valid() ? p.name() : "(empty)") +
                             "' for backend '" + requests[i].backend + "': ";
    try {
      std::rethrow_exception(errors[i]);
    } catch (const std::exception& e) {  // rill::Error, or the library's (std::bad_alloc)
      throw Error(what + e.what());
    }
  }
  return kernels;
}

}  // namespace rill
