#!/usr/bin/env python3
"""Renders the model `biscara mjcf` writes at one moment of its companion trajectory, to a PNG.

Usage: MUJOCO_GL=egl render.py MODEL.xml TRAJ.traj.csv T_SECONDS OUT.png

The joints (and the elbows, from our FK) are set from the row nearest T_SECONDS; the camera looks
at the workspace from the front right. Needs an OpenGL context (EGL or OSMesa). Not a test: this
made docs/viewer-mujoco.png.
"""

import struct
import sys
import zlib

import mujoco
import numpy as np

from common import load, set_joints


def write_png(pixels, path):
    height, width, _ = pixels.shape
    raw = b"".join(b"\x00" + pixels[y].tobytes() for y in range(height))

    def chunk(kind, data):
        body = kind + data
        return struct.pack(">I", len(data)) + body + struct.pack(">I", zlib.crc32(body))

    header = struct.pack(">IIBBBBB", width, height, 8, 2, 0, 0, 0)
    with open(path, "wb") as f:
        f.write(b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", header))
        f.write(chunk(b"IDAT", zlib.compress(raw, 9)) + chunk(b"IEND", b""))


def main(argv):
    if len(argv) != 4:
        print(__doc__, file=sys.stderr)
        return 2
    model, rows = load(argv[0], argv[1])
    data = mujoco.MjData(model)
    set_joints(model, data, rows[int(np.argmin(np.abs(rows[:, 0] - float(argv[2]))))])
    mujoco.mj_forward(model, data)
    renderer = mujoco.Renderer(model, 600, 900)
    camera = mujoco.MjvCamera()
    camera.lookat[:] = [0.0, 0.2, 0.15]
    camera.distance, camera.azimuth, camera.elevation = 1.0, -125.0, -25.0
    renderer.update_scene(data, camera)
    write_png(renderer.render(), argv[3])
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
