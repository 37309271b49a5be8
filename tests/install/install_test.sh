#!/usr/bin/env bash
# The installed tree (cmake/Install.cmake), after it has been moved:
#   install_test.sh install  WORK CMAKE BUILD            cmake --install BUILD into WORK/prefix, move it to WORK/moved
#   install_test.sh render   WORK SOURCE BUILD/tessera   the moved bin/tessera renders a Draco glTF and a TGA
#                                                        texture (through the OpenImageIO module), runs a tool
#                                                        sub-command, and loads nothing from the build tree
#   install_test.sh embed    WORK SOURCE BUILD/tessera CMAKE [CMAKE ARGS...]
#                                                        examples/embed builds with find_package(Tessera) from the
#                                                        moved tree and renders what build/tessera renders
#   install_test.sh subproject WORK SOURCE CMAKE         add_subdirectory(tessera): tests and tools off, src/ private
set -euo pipefail
mode="$1" work="$2"
moved="$work/moved"
fail() { echo "FAIL: $*" >&2; exit 1; }

case "$mode" in
install)
  cmake="$3" build="$4"
  rm -rf "$work" && mkdir -p "$work"
  "$cmake" --install "$build" --prefix "$work/prefix" >"$work/install.log" || { cat "$work/install.log"; fail "cmake --install failed"; }
  mv "$work/prefix" "$moved"
  for f in bin/tessera lib/tessera/tessera-tools lib/tessera/tessera-oiio-module.so lib/tessera/libtessera_draco.so \
           include/tessera/renderer.hpp lib/cmake/Tessera/TesseraConfig.cmake lib/cmake/Tessera/TesseraConfigVersion.cmake; do
    [ -e "$moved/$f" ] || fail "the installed tree has no $f: $(cd "$moved" && find . -type f | sort | head -40)"
  done
  # Only include/tessera/: no header of src/ is installed.
  [ -z "$(find "$moved/include" -type f ! -path "$moved/include/tessera/*")" ] || fail "headers outside include/tessera/ were installed"
  # Relative run paths only ($ORIGIN), none naming the build tree.
  for f in bin/tessera lib/tessera/tessera-tools; do
    runpath="$(readelf -d "$moved/$f" | sed -n 's/.*(R\(UN\)\{0,1\}PATH).*\[\(.*\)\]/\2/p')"
    case "$runpath" in '$ORIGIN'*) ;; *) fail "$f has run path '$runpath', expected one relative to \$ORIGIN" ;; esac
    case "$runpath" in *"$build"*) fail "$f's run path names the build tree: $runpath" ;; esac
  done
  echo "ok: installed and moved to $moved"
  ;;
render)
  source="$3" built="$4"
  [ -x "$moved/bin/tessera" ] || fail "no installed tree at $moved (the install test runs first)"
  out="$work/render" && rm -rf "$out" && mkdir -p "$out"
  build="$(cd "$(dirname "$built")" && pwd)"
  # What the dynamic linker loads (LD_DEBUG=files: "calling init: PATH" for each library and module).
  loaded() { grep -o 'calling init: .*' "$1" | sed 's/calling init: //' | while read -r path; do realpath -m "$path"; done; }
  # The paths of the build tree outside the moved tree (which the tests keep inside the build tree).
  from_build() { grep "^$build/" | grep -v "^$moved/"; }
  check_loads() {  # LOG LIBRARY...: each LIBRARY is loaded from the moved tree, nothing from the build tree
    local log="$1" files; shift
    files="$(loaded "$log")"
    for lib in "$@"; do
      grep -qx "$moved/lib/tessera/$lib" <<<"$files" || fail "$lib was not loaded from $moved/lib/tessera: $(grep tessera <<<"$files" || true)"
    done
    if from_build <<<"$files"; then fail "loaded from the build tree: $(from_build <<<"$files")"; fi
  }
  # A Draco-compressed glTF: the Draco library beside the helpers.
  draco="$source/tests/scene/models/BoomBox_geometry_draco.glb"
  LD_DEBUG=files "$moved/bin/tessera" render "$draco" --width 160 --height 120 -o "$out/draco.png" 2>"$out/draco.log" ||
    { grep -v '^ *[0-9]*:' "$out/draco.log" >&2; fail "the moved tessera does not render $draco"; }
  check_loads "$out/draco.log" libtessera_draco.so
  "$built" render "$draco" --width 160 --height 120 -o "$out/draco_build.png"
  cmp -s "$out/draco.png" "$out/draco_build.png" || fail "the moved tessera renders $draco differently from $built"
  # A TGA texture: read through the OpenImageIO module (PNG and JPEG are read without it).
  python3 - "$out/tiny.tga" <<'PY'
import struct, sys
# 2x2 uncompressed 24-bit TGA: blue, green, red, white (BGR order).
header = struct.pack("<BBBHHBHHHHBB", 0, 0, 2, 0, 0, 0, 0, 0, 2, 2, 24, 0)
open(sys.argv[1], "wb").write(header + bytes([255, 0, 0, 0, 255, 0, 0, 0, 255, 255, 255, 255]))
PY
  cat >"$out/tga.toml" <<'TOML'
[output]
width = 64
height = 64
[camera]
position = [0.0, 0.0, 3.0]
target = [0.0, 0.0, 0.0]
[[lights]]
position = [0.0, 0.0, 5.0]
color = [10.0, 10.0, 10.0]
[materials.tga]
albedo_map = "tiny.tga"
[[objects]]
mesh = "sphere"
material = "tga"
TOML
  LD_DEBUG=files "$moved/bin/tessera" render "$out/tga.toml" -o "$out/tga.png" 2>"$out/tga.log" ||
    { grep -v '^ *[0-9]*:' "$out/tga.log" >&2; fail "the moved tessera does not render a TGA texture"; }
  check_loads "$out/tga.log" tessera-oiio-module.so
  "$built" render "$out/tga.toml" -o "$out/tga_build.png"
  cmp -s "$out/tga.png" "$out/tga_build.png" || fail "the moved tessera renders the TGA scene differently from $built"
  # A tool sub-command: bin/tessera execs lib/tessera/tessera-tools.
  LD_DEBUG=files,libs "$moved/bin/tessera" contact-sheet "$out/draco.png" "$out/tga.png" -o "$out/sheet.png" >"$out/sheet.txt" 2>"$out/sheet.log" ||
    { grep -v '^ *[0-9]*:' "$out/sheet.log" >&2; fail "the moved tessera cannot run tessera-tools"; }
  [ -s "$out/sheet.png" ] || fail "tessera contact-sheet wrote no sheet.png"
  # The exec'd program keeps tessera's argv[0]; its run path's $ORIGIN shows where it is.
  grep -q "search path=$moved/lib/tessera[[:space:]]*(RUNPATH" "$out/sheet.log" || fail "tessera-tools did not run from $moved/lib/tessera"
  if from_build <<<"$(loaded "$out/sheet.log")"; then fail "tessera-tools loaded from the build tree"; fi
  echo "ok: the moved tessera renders Draco and TGA input and runs tessera-tools, loading only from $moved"
  ;;
embed)
  source="$3" built="$4" cmake="$5"; shift 5
  [ -d "$moved/lib/cmake/Tessera" ] || fail "no installed tree at $moved (the install test runs first)"
  out="$work/embed" && rm -rf "$out" && mkdir -p "$out"
  "$cmake" -S "$source/examples/embed" -B "$out/build" -DCMAKE_PREFIX_PATH="$moved" "$@" >"$out/configure.log" 2>&1 ||
    { cat "$out/configure.log"; fail "examples/embed does not configure against $moved"; }
  grep -q "Tessera_DIR:PATH=$moved/lib/cmake/Tessera" "$out/build/CMakeCache.txt" || fail "find_package(Tessera) did not find $moved"
  "$cmake" --build "$out/build" >"$out/build.log" 2>&1 || { cat "$out/build.log"; fail "examples/embed does not build"; }
  # Its compile lines name the installed headers, never the source tree's src/ or include/.
  if grep -rq -- "$source/src\|$source/include" "$out/build/CMakeFiles/embed.dir/flags.make"; then
    fail "examples/embed compiles with the source tree's headers: $(cat "$out/build/CMakeFiles/embed.dir/flags.make")"
  fi
  scene="$source/tests/check/scenes/ball.toml"
  "$out/build/embed" "$scene" "$out/ball.png" || fail "embed did not render $scene"
  "$built" render "$scene" -o "$out/ball_build.png"
  cmp -s "$out/ball.png" "$out/ball_build.png" || fail "embed renders $scene differently from $built"
  echo "ok: examples/embed built against $moved renders $scene as tessera does"
  ;;
subproject)
  # add_subdirectory(tessera) in another project: tests and tools default off, tessera::tessera
  # gives include/ and not src/ (configured only: building would compile everything again).
  source="$3" cmake="$4"
  out="$work" && rm -rf "$out" && mkdir -p "$out/project"
  cat >"$out/project/CMakeLists.txt" <<CMAKE
cmake_minimum_required(VERSION 3.25)
project(outer LANGUAGES CXX)
add_subdirectory("$source" tessera)
add_executable(outer_embed "$source/examples/embed/main.cpp")
target_link_libraries(outer_embed PRIVATE tessera::tessera)
CMAKE
  "$cmake" -S "$out/project" -B "$out/build" >"$out/configure.log" 2>&1 || { cat "$out/configure.log"; fail "a project including tessera does not configure"; }
  for option in TESSERA_BUILD_TESTS TESSERA_BUILD_GL_REFERENCE TESSERA_BUILD_MICROBENCH; do
    grep -qx "$option:BOOL=OFF" "$out/build/CMakeCache.txt" || fail "$option is not OFF by default in a subproject: $(grep "^$option" "$out/build/CMakeCache.txt")"
  done
  flags="$out/build/CMakeFiles/outer_embed.dir/flags.make"
  grep -q -- "$source/include" "$flags" || fail "tessera::tessera does not give include/: $(grep INCLUDES "$flags")"
  if grep -q -- "$source/src" "$flags"; then fail "tessera::tessera gives src/ to the program that links it: $(grep INCLUDES "$flags")"; fi
  echo "ok: as a subproject, tests and tools are off and tessera::tessera gives include/ only"
  ;;
*) fail "unknown mode $mode" ;;
esac
