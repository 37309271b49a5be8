#!/usr/bin/env bash
# tessera render does not load OpenImageIO (docs/cli.md, "Image files"): its ELF
# DT_NEEDED entries and ldd's full closure name no libOpenImageIO, while
# tessera-tools and the module beside it do; the tool sub-commands still run
# as `tessera SUBCOMMAND`; a texture format that needs the module says so,
# naming the file and the module, when the module is missing.
#   render_binary_test.sh BUILD/tessera OUTPUT_DIR
set -euo pipefail
tessera="$1"
out="$2"
dir="$(dirname "$tessera")"
mkdir -p "$out"
fail() { echo "FAIL: $*" >&2; exit 1; }

needed="$(readelf -d "$tessera" | sed -n 's/.*(NEEDED).*\[\(.*\)\]/\1/p')"
[ -n "$needed" ] || fail "readelf found no DT_NEEDED entries in $tessera"
grep -q "^libpng" <<<"$needed" || fail "tessera does not link libpng: $needed"
if grep -qi openimageio <<<"$needed"; then fail "tessera links OpenImageIO directly: $needed"; fi
closure="$(ldd "$tessera")"
if grep -qi openimageio <<<"$closure"; then fail "tessera loads OpenImageIO at start (ldd): $closure"; fi
count="$(echo "$closure" | wc -l)"
[ "$count" -lt 40 ] || fail "tessera loads $count libraries at start (ldd), expected a few dozen at most"

for beside in tessera-tools tessera-oiio-module.so; do
  [ -f "$dir/$beside" ] || fail "$beside is not beside tessera in $dir"
  grep -qi openimageio <<<"$(ldd "$dir/$beside")" || fail "$beside does not link OpenImageIO"
done

# The tool sub-commands run through tessera, with tessera's name in their usage.
"$tessera" --help >"$out/help.txt"
for sub in check contact-sheet bench; do
  grep -q "$sub" "$out/help.txt" || fail "tessera --help does not list $sub"
  "$tessera" "$sub" --help >"$out/$sub.txt" || fail "tessera $sub --help failed"
  grep -q "tessera $sub" "$out/$sub.txt" || fail "tessera $sub --help is not tessera's usage: $(head -3 "$out/$sub.txt")"
done
set +e
"$tessera" check >/dev/null 2>"$out/check_usage.txt"
status=$?
set -e
[ "$status" -eq 2 ] || fail "tessera check without a manifest exits $status, not 2 (usage)"

# A TGA texture without the module: a clear error naming the texture and the module.
python3 - "$out/tiny.tga" <<'PY'
import struct, sys
# 2x2 uncompressed 24-bit TGA, bottom-up.
header = struct.pack("<BBBHHBHHHHBB", 0, 0, 2, 0, 0, 0, 0, 0, 2, 2, 24, 0)
open(sys.argv[1], "wb").write(header + bytes([0, 0, 255] * 4))
PY
cat >"$out/tga.toml" <<'TOML'
[output]
width = 64
height = 64
[camera]
position = [0.0, 0.0, 3.0]
target = [0.0, 0.0, 0.0]
[[lights]]
type = "point"
position = [0.0, 0.0, 5.0]
color = [10.0, 10.0, 10.0]
[materials.tga]
albedo_map = "tiny.tga"
[[objects]]
mesh = "sphere"
material = "tga"
TOML
"$tessera" render "$out/tga.toml" -o "$out/tga.png" || fail "a TGA texture does not render with the module beside tessera"
set +e
TESSERA_OIIO_MODULE="$out/no-such-module.so" "$tessera" render "$out/tga.toml" -o "$out/tga_missing.png" 2>"$out/missing.txt"
status=$?
set -e
[ "$status" -ne 0 ] || fail "rendering a TGA texture without the module succeeded"
grep -q "tiny.tga" "$out/missing.txt" || fail "the error does not name the texture: $(cat "$out/missing.txt")"
grep -q "no-such-module.so" "$out/missing.txt" || fail "the error does not name the module: $(cat "$out/missing.txt")"
echo "ok: tessera needs $(echo "$needed" | wc -l) libraries directly, $count in all; none is OpenImageIO"
