#include "SharedObjectCache.h"

#include <dlfcn.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <thread>

#include <fcntl.h>

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
  std::ifstream in(p);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

// Runs argv, with stdout and stderr going to `log`; returns the exit status (-1: not run).
int run(const std::vector<std::string>& argv, const fs::path& log) {
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
  if (rc != 0) return -1;
  int status = 0;
  while (waitpid(pid, &status, 0) < 0) {
    if (errno != EINTR) return -1;
  }
  if (WIFEXITED(status)) return WEXITSTATUS(status) == 127 ? -1 : WEXITSTATUS(status);
  return 128;
}

}  // namespace

std::string cache_directory() {
  std::string dir = env("RILL_CACHE_DIR");
  if (dir.empty()) {
    std::string xdg = env("XDG_CACHE_HOME");
    std::string home = env("HOME");
    if (!xdg.empty())
      dir = xdg + "/rill";
    else if (!home.empty())
      dir = home + "/.cache/rill";
    else
      dir = (fs::temp_directory_path() / "rill-cache").string();
  }
  return dir;
}

std::string c_compiler() {
  std::string cc = env("RILL_CC");
  if (!cc.empty()) return cc;
#ifdef RILL_DEFAULT_CC
  if (fs::exists(RILL_DEFAULT_CC)) return RILL_DEFAULT_CC;
#endif
  return "cc";
}

SharedObject compile_shared_object(const std::string& source, const std::vector<std::string>& flags,
                                   const std::string& entry) {
  const std::string cc = c_compiler();
  std::string command = cc;
  for (const auto& f : flags) command += " " + f;
  const std::string key = ir::hex(ir::hash_bytes(source, ir::hash_bytes(command)));

  fs::path dir = cache_directory();
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (ec)
    throw Error("CPU backend: cannot create the kernel cache directory '" + dir.string() + "' (" +
                ec.message() + "); set RILL_CACHE_DIR to a writable directory");

  SharedObject so;
  fs::path lib = dir / (key + ".so");
  so.path = lib.string();
  so.from_disk_cache = fs::exists(lib);
  if (!so.from_disk_cache) {
    // Unique temporary names per process and thread, then an atomic rename.
    std::ostringstream tag;
    tag << key << "." << getpid() << "."
        << std::hash<std::thread::id>{}(std::this_thread::get_id());
    fs::path src = dir / (tag.str() + ".c");
    fs::path tmp = dir / (tag.str() + ".so.tmp");
    fs::path log = dir / (tag.str() + ".log");
    {
      std::ofstream out(src);
      out << source;
      if (!out) throw Error("CPU backend: cannot write '" + src.string() + "'");
    }
    std::vector<std::string> argv{cc};
    argv.insert(argv.end(), flags.begin(), flags.end());
    argv.insert(argv.end(), {"-o", tmp.string(), src.string(), "-lm"});
    int rc = run(argv, log);
    std::string messages = read_file(log);
    fs::remove(log, ec);
    if (rc != 0) {
      fs::remove(src, ec);
      fs::remove(tmp, ec);
      if (rc < 0)
        throw Error("CPU backend: the C compiler '" + cc +
                    "' could not be run; install one (apt-get install gcc) or set RILL_CC");
      throw Error("CPU backend: the C compiler rejected the generated kernel (exit " +
                  std::to_string(rc) + "):\n" + messages + "\ngenerated source:\n" +
                  codegen::numbered(source));
    }
    fs::remove(src, ec);
    fs::rename(tmp, lib, ec);
    if (ec)
      throw Error("CPU backend: cannot move the compiled kernel into the cache: " + ec.message());
  }

  so.handle = dlopen(lib.c_str(), RTLD_NOW | RTLD_LOCAL);
  if (!so.handle && so.from_disk_cache) {
    // A damaged cache file (a disk that filled up, a copy cut short): compile it afresh.
    fs::remove(lib, ec);
    return compile_shared_object(source, flags, entry);
  }
  if (!so.handle)
    throw Error(std::string("CPU backend: cannot load compiled kernel: ") + dlerror());
  so.symbol = dlsym(so.handle, entry.c_str());
  if (!so.symbol) {
    dlclose(so.handle);
    throw Error("CPU backend: compiled kernel has no '" + entry + "' (stale cache file " +
                lib.string() + "?)");
  }
  return so;
}

}  // namespace rill::cpu
