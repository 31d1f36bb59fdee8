#!/usr/bin/env python3
"""Renders a raylab reference scene with Mitsuba 3 (not run in CI).

    python3 -m venv /tmp/mitsuba-venv && /tmp/mitsuba-venv/bin/pip install mitsuba numpy
    apt-get install libllvm19   # the llvm variant's JIT
    DRJIT_LIBLLVM_PATH=/usr/lib/x86_64-linux-gnu/libLLVM.so.19.1 \
        /tmp/mitsuba-venv/bin/python scripts/mitsuba_reference.py assets/reference/rough.xml 4096

writes NAME.exr beside NAME.xml (linear RGB float32) and prints the render's
own noise: relMSE between two renders of half the samples, halved.

Only what the reference scenes use is translated: the camera, spheres, boxes
and triangles; matte, mirror and glass, with `roughness` (GGX α =
roughness²: Mitsuba's roughconductor with material "none", i.e. Fresnel 1
times `color`, and roughdielectric); emission as an area light on the front
side. See assets/reference/README.md for the conventions.
"""
import os
import sys
import xml.etree.ElementTree as ET

import mitsuba as mi
import numpy as np

mi.set_variant("llvm_ad_rgb")
T = mi.ScalarTransform4f


def floats(s):
    return [float(x) for x in s.split()]


def bsdf(el):
    kind = el.get("material", "matte")
    color = floats(el.get("color", "0.8 0.8 0.8"))
    roughness = float(el.get("roughness", "0"))
    alpha = roughness * roughness
    rgb = {"type": "rgb", "value": color}
    if kind == "matte":
        return {"type": "twosided", "b": {"type": "diffuse", "reflectance": rgb}}
    if kind == "mirror":
        if alpha > 0:
            return {"type": "roughconductor", "material": "none", "distribution": "ggx",
                    "alpha": alpha, "specular_reflectance": rgb}
        return {"type": "conductor", "material": "none", "specular_reflectance": rgb}
    if kind == "glass":
        ior = float(el.get("ior", "1.5"))
        if alpha > 0:
            return {"type": "roughdielectric", "distribution": "ggx", "alpha": alpha,
                    "int_ior": ior, "ext_ior": 1.0}
        return {"type": "dielectric", "int_ior": ior, "ext_ior": 1.0}
    raise ValueError(f"material {kind} has no Mitsuba translation here")


def emitter(el):
    e = el.get("emission")
    return {"type": "area", "radiance": {"type": "rgb", "value": floats(e)}} if e else None


def load(path, workdir):
    root = ET.parse(path).getroot()
    cam = root.find("camera")
    eye, toward = floats(cam.get("eye")), floats(cam.get("toward"))
    up = floats(cam.get("up", "0 1 0"))
    scene = {
        "type": "scene",
        "integrator": {"type": "path", "max_depth": 8},
        "sensor": {
            "type": "perspective", "fov": 2 * float(cam.get("theta")), "fov_axis": "y",
            "to_world": T().look_at(origin=eye, target=[e + t for e, t in zip(eye, toward)], up=up),
            "film": {"type": "hdrfilm", "width": int(cam.get("width")),
                     "height": int(cam.get("height")), "rfilter": {"type": "box"},
                     "pixel_format": "rgb"},
            "sampler": {"type": "independent", "sample_count": 1},
        },
    }
    triangles = {}
    for n, el in enumerate(root):
        shape = None
        if el.tag == "triangle":
            key = tuple(el.get(k) for k in ("material", "color", "roughness", "ior", "emission"))
            triangles.setdefault(key, (el, []))[1].append([floats(el.get(k)) for k in ("t0", "t1", "t2")])
        elif el.tag == "sphere":
            shape = {"type": "sphere", "center": floats(el.get("center")),
                     "radius": float(el.get("radius"))}
        elif el.tag == "box":
            c, size = floats(el.get("center")), floats(el.get("size"))
            rx, ry, rz = floats(el.get("rotate", "0 0 0"))
            to_world = (T().translate(c) @ T().rotate([0, 0, 1], rz) @ T().rotate([0, 1, 0], ry)
                        @ T().rotate([1, 0, 0], rx) @ T().scale([s / 2 for s in size]))
            shape = {"type": "cube", "to_world": to_world}
        if shape is not None:
            shape["bsdf"] = bsdf(el)
            if emitter(el):
                shape["emitter"] = emitter(el)
            scene[f"shape{n}"] = shape
    for k, (el, tris) in enumerate(triangles.values()):
        obj = os.path.join(workdir, f"triangles{k}.obj")
        with open(obj, "w") as f:
            for t in tris:
                for p in t:
                    f.write("v %r %r %r\n" % tuple(p))
            for i in range(len(tris)):
                f.write("f %d %d %d\n" % (3 * i + 1, 3 * i + 2, 3 * i + 3))
        shape = {"type": "obj", "filename": obj, "face_normals": True, "bsdf": bsdf(el)}
        if emitter(el):
            shape["emitter"] = emitter(el)
        scene[f"triangles{k}"] = shape
    return mi.load_dict(scene)


def rel_mse(x, ref):
    return float(np.mean((x - ref) ** 2 / (ref ** 2 + 0.01)))


def main():
    path, spp = sys.argv[1], int(sys.argv[2])
    workdir = "/tmp/mitsuba-reference"
    os.makedirs(workdir, exist_ok=True)
    scene = load(path, workdir)
    halves = [np.array(mi.render(scene, spp=spp // 2, seed=seed))[:, :, :3] for seed in (1, 2)]
    image = 0.5 * (halves[0] + halves[1])
    out = os.path.splitext(path)[0] + ".exr"
    mi.Bitmap(image.astype(np.float32), pixel_format=mi.Bitmap.PixelFormat.RGB).write(out)
    # Each half's error is twice the mean's; their difference has twice a half's.
    print(f"wrote {out}: {spp} spp, own noise (relMSE) ~{rel_mse(halves[0], halves[1]) / 4:.1e}")


if __name__ == "__main__":
    main()
