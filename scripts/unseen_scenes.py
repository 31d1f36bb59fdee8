#!/usr/bin/env python3
"""Writes scenes unlike the three in assets/reference, for measuring raylab against Mitsuba on scenes it
was not tuned on (issue 26: "it will be checked on scenes that are not in the repository"):

  grid900.xml       a 30 × 30 grid of spheres (matte, mirror, glass) on a floor, lit by an area light;
  scatter3000.xml   3,000 spheres of random sizes scattered over the floor and in the air;
  tessellated.xml   a UV sphere of 3,480 lone triangles beside five spheres;
  meshsphere.xml    the same sphere as a glTF mesh (meshsphere.gltf: shared vertices, smooth vertex
                    normals) placed by `<mesh>`, beside the five spheres;
  lamps.xml         64 spheres and boxes on an infinite floor before a tilted wall, under a sky, lit by
                    three point lights and the sun (a directional light), with named materials (rough
                    mirrors, rough glass): no area light at all.

Each is in the subset of raylab's format that scripts/mitsuba_reference.py translates, 512×384 (the
mesh through `raylab export-meshes`, so that Mitsuba sees raylab's placed triangles). The scenes are
the same on every run (fixed seeds).

    python3 scripts/unseen_scenes.py DIR

scripts/bench-vs-mitsuba.sh --dir DIR --references SPP renders their references with Mitsuba and compares.
"""
import base64
import json
import math
import os
import random
import struct
import sys

HEAD = """<scene>
  <camera eye="0 9 16" toward="0 -9 -16" up="0 1 0" theta="22" width="512" height="384"/>
  <triangle t0="-40 0 40" t1="40 0 40" t2="40 0 -40" material="matte" color="0.5 0.5 0.5"/>
  <triangle t0="-40 0 40" t1="40 0 -40" t2="-40 0 -40" material="matte" color="0.5 0.5 0.5"/>
  <triangle t0="-2 8 -2" t1="2 8 -2" t2="2 8 2" material="matte" color="0 0 0" emission="20 20 20"/>
  <triangle t0="-2 8 -2" t1="2 8 2" t2="-2 8 2" material="matte" color="0 0 0" emission="20 20 20"/>
"""


def material(rng):
    """A random material: matte twice as often as mirror or glass."""
    kind = rng.choice(["matte", "matte", "mirror", "glass"])
    if kind == "glass":
        return 'material="glass" ior="1.5"'
    color = " ".join("%.3f" % rng.random() for _ in range(3))
    return f'material="{kind}" color="{color}"'


def sphere(x, y, z, r, rng):
    return f'  <sphere center="{x:.4f} {y:.4f} {z:.4f}" radius="{r:.4f}" {material(rng)}/>\n'


def grid(n):
    rng = random.Random(7)
    side = int(math.isqrt(n))
    step = 16.0 / side
    body = ""
    for i in range(side):
        for j in range(side):
            r = 0.35 * step
            body += sphere((i - side / 2) * step, r, (j - side / 2) * step, r, rng)
    return HEAD + body + "</scene>\n"


def scatter(n):
    rng = random.Random(3)
    body = ""
    for _ in range(n):
        r = rng.uniform(0.05, 0.5)
        x, z = rng.uniform(-8, 8), rng.uniform(-8, 4)
        y = r + rng.choice([0, 0, rng.uniform(0, 3)])
        body += sphere(x, y, z, r, rng)
    return HEAD + body + "</scene>\n"


def tessellated(nu=60, nv=30, radius=2.5):
    rng = random.Random(11)

    def point(u, v):
        theta, phi = 2 * math.pi * u / nu, math.pi * v / nv
        return (radius * math.sin(phi) * math.cos(theta), radius + 0.1 + radius * math.cos(phi),
                radius * math.sin(phi) * math.sin(theta))

    body = ""
    for u in range(nu):
        for v in range(nv):
            a, b, c, d = point(u, v), point(u + 1, v), point(u + 1, v + 1), point(u, v + 1)
            quads = ([(a, b, c)] if v > 0 else []) + ([(a, c, d)] if v < nv - 1 else [])
            for t in quads:
                t0, t1, t2 = ("%.5f %.5f %.5f" % p for p in t)
                body += (f'  <triangle t0="{t0}" t1="{t1}" t2="{t2}" material="matte" '
                         'color="0.7 0.5 0.3"/>\n')
    for k in range(5):
        body += sphere(-5 + 2.5 * k, 0.6, 4, 0.6, rng)
    return HEAD + body + "</scene>\n"


def sphere_gltf(nu=60, nv=30, radius=2.5):
    """The tessellated sphere as a glTF 2.0 mesh: shared vertices on the (nu + 1) × (nv + 1) grid,
    each with its unit normal, and the same 3,480 triangles."""
    positions, normals = [], []
    for u in range(nu + 1):
        for v in range(nv + 1):
            theta, phi = 2 * math.pi * u / nu, math.pi * v / nv
            n = (math.sin(phi) * math.cos(theta), math.cos(phi), math.sin(phi) * math.sin(theta))
            normals.append(n)
            positions.append((radius * n[0], radius + 0.1 + radius * n[1], radius * n[2]))
    index = lambda u, v: u * (nv + 1) + v
    triangles = []
    for u in range(nu):
        for v in range(nv):
            a, b, c, d = index(u, v), index(u + 1, v), index(u + 1, v + 1), index(u, v + 1)
            triangles += ([(a, b, c)] if v > 0 else []) + ([(a, c, d)] if v < nv - 1 else [])
    pos = b"".join(struct.pack("<3f", *p) for p in positions)
    nor = b"".join(struct.pack("<3f", *n) for n in normals)
    idx = b"".join(struct.pack("<3I", *t) for t in triangles)
    data = pos + nor + idx
    lo = [min(p[k] for p in positions) for k in range(3)]
    hi = [max(p[k] for p in positions) for k in range(3)]
    gltf = {
        "asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0]}], "nodes": [{"mesh": 0}],
        "meshes": [{"primitives": [{"attributes": {"POSITION": 0, "NORMAL": 1}, "indices": 2}]}],
        "buffers": [{"byteLength": len(data),
                     "uri": "data:application/octet-stream;base64," + base64.b64encode(data).decode()}],
        "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": len(pos)},
                        {"buffer": 0, "byteOffset": len(pos), "byteLength": len(nor)},
                        {"buffer": 0, "byteOffset": len(pos) + len(nor), "byteLength": len(idx)}],
        "accessors": [
            {"bufferView": 0, "componentType": 5126, "count": len(positions), "type": "VEC3",
             "min": lo, "max": hi},
            {"bufferView": 1, "componentType": 5126, "count": len(normals), "type": "VEC3"},
            {"bufferView": 2, "componentType": 5125, "count": 3 * len(triangles), "type": "SCALAR"},
        ],
    }
    return json.dumps(gltf)


def meshsphere():
    rng = random.Random(11)
    body = ('  <mesh src="meshsphere.gltf" translate="0 0 0" material="matte" '
            'color="0.7 0.5 0.3"/>\n')
    for k in range(5):
        body += sphere(-5 + 2.5 * k, 0.6, 4, 0.6, rng)
    return HEAD + body + "</scene>\n"


def lamps(n=64):
    rng = random.Random(5)
    body = """<scene>
  <camera eye="0 5 14" toward="0 -4 -14" up="0 1 0" theta="24" width="512" height="384"/>
  <sky color="0.15 0.2 0.3"/>
  <light type="point" position="-5 6 3" color="1 0.85 0.7" intensity="80"/>
  <light type="point" position="4 3 5" color="0.6 0.7 1" intensity="30"/>
  <light type="point" position="0 8 -4" intensity="50"/>
  <light type="directional" direction="0.4 -1 -0.6" color="1 0.95 0.9" intensity="1.2"/>
  <material name="brushed" base="mirror" color="0.9 0.8 0.6" roughness="0.4"/>
  <material name="frosted" base="glass" roughness="0.3"/>
  <floor y="0" color="0.55 0.55 0.5"/>
  <plane point="0 0 -8" normal="0 0.2 1" color="0.4 0.45 0.5"/>
"""
    for k in range(n):
        x, z = rng.uniform(-7, 7), rng.uniform(-6, 5)
        kind = rng.choice(["matte", "matte", "brushed", "frosted", "mirror"])
        color = " ".join("%.3f" % rng.uniform(0.2, 0.9) for _ in range(3))
        paint = f'material="{kind}"' + (f' color="{color}"' if kind == "matte" else "")
        if k % 3 == 0:
            s = rng.uniform(0.4, 1.0)
            body += (f'  <box center="{x:.4f} {s / 2:.4f} {z:.4f}" size="{s:.4f} {s:.4f} {s:.4f}" '
                     f'rotate="0 {rng.uniform(0, 90):.2f} 0" {paint}/>\n')
        else:
            r = rng.uniform(0.2, 0.7)
            body += f'  <sphere center="{x:.4f} {r:.4f} {z:.4f}" radius="{r:.4f}" {paint}/>\n'
    return body + "</scene>\n"


def main():
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    out = sys.argv[1]
    os.makedirs(out, exist_ok=True)
    with open(os.path.join(out, "meshsphere.gltf"), "w") as f:
        f.write(sphere_gltf())
    for name, text in [("grid900", grid(900)), ("scatter3000", scatter(3000)),
                       ("tessellated", tessellated()), ("meshsphere", meshsphere()),
                       ("lamps", lamps())]:
        path = os.path.join(out, name + ".xml")
        with open(path, "w") as f:
            f.write(text)
        print(path)


if __name__ == "__main__":
    main()
