# Sourced by the build scripts (tools/test.sh, quickstart.sh, sanitize.sh, fuzz.sh,
# check_avx512_emulated.sh): when ccache is installed (the full set of
# tools/install_dependencies.sh), compile through it, so that a rebuild of unchanged
# sources (CI's builds of the same commit, a fresh clone) is a cache hit. Without ccache
# it adds nothing and the build is the same plain one.
# Sets compiler_cache=(cmake arguments); needs $root, the repository's top folder.
compiler_cache=()
if command -v ccache >/dev/null; then
  compiler_cache=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache)
  # Paths below the checkout are hashed relative to it, so two clones share hits.
  export CCACHE_BASEDIR="${CCACHE_BASEDIR:-$root}"
fi
