#!/usr/bin/env python3
"""Writes the deforming test scenes next to this script (the files are committed, so the tests do
not need Python; run it again after editing):

- skinned-arm.gltf: a tube of three joints, each swinging about z at 2 Hz (the tip moves about
  20 units a second), in front of a wall;
- morphing-sphere.gltf: a sphere with two morph targets (an inflation along the normals; a
  stretch along y that narrows it in x and z, with its normal displacements), their weights
  animated at 6 Hz in opposition, in front of a wall. At the default frame time (0.5 s) the
  inflation gives way to the stretch fastest: the sides sweep in, uncovering the wall; 1/12 s
  later the other way round, the sphere growing over the wall.

Both animate over [0, 1] s with linear keys every 1/120 s; past 1 s they hold still.

`generate.py --dense DIR` writes skinned-arm-dense.gltf into DIR instead: the same arm with
52,224 vertices, for the benchmark of deformation's cost (bench/results/passes/deforming/).
"""
import base64
import json
import math
import os
import struct
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
FLOAT, UNSIGNED_SHORT, UNSIGNED_INT = 5126, 5123, 5125


class Document:
    def __init__(self):
        self.doc = {"asset": {"version": "2.0", "generator": "hybrid-mblur tests/scenes/deforming/generate.py"},
                    "scene": 0, "scenes": [{"nodes": []}], "nodes": [], "meshes": [], "materials": [],
                    "accessors": [], "bufferViews": [], "buffers": []}
        self.bin = b""

    def accessor(self, values, kind, component=FLOAT, count=None, minmax=False):
        fmt = {FLOAT: "f", UNSIGNED_SHORT: "H", UNSIGNED_INT: "I"}[component]
        raw = struct.pack("<%d%s" % (len(values), fmt), *values)
        raw += b"\0" * (-len(raw) % 4)
        self.doc["bufferViews"].append({"buffer": 0, "byteOffset": len(self.bin), "byteLength": len(raw)})
        self.bin += raw
        width = {"SCALAR": 1, "VEC3": 3, "VEC4": 4, "MAT4": 16}[kind]
        acc = {"bufferView": len(self.doc["bufferViews"]) - 1, "componentType": component,
               "count": count if count is not None else len(values) // width, "type": kind}
        if minmax:
            acc["min"] = [min(values[i::width]) for i in range(width)]
            acc["max"] = [max(values[i::width]) for i in range(width)]
        self.doc["accessors"].append(acc)
        return len(self.doc["accessors"]) - 1

    def node(self, node, root=True):
        self.doc["nodes"].append(node)
        index = len(self.doc["nodes"]) - 1
        if root:
            self.doc["scenes"][0]["nodes"].append(index)
        return index

    def material(self, rgb, double_sided=False):
        self.doc["materials"].append({"pbrMetallicRoughness": {"baseColorFactor": list(rgb) + [1.0]},
                                      "doubleSided": double_sided})
        return len(self.doc["materials"]) - 1

    def mesh(self, positions, normals, indices, material, **extra):
        primitive = {"attributes": {"POSITION": self.accessor(positions, "VEC3", minmax=True),
                                    "NORMAL": self.accessor(normals, "VEC3")},
                     "indices": self.accessor(indices, "SCALAR", UNSIGNED_INT), "material": material}
        self.doc["meshes"].append(dict(primitives=[primitive], **extra))
        return len(self.doc["meshes"]) - 1

    def wall(self, z, half, rgb):
        positions = [-half, -half, z, half, -half, z, half, half, z, -half, half, z]
        mesh = self.mesh(positions, [0, 0, 1] * 4, [0, 1, 2, 0, 2, 3], self.material(rgb))
        self.node({"mesh": mesh, "name": "wall"})

    def camera(self, eye):
        self.doc["cameras"] = [{"type": "perspective", "perspective": {"yfov": 0.8, "znear": 0.1, "zfar": 100.0}}]
        self.node({"camera": 0, "translation": list(eye), "name": "camera"})

    def write(self, name, directory=HERE):
        self.doc["buffers"] = [{"byteLength": len(self.bin),
                                "uri": "data:application/octet-stream;base64," + base64.b64encode(self.bin).decode()}]
        with open(os.path.join(directory, name), "w") as f:
            json.dump(self.doc, f, indent=1)


KEY_TIMES = [k / 120.0 for k in range(121)]


def skinned_arm(rings=31, around=16, name="skinned-arm.gltf", directory=HERE):
    d = Document()
    d.camera((1.5, 0.3, 4.5))
    d.wall(-2.0, 8.0, (0.25, 0.35, 0.6))
    radius, length = 0.25, 3.0
    positions, normals, joints, weights, indices = [], [], [], [], []
    for r in range(rings):
        x = length * r / (rings - 1)
        # Each joint k leads the segment centred at x = k + 0.5; neighbours blend linearly.
        w = [max(0.0, 1.0 - abs(x - (k + 0.5))) if 0.5 <= x <= 2.5 or k == min(2, int(x)) else 0.0 for k in range(3)]
        total = sum(w)
        for a in range(around):
            angle = 2.0 * math.pi * a / around
            y, z = math.cos(angle), math.sin(angle)
            positions += [x, radius * y, radius * z]
            normals += [0.0, y, z]
            joints += [0, 1, 2, 0]
            weights += [v / total for v in w] + [0.0]
    for r in range(rings - 1):
        for a in range(around):
            i0, i1 = r * around + a, r * around + (a + 1) % around
            j0, j1 = i0 + around, i1 + around
            indices += [i0, j0, i1, i1, j0, j1]
    material = d.material((0.9, 0.45, 0.1), double_sided=True)
    mesh = d.mesh(positions, normals, indices, material)
    primitive = d.doc["meshes"][mesh]["primitives"][0]
    primitive["attributes"]["JOINTS_0"] = d.accessor(joints, "VEC4", UNSIGNED_SHORT, count=len(joints) // 4)
    primitive["attributes"]["WEIGHTS_0"] = d.accessor(weights, "VEC4")
    # The joint chain: shoulder at the origin, elbow and wrist a unit apart along x.
    wrist = d.node({"name": "wrist", "translation": [1.0, 0.0, 0.0]}, root=False)
    elbow = d.node({"name": "elbow", "translation": [1.0, 0.0, 0.0], "children": [wrist]}, root=False)
    shoulder = d.node({"name": "shoulder", "children": [elbow]})
    inverse_bind = []
    for k in range(3):
        inverse_bind += [1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, -float(k), 0, 0, 1]
    d.doc["skins"] = [{"joints": [shoulder, elbow, wrist], "inverseBindMatrices": d.accessor(inverse_bind, "MAT4")}]
    d.node({"name": "arm", "mesh": mesh, "skin": 0})
    times = d.accessor(KEY_TIMES, "SCALAR", minmax=True)
    channels, samplers = [], []
    for joint, amplitude, phase in ((shoulder, 0.5, 0.0), (elbow, 0.8, 0.7), (wrist, 0.8, 1.4)):
        rotations = []
        for t in KEY_TIMES:
            half = 0.5 * amplitude * math.sin(2.0 * math.pi * 2.0 * t + phase)
            rotations += [0.0, 0.0, math.sin(half), math.cos(half)]
        samplers.append({"input": times, "output": d.accessor(rotations, "VEC4"), "interpolation": "LINEAR"})
        channels.append({"sampler": len(samplers) - 1, "target": {"node": joint, "path": "rotation"}})
    d.doc["animations"] = [{"name": "swing", "channels": channels, "samplers": samplers}]
    d.write(name, directory)


def morphing_sphere():
    d = Document()
    d.camera((0.0, 0.0, 8.0))
    d.wall(-2.5, 8.0, (0.3, 0.55, 0.3))
    stacks, slices = 16, 24
    positions, normals, inflate, stretch, stretch_normals, indices = [], [], [], [], [], []
    for s in range(stacks + 1):
        phi = math.pi * s / stacks
        for k in range(slices + 1):
            theta = 2.0 * math.pi * k / slices
            n = (math.sin(phi) * math.cos(theta), math.cos(phi), math.sin(phi) * math.sin(theta))
            positions += list(n)
            normals += list(n)
            inflate += [0.8 * c for c in n]
            stretch += [-0.3 * n[0], 0.6 * n[1], -0.3 * n[2]]
            # The stretched sphere's normal (x / 0.7, y / 1.6, z / 0.7), normalized, minus the sphere's.
            m = (n[0] / 0.7, n[1] / 1.6, n[2] / 0.7)
            length = math.sqrt(sum(c * c for c in m))
            stretch_normals += [m[i] / length - n[i] for i in range(3)]
    for s in range(stacks):
        for k in range(slices):
            a, b = s * (slices + 1) + k, (s + 1) * (slices + 1) + k
            indices += [a, b, a + 1, a + 1, b, b + 1]
    material = d.material((0.8, 0.2, 0.5))
    mesh = d.mesh(positions, normals, indices, material, weights=[0.0, 0.0])
    d.doc["meshes"][mesh]["primitives"][0]["targets"] = [
        {"POSITION": d.accessor(inflate, "VEC3", minmax=True)},
        {"POSITION": d.accessor(stretch, "VEC3", minmax=True), "NORMAL": d.accessor(stretch_normals, "VEC3")},
    ]
    sphere = d.node({"name": "sphere", "mesh": mesh})
    times = d.accessor(KEY_TIMES, "SCALAR", minmax=True)
    values = []
    for t in KEY_TIMES:
        phase = math.sin(2.0 * math.pi * 6.0 * t)
        values += [0.5 - 0.5 * phase, 0.5 + 0.5 * phase]
    d.doc["animations"] = [{"name": "breathe",
                            "samplers": [{"input": times, "output": d.accessor(values, "SCALAR"), "interpolation": "LINEAR"}],
                            "channels": [{"sampler": 0, "target": {"node": sphere, "path": "weights"}}]}]
    d.write("morphing-sphere.gltf")


if __name__ == "__main__":
    if len(sys.argv) == 3 and sys.argv[1] == "--dense":
        os.makedirs(sys.argv[2], exist_ok=True)
        skinned_arm(rings=408, around=128, name="skinned-arm-dense.gltf", directory=sys.argv[2])
    else:
        skinned_arm()
        morphing_sphere()
