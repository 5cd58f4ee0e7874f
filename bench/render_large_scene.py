#!/usr/bin/env python3
"""A large scene for render's start-up figures: a terrain grid of about 1 M faces and an 8192^2 JPEG atlas,
in the bundled sample's ENU frame (so the sample's plan looks at it), as scene.json + scene.glb.

  bench/render_large_scene.py SAMPLE_SCENE_JSON ATLAS_JPEG OUT_DIR [--faces N]

SAMPLE_SCENE_JSON gives the origin (the bundled scene's scene.json); ATLAS_JPEG is the texture's bytes
as they are (bench/render_startup.sh makes one with ffmpeg). The GLB stores plain accessors (no Draco).
Pure Python (struct, array): no numpy on the machine.
"""
import argparse
import array
import json
import math
import os
import struct


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("scene_json")
    parser.add_argument("atlas_jpeg")
    parser.add_argument("out_dir")
    parser.add_argument("--faces", type=int, default=1_000_000)
    parser.add_argument("--half-size-m", type=float, default=200.0)
    parser.add_argument("--ground-up-m", type=float, default=-38.0)
    args = parser.parse_args()

    n = int(math.sqrt(args.faces / 2)) + 1  # vertices per side
    half = args.half_size_m
    positions = array.array("f")
    texcoords = array.array("f")
    for j in range(n):
        north = -half + 2 * half * j / (n - 1)
        for i in range(n):
            east = -half + 2 * half * i / (n - 1)
            up = args.ground_up_m + 1.5 * math.sin(east / 17.0) * math.cos(north / 23.0)
            positions.extend((east, up, -north))  # glTF (e, u, -n)
            texcoords.extend((i / (n - 1), 1 - j / (n - 1)))
    indices = array.array("I")
    for j in range(n - 1):
        for i in range(n - 1):
            a = j * n + i
            indices.extend((a, a + 1, a + n, a + 1, a + n + 1, a + n))
    atlas = open(args.atlas_jpeg, "rb").read()

    blobs = [indices.tobytes(), positions.tobytes(), texcoords.tobytes(), atlas]
    views, offset, binary = [], 0, b""
    for blob in blobs:
        views.append({"buffer": 0, "byteOffset": offset, "byteLength": len(blob)})
        pad = (4 - len(blob) % 4) % 4
        binary += blob + b"\0" * pad
        offset += len(blob) + pad
    xs, ys, zs = positions[0::3], positions[1::3], positions[2::3]
    gltf = {
        "asset": {"version": "2.0", "generator": "cinepath bench/render_large_scene.py"},
        "scene": 0,
        "scenes": [{"nodes": [0]}],
        "nodes": [{"mesh": 0}],
        "meshes": [{"primitives": [{"attributes": {"POSITION": 1, "TEXCOORD_0": 2}, "indices": 0, "material": 0}]}],
        "materials": [{"pbrMetallicRoughness": {"baseColorTexture": {"index": 0}, "metallicFactor": 0.0}}],
        "textures": [{"source": 0}],
        "images": [{"bufferView": 3, "mimeType": "image/jpeg"}],
        "buffers": [{"byteLength": len(binary)}],
        "bufferViews": views,
        "accessors": [
            {"bufferView": 0, "componentType": 5125, "count": len(indices), "type": "SCALAR"},
            {"bufferView": 1, "componentType": 5126, "count": n * n, "type": "VEC3",
             "min": [min(xs), min(ys), min(zs)], "max": [max(xs), max(ys), max(zs)]},
            {"bufferView": 2, "componentType": 5126, "count": n * n, "type": "VEC2"},
        ],
    }
    text = json.dumps(gltf).encode()
    text += b" " * ((4 - len(text) % 4) % 4)
    os.makedirs(args.out_dir, exist_ok=True)
    with open(os.path.join(args.out_dir, "scene.glb"), "wb") as f:
        f.write(struct.pack("<III", 0x46546C67, 2, 12 + 8 + len(text) + 8 + len(binary)))
        f.write(struct.pack("<II", len(text), 0x4E4F534A) + text)
        f.write(struct.pack("<II", len(binary), 0x004E4942) + binary)
    sample = json.load(open(args.scene_json))
    scene = {"format": "cinepath.scene", "version": 1, "mesh": "scene.glb", "origin": sample["origin"]}
    with open(os.path.join(args.out_dir, "scene.json"), "w") as f:
        json.dump(scene, f, indent=2)
    print(f"{len(indices) // 3} faces, {n * n} vertices, atlas {len(atlas)} bytes")


if __name__ == "__main__":
    main()
