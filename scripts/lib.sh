# shellcheck shell=bash
# Shared by scripts/demo, scripts/test and .ci/run. Source it; do not run it.
#
# Environment knobs:
#   RILL_BUILD_DIR     build directory (default: build/ in the repository)
#   RILL_BUILD_TYPE    CMake build type (default: RelWithDebInfo)
#   RILL_SKIP_DEPS=1   do not check or install Debian packages
#   RILL_JOBS          parallel jobs (default: nproc)
#   RILL_DEBUG_INFO    lines (default): RelWithDebInfo with line tables only (-g1), enough for
#                      backtraces and sanitizer reports and a sixth quicker to compile; full:
#                      CMake's -g, for a debugger that shows variables

RILL_ROOT=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
RILL_BUILD_DIR=${RILL_BUILD_DIR:-$RILL_ROOT/build}
RILL_BUILD_TYPE=${RILL_BUILD_TYPE:-RelWithDebInfo}
RILL_JOBS=${RILL_JOBS:-$(nproc 2>/dev/null || echo 2)}
RILL_CMAKE_MIN=3.25

rill_say() { printf '\033[1m==> %s\033[0m\n' "$*" >&2; }
rill_die() {
  printf 'error: %s\n' "$*" >&2
  exit 1
}

# The packages listed in scripts/packages.txt.
rill_packages() {
  sed -e 's/#.*//' -e 's/[[:space:]]//g' "$RILL_ROOT/scripts/packages.txt" | grep -v '^$'
}

rill_package_installed() {
  dpkg-query -W -f='${Status}' "$1" 2>/dev/null | grep -q 'ok installed'
}

# Installs whichever packages of scripts/packages.txt are missing (apt-get update first
# only when something is missing). Does nothing when all are there.
rill_install_packages() {
  if [[ ${RILL_SKIP_DEPS:-0} == 1 ]]; then
    rill_say "RILL_SKIP_DEPS=1: not checking packages"
    return 0
  fi
  if ! command -v dpkg-query >/dev/null 2>&1; then
    rill_say "not a Debian/Ubuntu system: install the equivalents of scripts/packages.txt yourself"
    return 0
  fi
  local missing=() p
  while read -r p; do
    rill_package_installed "$p" || missing+=("$p")
  done < <(rill_packages)
  if ((${#missing[@]} == 0)); then
    rill_say "all required packages are installed"
    return 0
  fi
  rill_say "installing missing packages: ${missing[*]}"
  local sudo=()
  if ((EUID != 0)); then
    command -v sudo >/dev/null 2>&1 ||
      rill_die "not root and no sudo; install these packages first: ${missing[*]}"
    sudo=(sudo)
  fi
  "${sudo[@]}" env DEBIAN_FRONTEND=noninteractive apt-get update -q ||
    rill_die "apt-get update failed"
  "${sudo[@]}" env DEBIAN_FRONTEND=noninteractive apt-get install -y -q --no-install-recommends \
    "${missing[@]}" || rill_die "apt-get install failed for: ${missing[*]}"
}

rill_check_cmake() {
  command -v cmake >/dev/null 2>&1 || rill_die "cmake not found"
  local have
  have=$(cmake --version | sed -n 's/^cmake version \([0-9][0-9.]*\).*/\1/p')
  if [[ $(printf '%s\n%s\n' "$RILL_CMAKE_MIN" "$have" | sort -V | head -n1) != "$RILL_CMAKE_MIN" ]]; then
    rill_die "CMake $have is too old; Rill needs $RILL_CMAKE_MIN or newer (Debian 12 and Ubuntu 24.04 have it; elsewhere try 'pip install cmake')"
  fi
}

# The environment the tests run in (scripts/test, .ci/run), where a user's setting does not
# already say otherwise:
# - RILL_OPENCL_WARM_UP=small: compile()'s warm-up on PoCL builds the work-group function for
#   the small grid class only (up to 65535 work-items), the one nearly all the tests' launches
#   use; a larger launch builds its own at its first enqueue. Users' default warms both, so
#   that a first large launch costs what later ones do: a cost in latency, not in results, and
#   a quarter of a cold OpenCL compile (docs/testing.md, "Measured, 2026-12-06").
#   example.mandelbrot.opencl.strict keeps the default.
rill_test_environment() {
  export RILL_OPENCL_WARM_UP=${RILL_OPENCL_WARM_UP:-small}
}

# Configures (first time, or when options change) and builds into $RILL_BUILD_DIR.
# Extra arguments are passed to cmake's configure step (e.g. -DRILL_SANITIZE=ON).
# RILL_BUILD_TARGETS (space-separated) limits the build to those targets; default: all.
rill_build() {
  rill_check_cmake
  # Ninja when it is there (scripts/packages.txt installs it): it keeps both cores busy across
  # targets, and its .ninja_log times every step for scripts/test-times. A build directory
  # configured earlier keeps its generator (CMake refuses to change it).
  local generator=()
  if [[ ! -f $RILL_BUILD_DIR/CMakeCache.txt ]] && command -v ninja >/dev/null 2>&1; then
    generator=(-G Ninja)
  fi
  local g
  case ${RILL_DEBUG_INFO:-lines} in
    lines) g=-g1 ;;
    full) g=-g ;;  # CMake's own RelWithDebInfo flags
    *) rill_die "RILL_DEBUG_INFO='${RILL_DEBUG_INFO}' is not one of lines, full" ;;
  esac
  local debug_info=(-DCMAKE_C_FLAGS_RELWITHDEBINFO="-O2 $g -DNDEBUG"
    -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O2 $g -DNDEBUG")
  rill_say "configuring $RILL_BUILD_DIR ($RILL_BUILD_TYPE)"
  cmake -S "$RILL_ROOT" -B "$RILL_BUILD_DIR" "${generator[@]}" -DCMAKE_BUILD_TYPE="$RILL_BUILD_TYPE" \
    "${debug_info[@]}" "$@" ||
    rill_die "CMake configure failed"
  local targets=()
  if [[ -n ${RILL_BUILD_TARGETS:-} ]]; then
    read -r -a targets <<<"$RILL_BUILD_TARGETS"
    targets=(--target "${targets[@]}")
  fi
  rill_say "building ${RILL_BUILD_TARGETS:-everything} with $RILL_JOBS jobs"
  local began=$SECONDS
  cmake --build "$RILL_BUILD_DIR" --parallel "$RILL_JOBS" "${targets[@]}" || rill_die "build failed"
  rill_say "built in $((SECONDS - began)) s (per target: scripts/test-times --build $RILL_BUILD_DIR)"
}
