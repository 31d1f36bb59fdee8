#!/usr/bin/env python3
"""Renders a raylab reference scene with Mitsuba 3 (not run in CI).

    python3 -m venv /tmp/mitsuba-venv && /tmp/mitsuba-venv/bin/pip install mitsuba numpy
    apt-get install libllvm19   # the llvm variant's JIT
    DRJIT_LIBLLVM_PATH=/usr/lib/x86_64-linux-gnu/libLLVM.so.19.1 \
        /tmp/mitsuba-venv/bin/python scripts/mitsuba_reference.py assets/reference/rough.xml 4096

writes NAME.exr beside NAME.xml (linear RGB float32) and prints the render's
own noise: relMSE between two renders of half the samples, halved.

Translated: the camera (eye, toward, up, theta, width, height), spheres, boxes and
triangles; `<floor>` and `<plane>` as a square of side 2·10⁴ lying in the plane (raylab's is
infinite); point and directional lights (W/sr and W/m², as raylab's: Mitsuba's `point` and
`directional` emitters), `<sky color>` (a `constant` emitter) and `<sky map rotate>` (an `envmap`
emitter in the same latitude-longitude layout, turned alike; a grey `color` times `strength` is
its scale); matte, mirror and glass, and
named `<material>`s derived from them (a shape's own parameters over its material's), with
`roughness` (GGX α = roughness²: Mitsuba's roughconductor with material "none", i.e. Fresnel 1
times `color`, and roughdielectric); emission as an area light on the front side. Colours are
three linear floats or #rrggbb / #rgb (sRGB). An ambient light is left out: raylab's path tracer
has no ambient term either (it lights Whitted's images only). A `<mesh>` is placed by raylab
itself (`raylab export-meshes`: each instance's world-space triangles and shading normals as OBJ,
with the material raylab resolved for it), so Mitsuba sees raylab's very triangles.

Anything else is refused with an error naming the element, never dropped: a comparison with a
scene Mitsuba did not see would be meaningless. That includes textured `<mesh>`es, cylinders,
cones and tori, plastic, metal and marble, CSS
colour names, shapes without an explicit position (raylab stands them on the floor), and scenes with no
light, emitter or sky (raylab then adds a key light of its own). See assets/reference/README.md
for the conventions.
"""
import json
import os
import subprocess
import sys
import xml.etree.ElementTree as ET

import mitsuba as mi
import numpy as np

mi.set_variant("llvm_ad_rgb")
T = mi.ScalarTransform4f


class Untranslated(ValueError):
    """An element of a raylab scene this script cannot give Mitsuba exactly."""


def where(el, n):
    """How an error names element number n (1-based among <scene>'s children)."""
    attrs = " ".join(f'{k}="{v}"' for k, v in el.attrib.items())
    return f"element {n}, <{el.tag}{' ' + attrs if attrs else ''}>"


def floats(s, count=3):
    values = [float(x) for x in s.split()]
    if len(values) != count:
        raise ValueError(f"expected {count} numbers, got {s!r}")
    return values


def required(el, name):
    value = el.get(name)
    if value is None:
        raise Untranslated(
            f"<{el.tag}> without {name}: raylab fills it in itself (a default, or a place on the "
            f"floor); give it explicitly to compare with Mitsuba")
    return value


def srgb_to_linear(c):
    return c / 12.92 if c <= 0.04045 else ((c + 0.055) / 1.055) ** 2.4


def color(text):
    """Linear RGB of a raylab colour: three floats, or #rrggbb / #rgb in sRGB."""
    text = text.strip()
    if text.startswith("#"):
        digits = text[1:]
        if len(digits) == 3:
            digits = "".join(d * 2 for d in digits)
        if len(digits) != 6:
            raise ValueError(f"colour {text!r} is neither #rrggbb nor #rgb")
        return [srgb_to_linear(int(digits[i:i + 2], 16) / 255) for i in (0, 2, 4)]
    try:
        return floats(text)
    except ValueError:
        raise Untranslated(f"colour {text!r}: give three linear floats or #rrggbb") from None


# raylab's built-in colours (scene/src/materials.rs) of the materials translated here.
DEFAULT_COLOR = {"matte": "0.8 0.8 0.8", "mirror": "0.95 0.95 0.95", "glass": "1 1 1"}


def refuse_lobes(el, kind, allowed_reflectivity):
    """raylab adds a mirror lobe (`reflectivity`) or a highlight (`specular`) that Mitsuba's
    translation here does not have: refuse them."""
    reflectivity = float(el.get("reflectivity", str(allowed_reflectivity)))
    if reflectivity != allowed_reflectivity or float(el.get("specular", "0")) > 0:
        raise Untranslated(f"{kind} with reflectivity or specular set has no Mitsuba translation")


def bsdf(el):
    kind = el.get("material", "matte")
    rgb_value = color(el.get("color", DEFAULT_COLOR.get(kind, "0.8 0.8 0.8")))
    roughness = float(el.get("roughness", "0"))
    alpha = roughness * roughness
    rgb = {"type": "rgb", "value": rgb_value}
    if kind == "matte":
        refuse_lobes(el, kind, 0.0)
        return {"type": "twosided", "b": {"type": "diffuse", "reflectance": rgb}}
    if kind == "mirror":
        refuse_lobes(el, kind, 1.0)
        # Two-sided, as raylab turns the normal toward the ray for every material.
        if alpha > 0:
            return {"type": "twosided", "b": {
                "type": "roughconductor", "material": "none", "distribution": "ggx",
                "alpha": alpha, "specular_reflectance": rgb}}
        return {"type": "twosided", "b": {"type": "conductor", "material": "none",
                                          "specular_reflectance": rgb}}
    if kind == "glass":
        refuse_lobes(el, kind, 0.0)
        ior = float(el.get("ior", "1.5"))
        # raylab tints what the glass transmits by its colour.
        if alpha > 0:
            return {"type": "roughdielectric", "distribution": "ggx", "alpha": alpha,
                    "int_ior": ior, "ext_ior": 1.0, "specular_transmittance": rgb}
        return {"type": "dielectric", "int_ior": ior, "ext_ior": 1.0,
                "specular_transmittance": rgb}
    raise Untranslated(f"material {kind!r} has no Mitsuba translation here (matte, mirror, glass)")


def emitter(el):
    """The area light of an element whose emission is positive (raylab's rule), else None."""
    e = el.get("emission")
    radiance = color(e) if e is not None else [0.0]
    if max(radiance) <= 0:
        return None
    return {"type": "area", "radiance": {"type": "rgb", "value": radiance}}


def rotation_to(normal):
    """A rotation taking +z (a Mitsuba rectangle's normal) to the unit vector `normal`."""
    n = np.array(normal, dtype=float)
    n /= np.linalg.norm(n)
    axis = np.cross([0.0, 0.0, 1.0], n)
    if np.linalg.norm(axis) < 1e-9:
        return T() if n[2] > 0 else T().rotate([1, 0, 0], 180)
    angle = np.degrees(np.arccos(np.clip(n[2], -1.0, 1.0)))
    return T().rotate(list(axis / np.linalg.norm(axis)), float(angle))


# Half the side of the square that stands for an infinite plane.
PLANE_HALF_SIZE = 1.0e4


def shape_of(el):
    """The Mitsuba shape of one raylab object element other than a triangle (without its BSDF)."""
    if el.tag == "sphere":
        return {"type": "sphere", "center": floats(required(el, "center")),
                "radius": float(required(el, "radius"))}
    if el.tag == "box":
        c, size = floats(required(el, "center")), floats(required(el, "size"))
        rx, ry, rz = floats(el.get("rotate", "0 0 0"))
        to_world = (T().translate(c) @ T().rotate([0, 0, 1], rz) @ T().rotate([0, 1, 0], ry)
                    @ T().rotate([1, 0, 0], rx) @ T().scale([s / 2 for s in size]))
        return {"type": "cube", "to_world": to_world}
    if el.tag in ("floor", "plane"):
        if el.tag == "floor":
            point, normal = [0.0, float(el.get("y", "0")), 0.0], [0.0, 1.0, 0.0]
        else:
            point, normal = floats(required(el, "point")), floats(required(el, "normal"))
        to_world = T().translate(point) @ rotation_to(normal) @ T().scale(PLANE_HALF_SIZE)
        return {"type": "rectangle", "to_world": to_world}
    raise Untranslated(f"<{el.tag}> has no Mitsuba translation here")


def light_of(el):
    """The Mitsuba emitter of a raylab <light>, with raylab's defaults; None for ambient light."""
    kind = el.get("type", "point")
    rgb = color(el.get("color", "1 1 1"))
    if kind == "ambient":
        print(f"note: {el.get('name', 'an ambient light')} is left out: the path tracer has no "
              "ambient term", file=sys.stderr)
        return None
    if kind == "point":
        power = float(el.get("intensity", "60"))
        return {"type": "point", "position": floats(el.get("position", "-4 6 4")),
                "intensity": {"type": "rgb", "value": [power * c for c in rgb]}}
    if kind == "directional":
        power = float(el.get("intensity", "2"))
        return {"type": "directional", "direction": floats(el.get("direction", "-1 -2 -1")),
                "irradiance": {"type": "rgb", "value": [power * c for c in rgb]}}
    raise Untranslated(f"light type {kind!r}")


def sky_of(el, scene_dir):
    """The Mitsuba emitter of a raylab <sky>: `constant` for a colour; for a map, `envmap` (the
    same lat-long layout) turned by `rotate` as raylab turns it (x, then y, then z) and scaled by
    a grey `color` times `strength` (Mitsuba's envmap takes a scalar scale, not a tint)."""
    rgb = color(el.get("color", "1 1 1"))
    strength = float(el.get("strength", "1"))
    if el.get("map") is None:
        if el.get("rotate") is not None:
            raise Untranslated("rotate without a map")
        radiance = [strength * c for c in color(required(el, "color"))]
        return {"type": "constant", "radiance": {"type": "rgb", "value": radiance}}
    if max(rgb) != min(rgb):
        raise Untranslated("a tinted map: Mitsuba's envmap scales by a number, not a colour")
    rx, ry, rz = floats(el.get("rotate", "0 0 0"))
    to_world = T().rotate([0, 0, 1], rz) @ T().rotate([0, 1, 0], ry) @ T().rotate([1, 0, 0], rx)
    return {"type": "envmap", "filename": os.path.join(scene_dir, el.get("map")),
            "scale": rgb[0] * strength, "to_world": to_world}


# The material parameters a <material> or a shape may set.
MATERIAL_PARAMS = ("color", "roughness", "ior", "emission", "shininess", "specular", "reflectivity")
# raylab's built-in materials.
BUILT_IN = ("matte", "plastic", "mirror", "metal", "glass", "marble")


class Resolved:
    """An element's attributes with its named material folded in, as raylab resolves them: the
    material's base chain first, then the material's own parameters, then the element's."""

    def __init__(self, el, named):
        self.tag = el.tag
        self.attrib = dict(el.attrib)
        kind = el.get("material", "matte")
        chain = []
        while kind not in BUILT_IN:
            if kind not in named:
                raise Untranslated(f"material {kind!r} is neither built in nor defined")
            if named[kind] in chain:
                raise Untranslated(f"material {kind!r} derives from itself")
            chain.append(named[kind])
            kind = named[kind].get("base", "matte")
        params = {}
        for m in reversed(chain):
            params.update({k: v for k, v in m.attrib.items() if k in MATERIAL_PARAMS})
        params.update({k: v for k, v in el.attrib.items() if k in MATERIAL_PARAMS})
        params["material"] = kind
        self.attrib.update(params)

    def get(self, name, default=None):
        return self.attrib.get(name, default)


def export_meshes(path, workdir):
    """raylab's own placement of the scene's <mesh>es (`raylab export-meshes`: world-space OBJ
    files and each instance's resolved material), one entry per <mesh> in file order. The
    raylab binary is $RAYLAB, else this checkout's release build."""
    raylab = os.environ.get("RAYLAB") or os.path.join(
        os.path.dirname(os.path.abspath(__file__)), "..", "target", "release", "raylab")
    try:
        done = subprocess.run([raylab, "export-meshes", path, "--dir", workdir],
                              capture_output=True, text=True)
    except OSError as e:
        raise Untranslated(f"<mesh> needs raylab to place it ({raylab}: {e}); "
                           "build it with cargo build --release -p raylab or set RAYLAB") from None
    if done.returncode != 0:
        raise Untranslated(f"raylab export-meshes failed: {done.stderr.strip()}")
    with open(os.path.join(workdir, "meshes.json")) as f:
        return json.load(f)


def load(path, workdir):
    """The Mitsuba scene of the raylab scene file `path` (OBJ files go to `workdir`); raises
    Untranslated, naming the element, for anything it cannot translate exactly."""
    try:
        root = ET.parse(path).getroot()
    except ET.ParseError as e:
        raise Untranslated(f"{path}: {e} (raylab reads unclosed tags, as the lecture writes them; "
                           "this translation needs well-formed XML)") from None
    cam = root.find("camera")
    if cam is None:
        raise Untranslated("no <camera>: raylab frames the scene itself; give eye and toward")
    eye, toward = floats(required(cam, "eye")), floats(required(cam, "toward"))
    up = floats(cam.get("up", "0 1 0"))
    scene = {
        "type": "scene",
        "integrator": {"type": "path", "max_depth": 8},
        "sensor": {
            "type": "perspective", "fov": 2 * float(required(cam, "theta")), "fov_axis": "y",
            "to_world": T().look_at(origin=eye, target=[e + t for e, t in zip(eye, toward)], up=up),
            "film": {"type": "hdrfilm", "width": int(required(cam, "width")),
                     "height": int(required(cam, "height")), "rfilter": {"type": "box"},
                     "pixel_format": "rgb"},
            "sampler": {"type": "independent", "sample_count": 1},
        },
    }
    triangles = {}
    # raylab resolves material names once the whole file is read: a shape may name a later one.
    named = {el.get("name"): el for el in root if el.tag == "material" and el.get("name")}
    lit = False
    exported, meshes_seen = None, 0
    for n, raw in enumerate(root):
        el = raw
        try:
            if el.tag == "camera":
                continue
            if el.tag == "material":
                required(el, "name")
                base = el.get("base", "matte")
                if base not in BUILT_IN and base not in named:
                    raise Untranslated(f"base {base!r} is neither built in nor defined")
                continue
            if el.tag == "sky":
                scene["sky"] = sky_of(el, os.path.dirname(os.path.abspath(path)))
                lit = True
                continue
            if el.tag == "light":
                light = light_of(el)
                if light is not None:
                    scene[f"light{n}"] = light
                    lit = True
                continue
            if el.tag == "mesh":
                if exported is None:
                    exported = export_meshes(path, workdir)
                if len(exported) <= meshes_seen:
                    raise Untranslated("raylab exported fewer models than the file has <mesh>es")
                model = exported[meshes_seen]
                meshes_seen += 1
                for k, inst in enumerate(model["instances"]):
                    if inst["textured"]:
                        raise Untranslated("a textured glTF material has no Mitsuba translation "
                                           "here (the texture's colours and coordinates)")
                    # The material raylab resolved for the instance, as an element's attributes.
                    resolved = ET.Element("mesh", {k2: v for k2, v in inst["material"].items()})
                    shape = {"type": "obj", "filename": os.path.join(workdir, inst["obj"]),
                             "bsdf": bsdf(resolved)}
                    light = emitter(resolved)
                    if light:
                        shape["emitter"] = light
                        lit = True
                    scene[f"mesh{n}_{k}"] = shape
                continue
            el = Resolved(el, named)
            if el.tag == "triangle":
                key = tuple(el.get(k) for k in ("material", "color", "roughness", "ior", "emission"))
                corners = [floats(required(el, k)) for k in ("t0", "t1", "t2")]
                triangles.setdefault(key, (el, []))[1].append(corners)
                bsdf(el)  # refused now, with the element named, if it has no translation
                lit = lit or emitter(el) is not None
                continue
            shape = shape_of(el)
            shape["bsdf"] = bsdf(el)
            light = emitter(el)
            if light:
                shape["emitter"] = light
                lit = True
            scene[f"shape{n}"] = shape
        except (Untranslated, ValueError) as e:
            raise Untranslated(f"{path}: {where(raw, n + 1)}: {e}") from None
    if not lit:
        raise Untranslated(f"{path}: no light, emitter or sky: raylab adds a key light of its own")
    for k, (el, tris) in enumerate(triangles.values()):
        obj = os.path.join(workdir, f"triangles{k}.obj")
        with open(obj, "w") as f:
            for t in tris:
                for p in t:
                    f.write("v %r %r %r\n" % tuple(p))
            for i in range(len(tris)):
                f.write("f %d %d %d\n" % (3 * i + 1, 3 * i + 2, 3 * i + 3))
        shape = {"type": "obj", "filename": obj, "face_normals": True, "bsdf": bsdf(el)}
        light = emitter(el)
        if light:
            shape["emitter"] = light
        scene[f"triangles{k}"] = shape
    return mi.load_dict(scene)


def rel_mse(x, ref):
    return float(np.mean((x - ref) ** 2 / (ref ** 2 + 0.01)))


def main():
    path, spp = sys.argv[1], int(sys.argv[2])
    workdir = "/tmp/mitsuba-reference"
    os.makedirs(workdir, exist_ok=True)
    try:
        scene = load(path, workdir)
    except Untranslated as e:
        sys.exit(f"mitsuba_reference: {e}")
    halves = [np.array(mi.render(scene, spp=spp // 2, seed=seed))[:, :, :3] for seed in (1, 2)]
    image = 0.5 * (halves[0] + halves[1])
    out = os.path.splitext(path)[0] + ".exr"
    mi.Bitmap(image.astype(np.float32), pixel_format=mi.Bitmap.PixelFormat.RGB).write(out)
    # Each half's error is twice the mean's; their difference has twice a half's.
    print(f"wrote {out}: {spp} spp, own noise (relMSE) ~{rel_mse(halves[0], halves[1]) / 4:.1e}")


if __name__ == "__main__":
    main()
