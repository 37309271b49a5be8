#!/usr/bin/env python3
"""Hostile inputs for tessera, made deterministically into a folder (issue 35).

    make_cases.py OUT_DIR      writes the case files and OUT_DIR/cases.json

Every file is small or sparse; FIFOs are made here too, so the whole set lives
in the build folder. Each case in cases.json is {name, args, expect, files},
where args is the tessera command line (paths relative to OUT_DIR/<name>/),
expect the text the one error line must hold, and status the exit status
wanted ("nonzero" by default). run_cases.py runs them under prlimit caps.
"""
import base64
import json
import os
import struct
import sys
import zlib

out = sys.argv[1]
cases = []

CAMERA = "[camera]\nposition = [0, 0, 5]\ntarget = [0, 0, 0]\n"
TINY = "[output]\nwidth = 32\nheight = 24\n" + CAMERA + \
    "[[lights]]\ntype = \"point\"\nposition = [0, 0, 4]\ncolor = [10, 10, 10]\n" + \
    "[[objects]]\nmesh = \"sphere\"\n"


def case(name, args, expect, status="nonzero", files=None, fifos=(), sparse=None, links=None, **extra):
    """files: {relative path: bytes or str}; sparse: {path: size}; links: {path: target}."""
    folder = os.path.join(out, name)
    os.makedirs(folder, exist_ok=True)
    for path, data in (files or {}).items():
        full = os.path.join(folder, path)
        os.makedirs(os.path.dirname(full), exist_ok=True)
        with open(full, "wb") as f:
            f.write(data.encode() if isinstance(data, str) else data)
    for path in fifos:
        full = os.path.join(folder, path)
        os.makedirs(os.path.dirname(full), exist_ok=True)
        if not os.path.exists(full):
            os.mkfifo(full)
    for path, size in (sparse or {}).items():
        with open(os.path.join(folder, path), "wb") as f:
            f.write(b"glTF\x02\x00\x00\x00" if path.endswith(".glb") else b"#")
            f.truncate(size)
    for path, target in (links or {}).items():
        full = os.path.join(folder, path)
        os.makedirs(os.path.dirname(full), exist_ok=True)
        if not os.path.lexists(full):
            os.symlink(target, full)
    cases.append(dict(name=name, args=args, expect=expect, status=status, **extra))


# ---- Encoded images, by hand (no imaging library needed) ---------------------------------------

def png(width, height, raw_rows=None, color_type=6):
    """A PNG; raw_rows None gives a few bytes of IDAT whatever the header claims."""
    def chunk(kind, data):
        return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data) & 0xFFFFFFFF)
    ihdr = struct.pack(">IIBBBBB", width, height, 8, color_type, 0, 0, 0)
    data = zlib.compress(raw_rows if raw_rows is not None else b"\x00" * 16, 9)
    return b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", ihdr) + chunk(b"IDAT", data) + chunk(b"IEND", b"")


def flat_png(width, height):
    row = b"\x00" + b"\x80\x80\x80\xff" * width
    return png(width, height, row * height)


def jpeg(width, height):
    """A baseline greyscale JPEG whose every 8x8 block is flat grey: one-bit Huffman
    codes for DC category 0 and the end of block, so a block costs two bits. With a
    header claiming a large size the scan holds only a byte: the data is missing."""
    def segment(marker, data):
        return b"\xff" + bytes([marker]) + struct.pack(">H", len(data) + 2) + data
    dqt = segment(0xDB, b"\x00" + b"\x01" * 64)
    sof = segment(0xC0, b"\x08" + struct.pack(">HH", height, width) + b"\x01" + b"\x01\x11\x00")
    # A Huffman table with one code of length 1 for symbol 0 (DC: category 0; AC: end of block).
    one_code = b"\x01" + b"\x00" * 15 + b"\x00"
    dht = segment(0xC4, b"\x00" + one_code + b"\x10" + one_code)
    sos = segment(0xDA, b"\x01\x01\x00\x00\x3f\x00")
    blocks = ((width + 7) // 8) * ((height + 7) // 8)
    bits = min(blocks, 64) * 2  # a true file for small sizes; a byte or so of the rest
    scan = bytes([0x00] * (bits // 8)) + (bytes([(0xFF >> (bits % 8))]) if bits % 8 else b"")
    return b"\xff\xd8" + dqt + sof + dht + sos + scan + b"\xff\xd9"


# ---- glTF -------------------------------------------------------------------------------------------

TRIANGLE = struct.pack("<9f", 0, 0, 0, 1, 0, 0, 0, 1, 0)


def gltf(buffers=None, images=None, accessors=None, views=None, meshes=None, nodes=None, scenes=True, extra=None,
         materials=None, textures=None):
    doc = {"asset": {"version": "2.0"}}
    doc["buffers"] = buffers if buffers is not None else [
        {"byteLength": 36, "uri": "data:application/octet-stream;base64," + base64.b64encode(TRIANGLE).decode()}]
    doc["bufferViews"] = views if views is not None else [{"buffer": 0, "byteLength": 36}]
    doc["accessors"] = accessors if accessors is not None else [
        {"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3", "min": [0, 0, 0], "max": [1, 1, 0]}]
    doc["meshes"] = meshes if meshes is not None else [{"primitives": [{"attributes": {"POSITION": 0}}]}]
    doc["nodes"] = nodes if nodes is not None else [{"mesh": 0}]
    if scenes:
        doc["scenes"] = [{"nodes": [0]}]
    for key, value in (("images", images), ("materials", materials), ("textures", textures)):
        if value is not None:
            doc[key] = value
    doc.update(extra or {})
    return json.dumps(doc)


def glb(json_text, version=2, bin_chunk=b""):
    body = json_text.encode()
    body += b" " * (-len(body) % 4)
    chunks = struct.pack("<I", len(body)) + b"JSON" + body
    if bin_chunk:
        bin_chunk += b"\x00" * (-len(bin_chunk) % 4)
        chunks += struct.pack("<I", len(bin_chunk)) + b"BIN\x00" + bin_chunk
    return b"glTF" + struct.pack("<II", version, 12 + len(chunks)) + chunks


def render(scene, *more):
    return ["render", scene, "-o", "out.png", *more]


def nested(depth):
    return "[" * depth + "]" * depth


# ---- TOML scenes -------------------------------------------------------------------------------

case("toml_deep_dotted_key", render("s.toml"), "s.toml:4: nested deeper than 64 levels",
     files={"s.toml": CAMERA + "a." * 100000 + "a = 1\n"})
case("toml_deep_table_header", render("s.toml"), "nested deeper than 64 levels",
     files={"s.toml": "[" + "a." * 100000 + "a]\n"})
case("toml_deep_arrays", render("s.toml"), "nested deeper than 64 levels",
     files={"s.toml": "x = " + nested(100000) + "\n"})
case("toml_deep_inline_tables", render("s.toml"), "nested deeper than 64 levels",
     files={"s.toml": "x = " + "{a = " * 50000 + "1" + "}" * 50000 + "\n"})
case("scene_fifo", render("s.toml"), "s.toml: cannot read scene file: it is a named pipe (FIFO)", fifos=["s.toml"])
# A device by its own name has no scene extension (refused as a usage error); behind a .toml name
# it must still be refused before a byte is read.
case("scene_dev_zero", render("/dev/zero"), "/dev/zero: not a scene file (expected .toml, .gltf or .glb)", status=2)
case("scene_dev_zero_named_toml", render("zero.toml"), "zero.toml: cannot read scene file: it is a character device",
     links={"zero.toml": "/dev/zero"})
case("scene_dev_urandom_named_glb", render("random.glb"), "it is a character device",
     links={"random.glb": "/dev/urandom"})
case("scene_folder", render("d"), "d: cannot read scene file: it is a folder", files={"d/x": ""})
case("scene_sparse_8g", render("s.toml"), "scene file of 8.0 GB is larger than", sparse={"s.toml": 8 << 30})
case("log_fifo", render("s.toml", "--log", "log.fifo"), "log.fifo: cannot write the log: it is a named pipe",
     files={"s.toml": TINY}, fifos=["log.fifo"])
case("frames_empty", render("s.toml", "--frames", ""), "--frames: expected a range", files={"s.toml": TINY})
case("outputs_collide", ["render", "s.toml", "--frames", "1-11", "-o", "x{frame}.png", "-o", "x1{frame}.png"],
     "both write 'x11.png'", files={"s.toml": TINY + "[animation]\nframes = 12\n"})
case("texture_fifo", render("s.toml"), "texture 't.png': cannot read texture: it is a named pipe",
     files={"s.toml": TINY.replace('mesh = "sphere"', 'mesh = "sphere"\nmaterial = "m"') +
            '[materials.m]\nalbedo_map = "t.png"\n'}, fifos=["t.png"])
case("texture_dev_zero", render("s.toml"), "texture '/dev/zero': cannot read texture: it is a character device",
     files={"s.toml": TINY.replace('mesh = "sphere"', 'mesh = "sphere"\nmaterial = "m"') +
            '[materials.m]\nalbedo_map = "/dev/zero"\n'})
TEXTURED = TINY.replace('mesh = "sphere"', 'mesh = "sphere"\nmaterial = "m"') + '[materials.m]\nalbedo_map = "t.{}"\n'
case("jpeg_claims_16384", render("s.toml"), "the header claims 16384x16384",
     files={"s.toml": TEXTURED.format("jpg"), "t.jpg": jpeg(16384, 16384)})
case("png_claims_16384", render("s.toml"), "the header claims 16384x16384",
     files={"s.toml": TEXTURED.format("png"), "t.png": png(16384, 16384)})
case("jpeg_true_8x8_renders", render("s.toml"), "", status=0,
     files={"s.toml": TEXTURED.format("jpg"), "t.jpg": jpeg(8, 8)}, output="out.png")
# Six 2048² textures of 22 MB each with their mips, under a 64 MB budget: the third is refused.
six = TINY.replace('[[objects]]\nmesh = "sphere"\n', "")
for i in range(6):
    six += f'[materials.m{i}]\nalbedo_map = "t{i}.png"\n[[objects]]\nmesh = "sphere"\nmaterial = "m{i}"\n'
case("six_textures_over_budget", render("s.toml", "--max-memory", "64M"), "more than the memory budget of 64.0 MB",
     files=dict({"s.toml": six}, **{f"t{i}.png": flat_png(2048, 2048) for i in range(6)}))

# ---- glTF / GLB ----------------------------------------------------------------------------------

deep_extras = gltf(extra={"extras": json.loads("[" * 1 + "]")})
deep_extras = deep_extras[:-1] + ', "extras": ' + nested(20000) + "}"
case("gltf_deep_extras", render("m.gltf"), "JSON nested deeper than 256 levels", files={"m.gltf": deep_extras})
case("glb_deep_extras", render("m.glb"), "the JSON chunk's line 1: JSON nested deeper than 256",
     files={"m.glb": glb(deep_extras)})
case("glb_version_1", render("m.glb"), "version 1, expected 2", files={"m.glb": glb(gltf(), version=1)})
case("glb_sparse_5g", render("m.glb"), "glTF file of 5.0 GB is larger than", sparse={"m.glb": 5 << 30})
case("glb_fifo", render("m.glb"), "m.glb: cannot read glTF file: it is a named pipe", fifos=["m.glb"])
external = lambda uri: gltf(buffers=[{"byteLength": 36, "uri": uri}])
case("uri_absolute", render("model/m.gltf"), "is an absolute path",
     files={"model/m.gltf": external(os.path.abspath(os.path.join(out, "uri_absolute", "secret.bin"))),
            "secret.bin": TRIANGLE})
case("uri_dotdot", render("model/m.gltf"), "leaves the model's folder",
     files={"model/m.gltf": external("../secret.bin"), "secret.bin": TRIANGLE})
case("uri_dotdot_percent", render("model/m.gltf"), "leaves the model's folder",
     files={"model/m.gltf": external("%2e%2e/secret.bin"), "secret.bin": TRIANGLE})
case("uri_file_scheme", render("model/m.gltf"), "has a scheme (file:)",
     files={"model/m.gltf": external("file:///etc/hostname")})
case("uri_symlink_out", render("model/m.gltf"), "resolves (through a symbolic link) outside",
     files={"model/m.gltf": external("link.bin"), "secret.bin": TRIANGLE}, links={"model/link.bin": "../secret.bin"})
case("uri_allowed_by_flag", render("model/m.gltf", "--allow-external-uris", "--width", "16", "--height", "16"), "",
     status=0, files={"model/m.gltf": external("../secret.bin"), "secret.bin": TRIANGLE}, output="out.png")
case("uri_allowed_by_scene_key", render("s.toml"), "", status=0, output="out.png",
     files={"s.toml": TINY + '[[models]]\nfile = "model/m.gltf"\nallow_external_uris = true\n',
            "model/m.gltf": external("../secret.bin"), "secret.bin": TRIANGLE})
case("uri_refused_in_scene", render("s.toml"), "leaves the model's folder",
     files={"s.toml": TINY + '[[models]]\nfile = "model/m.gltf"\n',
            "model/m.gltf": external("../secret.bin"), "secret.bin": TRIANGLE})
case("image_uri_dotdot", render("model/m.gltf"), "leaves the model's folder",
     files={"model/m.gltf": gltf(images=[{"uri": "../t.png"}], textures=[{"source": 0}],
                                 materials=[{"pbrMetallicRoughness": {"baseColorTexture": {"index": 0}}}],
                                 meshes=[{"primitives": [{"attributes": {"POSITION": 0}, "material": 0}]}]),
            "t.png": flat_png(4, 4)})
case("buffer_fifo", render("model/m.gltf"), "named pipe",
     files={"model/m.gltf": external("b.bin")}, fifos=["model/b.bin"])
case("nodes_cycle_no_roots", render("m.gltf"), "is its own ancestor",
     files={"m.gltf": gltf(nodes=[{"children": [1], "mesh": 0}, {"children": [0]}], scenes=False)})
case("accessor_negative_offset", render("m.gltf"), "\"byteOffset\" is negative",
     files={"m.gltf": gltf(accessors=[{"bufferView": 0, "byteOffset": -4, "componentType": 5126, "count": 3,
                                       "type": "VEC3", "min": [0, 0, 0], "max": [1, 1, 0]}])})
many = [{"attributes": {"POSITION": 1}}] * 100000
case("primitives_amplify", render("m.gltf", "--max-memory", "256M"), "more than the memory budget",
     files={"m.gltf": gltf(
         buffers=[{"byteLength": 120000, "uri": "b.bin"}],
         views=[{"buffer": 0, "byteLength": 36}, {"buffer": 0, "byteLength": 120000}],
         accessors=[{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3", "min": [0, 0, 0],
                     "max": [1, 1, 0]},
                    {"bufferView": 1, "componentType": 5126, "count": 9999, "type": "VEC3", "min": [0, 0, 0],
                     "max": [0, 0, 0]}],
         meshes=[{"primitives": many}]), "b.bin": b"\x00" * 120000})
case("morph_targets_amplify", render("m.gltf", "--max-memory", "256M"), "more than the memory budget",
     files={"m.gltf": gltf(
         buffers=[{"byteLength": 1200000, "uri": "b.bin"}],
         views=[{"buffer": 0, "byteLength": 1200000}],
         accessors=[{"bufferView": 0, "componentType": 5126, "count": 100000, "type": "VEC3", "min": [0, 0, 0],
                     "max": [0, 0, 0]}],
         meshes=[{"primitives": [{"attributes": {"POSITION": 0}, "targets": [{"POSITION": 0}] * 10000}]}]),
         "b.bin": b"\x00" * 1200000})
case("morph_weights_nan_strings", render("m.gltf"), "\"weights\" holds something other than numbers",
     files={"m.gltf": gltf(meshes=[{"weights": ["NaN"], "primitives": [
         {"attributes": {"POSITION": 0}, "targets": [{"POSITION": 0}]}]}])})

# ---- tessera check -------------------------------------------------------------------------------

case("manifest_deep_dotted_key", ["check", "check.toml"], "check.toml:1: nested deeper than 64 levels",
     files={"check.toml": "a." * 100000 + "a = 1\n"}, status=2)
case("manifest_fifo", ["check", "check.toml"], "check.toml: cannot read check manifest: it is a named pipe",
     fifos=["check.toml"], status=2)
case("golden_fifo", ["check", "check.toml", "-r", "report"], "s.png: cannot read golden image: it is a named pipe",
     files={"check.toml": 'scenes = ["scenes/*.toml"]\ngolden = "golden"\n', "scenes/s.toml": TINY},
     fifos=["golden/s.png"], status=1, in_report=True)
case("golden_16384_not_read", ["check", "check.toml", "-r", "report"], "size differs: golden 16384x16384",
     files={"check.toml": 'scenes = ["scenes/*.toml"]\ngolden = "golden"\n', "scenes/s.toml": TINY,
            "golden/s.png": png(16384, 16384)}, status=1, in_report=True)
# --merge: shard folders are made at run time from a real one-scene run (run_cases.py "setup": "shard").
case("merge_deep_summary", ["check", "--merge", "shard", "-r", "merged"], "nested deeper than 16 levels",
     setup="shard", summary=lambda s: s[:-2] + ', "x": ' + nested(100000) + "}\n", status=2)
case("merge_image_escapes", ["check", "--merge", "shard", "-r", "merged"], "",
     setup="shard", summary="escape", status="any", untouched=["victim.png"], files={"victim.png": "keep me"})
case("merge_symlink_out", ["check", "--merge", "shard", "-r", "merged"], "leading out of the shard's folder",
     setup="shard", summary="symlink", status=2, files={"outside.png": "secret"})
case("merge_billion_scenes", ["check", "--merge", "shard", "-r", "merged"], "too few for a suite of 1000000000",
     setup="shard", summary="billion", status=2)

# ---- contact-sheet -------------------------------------------------------------------------------

case("contact_sheet_fifo", ["contact-sheet", "f.png", "-o", "sheet.png"], "f.png: cannot read the frame: it is a named pipe", fifos=["f.png"])
case("contact_sheet_dev_zero", ["contact-sheet", "/dev/zero", "-o", "sheet.png"], "it is a character device")
case("contact_sheet_not_an_image", ["contact-sheet", "f.png", "-o", "sheet.png"], "f.png: cannot read the frame",
     files={"f.png": "this is not a PNG\n"})
case("contact_sheet_png_claims_16384", ["contact-sheet", "f.png", "-o", "sheet.png"], "f.png",
     files={"f.png": png(16384, 16384)})
case("texture_tiff_garbage", render("s.toml"), "t.tif", files={"s.toml": TEXTURED.format("tif"),
                                                           "t.tif": b"II*\x00" + b"\xff" * 64})
case("contact_sheet_tall_overflow", ["contact-sheet", "f.png", "-o", "sheet.png", "--tile-width", "4096"],
     "pixels is too large", files={"f.png": flat_png(1, 60000)})

# Lambdas cannot go to JSON: summary edits are named in run_cases.py.
for c in cases:
    if callable(c.get("summary")):
        c["summary"] = "deep"
with open(os.path.join(out, "cases.json"), "w") as f:
    json.dump(cases, f, indent=1)
print(f"{len(cases)} cases in {out}")
