#!/usr/bin/env python3
"""Writes the procedural environment map of assets/reference/sky.xml (not run in CI).

    /tmp/mitsuba-venv/bin/python scripts/make_sky_map.py assets/reference/sky_map.exr

A latitude-longitude map, 256 × 128, in Mitsuba 3's `envmap` layout (row 0 toward +y, column x
at azimuth φ = 2π (x + ½) / W measured from −z toward +x; a direction is
(sin θ sin φ, cos θ, −sin θ cos φ)): a blue sky brightening toward a warm horizon, a dim brown
ground below it, and a sun of radius 5° at 40° above the horizon, 20 to 60 times brighter than the
sky, with a soft edge. Linear RGB float32 (OpenEXR).
"""
import sys

import mitsuba as mi
import numpy as np

mi.set_variant("scalar_rgb")

W, H = 256, 128


def sky_map():
    x = (np.arange(W) + 0.5) / W * 2 * np.pi
    theta = np.arange(H) / (H - 1) * np.pi
    phi, theta = np.meshgrid(x, theta)
    d = np.stack([np.sin(theta) * np.sin(phi), np.cos(theta), -np.sin(theta) * np.cos(phi)], -1)
    up = d[..., 1]
    zenith, horizon, ground = np.array([0.25, 0.45, 1.1]), np.array([1.1, 0.95, 0.8]), np.array([0.3, 0.22, 0.15])
    t = np.clip(up, 0, 1)[..., None] ** 0.5
    image = np.where(up[..., None] >= 0, horizon * (1 - t) + zenith * t, ground * (0.6 + 0.4 * np.exp(8 * up[..., None])))
    sun_dir = np.array([np.cos(np.radians(40)) * np.sin(np.radians(60)), np.sin(np.radians(40)),
                        -np.cos(np.radians(40)) * np.cos(np.radians(60))])
    angle = np.degrees(np.arccos(np.clip(d @ sun_dir, -1, 1)))
    sun = np.clip((6.0 - angle) / 2.0, 0, 1)[..., None] * np.array([40.0, 36.0, 30.0])
    return (image + sun).astype(np.float32)


if __name__ == "__main__":
    out = sys.argv[1]
    mi.Bitmap(sky_map(), pixel_format=mi.Bitmap.PixelFormat.RGB).write(out)
    print(f"wrote {out}")
