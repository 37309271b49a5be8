"""Tessera from Python: render TOML scenes, glTF files and scenes built from
NumPy arrays on the CPU, and get RGB, depth, normals and per-object masks back
as NumPy arrays. No display or GL context; renders run with the GIL released.

    scene = tessera.load("model.glb")
    frame = tessera.Renderer(640, 480, aovs=("depth", "object_id")).render(scene)
    frame.color, frame.depth, frame.object_id   # (H, W, 3) uint8, (H, W) float32, (H, W) uint32

The API is documented in docs/python.md.
"""
from ._tessera import (Camera, Frame, ImageError, Renderer, Scene, SceneError, load, read_image)

__all__ = ["Camera", "Frame", "ImageError", "Renderer", "Scene", "SceneError", "load", "read_image"]
