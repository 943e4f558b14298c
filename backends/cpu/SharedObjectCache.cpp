#include "SharedObjectCache.h"

#include <dlfcn.h>
#include <spawn.h>
#include <sys/mman.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <thread>

#include <fcntl.h>

#include "../cache/DiskCache.h"
#include "../codegen/SourceText.h"
#include "rill/Error.h"
#include "rill/ir/Hash.h"

extern char** environ;

namespace rill::cpu {

namespace fs = std::filesystem;

namespace {

std::string env(const char* name) {
  const char* v = std::getenv(name);
  return v ? std::string(v) : std::string();
}

std::string read_file(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

// Starts argv, with stdout and stderr going to `log`; returns its process id (-1: not run).
pid_t spawn(const std::vector<std::string>& argv, const fs::path& log) {
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, 1, log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  posix_spawn_file_actions_adddup2(&actions, 1, 2);
  std::vector<char*> args;
  for (const auto& a : argv) args.push_back(const_cast<char*>(a.c_str()));
  args.push_back(nullptr);
  pid_t pid;
  int rc = posix_spawnp(&pid, args[0], &actions, nullptr, args.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  return rc != 0 ? -1 : pid;
}

// Waits for a process spawn() started; returns its exit status (-1: not run).
int wait_for(pid_t pid) {
  if (pid < 0) return -1;
  int status = 0;
  while (waitpid(pid, &status, 0) < 0) {
    if (errno != EINTR) return -1;
  }
  if (WIFEXITED(status)) return WEXITSTATUS(status) == 127 ? -1 : WEXITSTATUS(status);
  return 128;
}

}  // namespace

std::string cache_directory() {
  return cache::directory();
}

std::string c_compiler() {
  std::string cc = env("RILL_CC");
  if (!cc.empty()) return cc;
#ifdef RILL_DEFAULT_CC
  if (fs::exists(RILL_DEFAULT_CC)) return RILL_DEFAULT_CC;
#endif
  return "cc";
}

namespace {

// Loads a verified shared object from memory (see the header: a memory file, never the
// cache file) and looks up `entry`. Returns an object without a handle, and dlerror()'s text
// in `why`, when the loader refuses it.
SharedObject load_from_memory(std::string_view bytes, const std::string& entry, std::string& why) {
  SharedObject so;
  so.fd = memfd_create("rill-kernel", MFD_CLOEXEC);
  if (so.fd < 0)
    throw Error(std::string("CPU backend: memfd_create failed: ") + std::strerror(errno));
  size_t done = 0;
  while (done < bytes.size()) {
    ssize_t n = write(so.fd, bytes.data() + done, bytes.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) {
      close(so.fd);
      throw Error(std::string("CPU backend: cannot write a kernel to memory: ") +
                  std::strerror(errno));
    }
    done += static_cast<size_t>(n);
  }
  const std::string name = "/proc/self/fd/" + std::to_string(so.fd);
  so.handle = dlopen(name.c_str(), RTLD_NOW | RTLD_LOCAL);
  if (!so.handle) {
    const char* e = dlerror();
    why = e ? e : "unknown error";
    close(so.fd);
    so.fd = -1;
    return so;
  }
  so.symbol = dlsym(so.handle, entry.c_str());
  if (!so.symbol) {
    why = "it has no '" + entry + "'";
    release(so);
  }
  return so;
}

}  // namespace

void release(SharedObject& so) {
  if (so.handle) dlclose(so.handle);
  if (so.fd >= 0) close(so.fd);
  so.handle = so.symbol = nullptr;
  so.fd = -1;
}

namespace {

// Temporary files of one compile, removed on every path out of its scope.
struct TemporaryFiles {
  std::vector<fs::path> paths;
  ~TemporaryFiles() {
    std::error_code ignored;
    for (const fs::path& p : paths) fs::remove(p, ignored);
  }
};

// Throws rill::Error for a compiler run that failed with status rc, with its messages and
// the numbered source.
void check_compile(int rc, const std::string& cc, const std::string& messages,
                   const std::string& source) {
  if (rc == 0) return;
  if (rc < 0)
    throw Error("CPU backend: the C compiler '" + cc +
                "' could not be run; install one (apt-get install gcc) or set RILL_CC");
  throw Error("CPU backend: the C compiler rejected the generated kernel (exit " +
              std::to_string(rc) + "):\n" + messages + "\ngenerated source:\n" +
              codegen::numbered(source));
}

// Runs the compiler and returns its status, its messages in `messages`.
int run_compiler(const std::vector<std::string>& argv, const fs::path& log, std::string& messages) {
  const int rc = wait_for(spawn(argv, log));
  messages = read_file(log);
  std::error_code ec;
  fs::remove(log, ec);
  return rc;
}

// Compiles the C file src (whose text is `source`) into out; throws rill::Error with the
// compiler's messages and the numbered source. The callers remove out (TemporaryFiles).
// A source of several translation units (CEmitter.h's c_units) is compiled once per unit,
// with -DRILL_TU=k, all units at the same time, and the objects linked into out; the last
// cold_units of them at -O1.
void compile_file(const std::string& cc, const std::vector<std::string>& flags, const fs::path& src,
                  const fs::path& out, const fs::path& log, const std::string& source,
                  int units = 1, int cold_units = 0) {
  std::string messages;
  if (units <= 1) {
    std::vector<std::string> argv{cc};
    argv.insert(argv.end(), flags.begin(), flags.end());
    argv.insert(argv.end(), {"-o", out.string(), src.string(), "-lm"});
    check_compile(run_compiler(argv, log, messages), cc, messages, source);
    return;
  }
  std::vector<fs::path> objects, logs;
  std::vector<pid_t> pids;
  TemporaryFiles temporaries;  // the objects
  for (int u = 0; u < units; ++u) {
    const std::string k = std::to_string(u);
    objects.push_back(out.string() + "." + k + ".o");
    temporaries.paths.push_back(objects.back());
    logs.push_back(log.string() + "." + k);
    std::vector<std::string> argv{cc};
    argv.insert(argv.end(), flags.begin(), flags.end());
    if (u >= units - cold_units)
      std::replace(argv.begin(), argv.end(), std::string("-O2"), std::string("-O1"));
    argv.insert(argv.end(), {"-c", "-DRILL_TU=" + k, "-o", objects.back().string(), src.string()});
    pids.push_back(spawn(argv, logs.back()));
  }
  int failed = 0;
  for (int u = 0; u < units; ++u) {
    const int rc = wait_for(pids[static_cast<size_t>(u)]);
    std::string m = read_file(logs[static_cast<size_t>(u)]);
    std::error_code ec;
    fs::remove(logs[static_cast<size_t>(u)], ec);
    if (rc != 0 && failed == 0) {
      failed = rc;
      messages = m;
    }
  }
  if (failed == 0) {
    std::vector<std::string> argv{cc};
    argv.insert(argv.end(), flags.begin(), flags.end());
    argv.insert(argv.end(), {"-o", out.string()});
    for (const fs::path& o : objects) argv.push_back(o.string());
    argv.push_back("-lm");
    failed = run_compiler(argv, log, messages);
  }
  check_compile(failed, cc, messages, source);
}

void write_text(const fs::path& p, const std::string& text) {
  std::ofstream file(p);
  file << text;
  if (!file) throw Error("CPU backend: cannot write '" + p.string() + "'");
}

// The compiler and its flags as one line: the cache key's "driver=" and the profile files'
// hash.
std::string compiler_command(const std::string& cc, const std::vector<std::string>& flags) {
  std::string command = cc;
  for (const auto& f : flags) command += " " + f;
  return command;
}

// A unique suffix for temporary files of this process and thread.
std::string temporary_tag() {
  std::ostringstream tag;
  tag << getpid() << "." << std::hash<std::thread::id>{}(std::this_thread::get_id());
  return tag.str();
}

// RILL_PROFILE_DIR (see the header): the kernel as NAME.c and NAME.so with debug
// information, loaded from that path so that a profiler finds both. A file from an earlier
// run is reused when its source is the same; the disk cache is not involved.
SharedObject compile_for_profiling(const fs::path& dir, const std::string& backend,
                                   const std::string& kernel, const std::string& source,
                                   std::vector<std::string> flags, const std::string& entry) {
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (ec)
    throw Error("CPU backend: cannot create the profile directory '" + dir.string() + "' (" +
                ec.message() + "); set RILL_PROFILE_DIR to a writable directory");
  // -g adds the line tables; it is meant not to change the generated code (GCC checks that
  // with -fcompare-debug), and for the ray tracer's megakernel objdump -d shows the same code
  // with and without it (GCC 12 and clang 14), so the profile is the kernel's.
  flags.push_back("-g");
  const std::string cc = c_compiler();
  const std::string command = compiler_command(cc, flags);
  // The program's name, cut to a length that leaves room in a file name for the rest.
  std::string name;
  for (char c : kernel.substr(0, 64)) name += std::isalnum(static_cast<unsigned char>(c)) ? c : '_';
  const std::string stem = backend + "-" + (name.empty() ? "kernel" : name) + "-" +
                           ir::hex(ir::hash_bytes(command + "\n" + source)).substr(0, 12);
  const fs::path c_path = dir / (stem + ".c"), so_path = dir / (stem + ".so");
  auto fail = [&](const std::string& what) {
    throw Error("CPU backend: cannot " + what + " in the profile directory '" + dir.string() +
                "' (" + ec.message() + ")");
  };
  auto build = [&] {
    // Written under temporary names and renamed into place, so that processes profiling at
    // the same time never read a half-written file. The compiler reads the source under its
    // final name, which the line tables then record; a kernel the compiler rejects leaves
    // its .c there, for reading beside the error.
    const std::string tmp = stem + ".tmp." + temporary_tag();
    const fs::path tmp_c = dir / (tmp + ".c"), tmp_so = dir / (tmp + ".so");
    const TemporaryFiles temporaries{{tmp_c, tmp_so}};
    write_text(tmp_c, source);
    fs::rename(tmp_c, c_path, ec);
    if (ec) fail("write '" + c_path.filename().string() + "'");
    compile_file(cc, flags, c_path, tmp_so, dir / (tmp + ".log"), source);
    fs::rename(tmp_so, so_path, ec);
    if (ec) fail("write '" + so_path.filename().string() + "'");
  };
  SharedObject so;
  so.from_disk_cache = fs::exists(so_path, ec) && read_file(c_path) == source;
  if (!so.from_disk_cache) build();
  so.handle = dlopen(so_path.c_str(), RTLD_NOW | RTLD_LOCAL);
  if (!so.handle && so.from_disk_cache) {
    // An earlier run's file the loader refuses (damaged, or from another system): made again.
    so.from_disk_cache = false;
    build();
    so.handle = dlopen(so_path.c_str(), RTLD_NOW | RTLD_LOCAL);
  }
  if (!so.handle) {
    const char* e = dlerror();
    throw Error("CPU backend: cannot load '" + so_path.string() +
                "': " + (e ? e : "unknown error"));
  }
  so.symbol = dlsym(so.handle, entry.c_str());
  if (!so.symbol) {
    release(so);
    throw Error("CPU backend: '" + so_path.string() + "' has no '" + entry + "'");
  }
  so.path = so_path.string();
  return so;
}

}  // namespace

std::string profile_directory() {
  return env("RILL_PROFILE_DIR");
}

SharedObject compile_shared_object(const std::string& backend, const std::string& kernel,
                                   const std::string& source, const std::vector<std::string>& flags,
                                   const std::string& entry, int units, int cold_units) {
  if (const std::string dir = profile_directory(); !dir.empty())
    return compile_for_profiling(dir, backend, kernel, source, flags, entry);
  const std::string cc = c_compiler();
  const std::string command = compiler_command(cc, flags);
  const std::string key_text = "backend=" + backend + "\ndriver=" + command + "\nentry=" + entry +
                               "\n" + cache::source_line(source);
  const std::string cache_path = cache::entry_path(backend, key_text).string();

  std::string why;
  if (std::optional<std::string> cached = cache::load(backend, key_text)) {
    SharedObject so = load_from_memory(*cached, entry, why);
    if (so.handle) {
      so.from_disk_cache = true;
      so.path = cache_path;
      return so;
    }
    // It passed the checksum, so it is what an earlier compile wrote, yet the loader refuses
    // it (a compiler command that means something else now): rebuild it.
    cache::remove(backend, key_text);
  }

  fs::path dir = cache_directory();
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (ec)
    throw Error("CPU backend: cannot create the kernel cache directory '" + dir.string() + "' (" +
                ec.message() + "); set RILL_CACHE_DIR to a writable directory");

  // Unique temporary names per process and thread.
  const std::string tag = ir::hex(ir::hash_bytes(key_text)) + ".rill.tmp." + temporary_tag();
  const fs::path src = dir / (tag + ".c"), tmp = dir / (tag + ".so");
  std::string binary;
  {
    const TemporaryFiles temporaries{{src, tmp}};
    write_text(src, source);
    compile_file(cc, flags, src, tmp, dir / (tag + ".log"), source, units, cold_units);
    binary = read_file(tmp);
  }
  cache::store(backend, key_text, binary);

  SharedObject so = load_from_memory(binary, entry, why);
  if (!so.handle) throw Error("CPU backend: cannot load compiled kernel: " + why);
  so.path = cache_path;
  return so;
}

}  // namespace rill::cpu
