# Sourced by the build scripts: sets compiler_cache to the CMake arguments that put ccache in front
# of the compilers when it is installed (empty otherwise). Objects are keyed by their preprocessed
# source and flags, so a fresh clone at the same path reuses them; ccache hashes the working
# folder out of debug paths (base_dir), so clones elsewhere hit too.
compiler_cache=()
if command -v ccache >/dev/null 2>&1; then
  export CCACHE_BASEDIR="${CCACHE_BASEDIR:-$PWD}"
  export CCACHE_MAXSIZE="${CCACHE_MAXSIZE:-5G}"
  compiler_cache=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache -DCMAKE_C_COMPILER_LAUNCHER=ccache)
fi
