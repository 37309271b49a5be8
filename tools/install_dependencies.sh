#!/usr/bin/env bash
# Installs, from Debian 12's packages, whatever Tessera needs that is missing.
# Run as root (or with sudo available). Installs nothing when all is present.
#   tools/install_dependencies.sh          everything: build, tests, tools, fuzzing
#   tools/install_dependencies.sh render   only what building the tessera command needs
set -euo pipefail
packages=(
  g++ make cmake pkg-config
  libglm-dev libtbb-dev libopenimageio-dev libxsimd-dev libtomlplusplus-dev libcli11-dev
  libtinygltf-dev nlohmann-json3-dev
  # Image I/O of tessera render without OpenImageIO: PNG, JPEG textures; PNG, EXR outputs.
  libpng-dev libjpeg62-turbo-dev libopenexr-dev
  # glTF textures in WebP and AVIF (EXT_texture_webp, EXT_texture_avif).
  libwebp-dev libavif-dev
  # Compressed glTF geometry: KHR_draco_mesh_compression and EXT_meshopt_compression.
  libdraco-dev libmeshoptimizer-dev
  # Every build script compiles through ccache when it is there (tools/compiler_cache.sh), so
  # a rebuild or a fresh clone of the same sources is mostly cache hits.
  ccache
)
if [ "${1:-all}" != render ]; then
  packages+=(
    doctest-dev openimageio-tools libbenchmark-dev
    # The OpenGL peer renderer (tools/gl_reference): glvnd's GL/EGL, Mesa's llvmpipe.
    libegl-dev libgl-dev libopengl-dev libegl-mesa0 libgl1-mesa-dri
    # The libFuzzer targets (tools/ci/fuzz.sh): clang and its runtime (-fsanitize=fuzzer).
    clang libclang-rt-14-dev
    # The fresh-machine check (tools/ci/fresh_machine_check.sh): minimal Debian 12 roots.
    mmdebstrap
    # The one-node Slurm cluster of tools/slurm/check_cluster.sh (python3 picks free ports, procps' pgrep
    # finds what the daemons started).
    slurmctld slurmd slurm-client munge python3 procps
    # tessera check's report tested in a real browser (tests/check/report_browser_test.py).
    chromium python3
    # The AVX-512 kernels run emulated on CPUs without AVX-512 (tools/ci/check_avx512_emulated.sh).
    libsimde-dev
    # The Python module (src/python, TESSERA_BUILD_PYTHON) and its pytest suite (tests/python);
    # pip, setuptools, wheel and venv for `pip install --no-build-isolation ./python`.
    pybind11-dev python3-dev python3-numpy python3-pytest python3-pip python3-setuptools python3-wheel python3-venv
  )
fi
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -eq 0 ]; then
  exit 0
fi
echo "Installing: ${missing[*]}"
sudo_cmd=()
[ "$(id -u)" -eq 0 ] || sudo_cmd=(sudo)
export DEBIAN_FRONTEND=noninteractive
"${sudo_cmd[@]}" apt-get update -qq
# --no-install-recommends: with recommends OpenImageIO pulls in PostgreSQL, GTK and Qt.
"${sudo_cmd[@]}" apt-get install -y -qq --no-install-recommends "${missing[@]}"
