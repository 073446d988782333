# Sourced by scripts/build.sh and scripts/sanitize.sh: rrf_generator_args <build dir> prints the
# CMake generator arguments for that build directory. Ninja (install-deps installs it) schedules
# objects of a target before the targets it depends on have linked, which Make does not, so a
# build from scratch keeps both cores busy to the end; a directory already configured with another
# generator keeps it (CMake refuses to switch generators in place).
rrf_generator_args() {
  local cache=$1/CMakeCache.txt
  if [[ -f $cache ]]; then
    grep -q '^CMAKE_GENERATOR:INTERNAL=Ninja$' "$cache" && echo "-G Ninja"
    return 0
  fi
  command -v ninja >/dev/null && echo "-G Ninja"
  return 0
}
