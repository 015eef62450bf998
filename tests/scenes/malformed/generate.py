#!/usr/bin/env python3
"""Writes the malformed glTF corpus next to this script: one file per way a glTF can be broken.

Every file must make the loader fail with a one-line hmb::Error (gltf_corpus_test.cpp), and the
CLI exit non-zero; the same files seed the loader's fuzzer (fuzz/). Run it again after editing;
the files are committed, so the tests do not need Python. `generate.py --seeds DIR` also writes
small valid files into DIR, the fuzzer's other seeds.
"""
import base64
import copy
import json
import math
import os
import struct
import sys

HERE = os.path.dirname(os.path.abspath(__file__))


def triangle_buffer(positions=None, indices=(0, 1, 2)):
    positions = positions or [(0.0, 0.0, 0.0), (1.0, 0.0, 0.0), (0.0, 1.0, 0.0)]
    data = b"".join(struct.pack("<3f", *p) for p in positions)
    index_bytes = struct.pack("<%dH" % len(indices), *indices)
    index_bytes += b"\0" * (-len(index_bytes) % 4)
    return data, index_bytes


def data_uri(raw):
    return "data:application/octet-stream;base64," + base64.b64encode(raw).decode()


def triangle_gltf(positions=None, indices=(0, 1, 2)):
    """A valid file: one triangle, one node, one scene."""
    pos, idx = triangle_buffer(positions, indices)
    # min and max of the finite coordinates: JSON has no NaN or Inf, the binary buffer does.
    coords = [[p[i] for p in (positions or [(0, 0, 0), (1, 0, 0), (0, 1, 0)]) if math.isfinite(p[i])] for i in range(3)]
    lo = [min(c, default=0.0) for c in coords]
    hi = [max(c, default=0.0) for c in coords]
    return {
        "asset": {"version": "2.0"},
        "scene": 0,
        "scenes": [{"nodes": [0]}],
        "nodes": [{"mesh": 0}],
        "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "indices": 1}]}],
        "buffers": [{"byteLength": len(pos) + len(idx), "uri": data_uri(pos + idx)}],
        "bufferViews": [
            {"buffer": 0, "byteOffset": 0, "byteLength": len(pos)},
            {"buffer": 0, "byteOffset": len(pos), "byteLength": len(idx)},
        ],
        "accessors": [
            {"bufferView": 0, "componentType": 5126, "count": len(pos) // 12, "type": "VEC3", "min": lo, "max": hi},
            {"bufferView": 1, "componentType": 5123, "count": len(indices), "type": "SCALAR"},
        ],
    }


def glb(document, binary=b""):
    text = json.dumps(document).encode()
    text += b" " * (-len(text) % 4)
    binary += b"\0" * (-len(binary) % 4)
    chunks = struct.pack("<II", len(text), 0x4E4F534A) + text
    if binary:
        chunks += struct.pack("<II", len(binary), 0x004E4942) + binary
    return struct.pack("<III", 0x46546C67, 2, 12 + len(chunks)) + chunks


def edited(edit):
    doc = triangle_gltf()
    edit(doc)
    return doc


def with_data(doc, raw, accessors):
    """Appends raw bytes to the document's buffer, one view per accessor (kind, count, component,
    byte length), and returns the new accessors' indices."""
    old = base64.b64decode(doc["buffers"][0]["uri"].split(",", 1)[1])
    offset = len(old)
    doc["buffers"][0] = {"byteLength": len(old) + len(raw), "uri": data_uri(old + raw)}
    indices = []
    for kind, count, component, length in accessors:
        doc["bufferViews"].append({"buffer": 0, "byteOffset": offset, "byteLength": length})
        doc["accessors"].append({"bufferView": len(doc["bufferViews"]) - 1, "componentType": component,
                                 "count": count, "type": kind})
        indices.append(len(doc["accessors"]) - 1)
        offset += length
    return indices


def skinned_triangle(joints=(0, 1, 0, 0) * 3, weights=(0.5, 0.5, 0, 0) * 3, inverse_binds=2):
    """The triangle skinned to two joint nodes (1 and 2) by JOINTS_0 / WEIGHTS_0."""
    doc = triangle_gltf()
    joint_bytes = struct.pack("<12H", *joints)
    weight_bytes = struct.pack("<12f", *weights)
    binds = struct.pack("<%df" % (16 * inverse_binds), *([1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1] * inverse_binds))
    j, w, m = with_data(doc, joint_bytes + weight_bytes + binds,
                        [("VEC4", 3, 5123, len(joint_bytes)), ("VEC4", 3, 5126, len(weight_bytes)),
                         ("MAT4", inverse_binds, 5126, len(binds))])
    doc["meshes"][0]["primitives"][0]["attributes"].update(JOINTS_0=j, WEIGHTS_0=w)
    doc["nodes"] = [{"mesh": 0, "skin": 0}, {"children": [2]}, {"translation": [1.0, 0.0, 0.0]}]
    doc["scenes"][0]["nodes"] = [0, 1]
    doc["skins"] = [{"joints": [1, 2], "inverseBindMatrices": m}]
    return doc


def morphing_triangle(target_positions=3, mesh_weights=(0.5,)):
    """The triangle with one morph target moving it along z."""
    doc = triangle_gltf()
    raw = struct.pack("<%df" % (3 * target_positions), *([0.0, 0.0, 1.0] * target_positions))
    (t,) = with_data(doc, raw, [("VEC3", target_positions, 5126, len(raw))])
    doc["meshes"][0]["primitives"][0]["targets"] = [{"POSITION": t}]
    doc["meshes"][0]["weights"] = list(mesh_weights)
    return doc


def write(name, content):
    path = os.path.join(HERE, name)
    mode = "wb" if isinstance(content, bytes) else "w"
    with open(path, mode) as f:
        if isinstance(content, dict):
            json.dump(content, f, indent=1, allow_nan=False)
        else:
            f.write(content)


def main():
    valid = json.dumps(triangle_gltf(), indent=1)
    write("empty.gltf", "")
    write("not-json.gltf", "this is { not json")
    write("truncated.gltf", valid[: len(valid) // 2])
    write("json-array.gltf", "[1, 2, 3]")
    write("no-asset.gltf", edited(lambda d: d.pop("asset")))
    write("gltf-version-1.gltf", edited(lambda d: d["asset"].update(version="1.0")))
    write("requires-unimplemented-extension.gltf",
          edited(lambda d: d.update(extensionsUsed=["KHR_texture_transform"], extensionsRequired=["KHR_texture_transform"])))

    def draco(d):
        # Compressed geometry: the accessor has no buffer view, the primitive decodes it.
        d["accessors"][0].pop("bufferView")
        d["meshes"][0]["primitives"][0]["extensions"] = {
            "KHR_draco_mesh_compression": {"bufferView": 0, "attributes": {"POSITION": 0}}}
        d["extensionsUsed"] = d["extensionsRequired"] = ["KHR_draco_mesh_compression"]

    write("requires-draco.gltf", edited(draco))
    write("wrong-type-count.gltf", edited(lambda d: d["accessors"][0].update(count="three")))
    write("wrong-type-component.gltf", edited(lambda d: d["accessors"][0].update(componentType="FLOAT")))
    write("wrong-accessor-type.gltf", edited(lambda d: d["accessors"][0].update(type="VEC2")))
    write("index-accessor-float.gltf", edited(lambda d: d["accessors"][1].update(componentType=5126)))
    write("index-out-of-range.gltf", triangle_gltf(indices=(0, 1, 99)))
    write("accessor-past-buffer.gltf", edited(lambda d: d["accessors"][0].update(count=1000)))
    write("accessor-offset-past-view.gltf", edited(lambda d: d["accessors"][0].update(byteOffset=1 << 20)))
    write("view-past-buffer.gltf", edited(lambda d: d["bufferViews"][1].update(byteLength=1 << 20)))
    write("huge-count.gltf", edited(lambda d: d["accessors"][0].update(count=4294967295)))
    write("huge-byte-length.gltf", edited(lambda d: d["buffers"][0].update(byteLength=1 << 62)))
    write("negative-count.gltf", edited(lambda d: d["accessors"][0].update(count=-3)))
    write("nan-position.gltf", triangle_gltf(positions=[(0, 0, 0), (math.nan, 0, 0), (0, 1, 0)]))
    write("inf-position.gltf", triangle_gltf(positions=[(0, 0, 0), (1, 0, 0), (0, math.inf, 0)]))
    write("node-cycle.gltf", edited(lambda d: d.update(nodes=[{"mesh": 0, "children": [1]}, {"children": [0]}])))
    write("node-own-child.gltf", edited(lambda d: d.update(nodes=[{"mesh": 0, "children": [0]}])))
    write("node-two-parents.gltf",
          edited(lambda d: d.update(nodes=[{"children": [2]}, {"children": [2]}, {"mesh": 0}],
                                    scenes=[{"nodes": [0, 1]}])))
    write("node-child-missing.gltf", edited(lambda d: d["nodes"][0].update(children=[7])))
    write("node-mesh-missing.gltf", edited(lambda d: d["nodes"][0].update(mesh=5)))
    write("scene-node-missing.gltf", edited(lambda d: d["scenes"][0].update(nodes=[3])))
    # 1e300 is a finite double but Inf as the float the scene holds.
    write("float-overflow-matrix.gltf", edited(lambda d: d["nodes"][0].update(matrix=[1e300] + [0.0] * 14 + [1.0])))
    write("missing-buffer-file.gltf", edited(lambda d: d["buffers"][0].update(uri="no-such-buffer.bin")))
    write("buffer-without-uri.gltf", edited(lambda d: d["buffers"][0].pop("uri")))
    write("bad-base64.gltf", edited(lambda d: d["buffers"][0].update(uri="data:application/octet-stream;base64,@@@@")))
    write("missing-image-file.gltf",
          edited(lambda d: d.update(images=[{"uri": "no-such-image.png"}], textures=[{"source": 0}],
                                    materials=[{"pbrMetallicRoughness": {"baseColorTexture": {"index": 0}}}])))
    write("material-missing.gltf", edited(lambda d: d["meshes"][0]["primitives"][0].update(material=4)))
    write("animation-bad-sampler.gltf",
          edited(lambda d: d.update(animations=[{"channels": [{"sampler": 3, "target": {"node": 0, "path": "translation"}}],
                                                  "samplers": []}])))
    write("skin-joint-out-of-range.gltf", skinned_triangle(joints=(0, 5, 0, 0) * 3))
    write("skin-negative-weight.gltf", skinned_triangle(weights=(1.5, -0.5, 0, 0) * 3))
    write("skin-nan-weight.gltf", skinned_triangle(weights=(math.nan, 0.5, 0, 0) * 3))
    write("skin-joint-missing.gltf", edited(lambda d: d.update(skins=[{"joints": [9]}])))
    write("skin-no-joints.gltf", edited(lambda d: d.update(skins=[{"joints": []}])))
    write("skin-few-inverse-binds.gltf", skinned_triangle(inverse_binds=1))
    write("skin-missing.gltf", edited(lambda d: d["nodes"][0].update(skin=3)))
    write("skin-joints-without-weights.gltf",
          (lambda d: (d["meshes"][0]["primitives"][0]["attributes"].pop("WEIGHTS_0"), d)[1])(skinned_triangle()))
    write("morph-target-count-differs.gltf", morphing_triangle(target_positions=2))
    write("morph-weights-count-differs.gltf", morphing_triangle(mesh_weights=(0.5, 0.5)))
    write("morph-node-weights-count-differs.gltf",
          (lambda d: (d["nodes"][0].update(weights=[1.0, 2.0, 3.0]), d)[1])(morphing_triangle()))
    pos, idx = triangle_buffer()
    document = triangle_gltf()
    document["buffers"] = [{"byteLength": len(pos) + len(idx)}]
    whole = glb(document, pos + idx)
    write("glb-truncated-header.glb", whole[:10])
    write("glb-truncated-json.glb", whole[:40])
    write("glb-truncated-binary.glb", whole[: len(whole) - 8])
    write("glb-bad-length.glb", whole[:8] + struct.pack("<I", 1 << 30) + whole[12:])
    write("glb-bad-chunk-length.glb", whole[:12] + struct.pack("<I", 1 << 30) + whole[16:])
    write("glb-wrong-version.glb", whole[:4] + struct.pack("<I", 7) + whole[8:])


def write_valid_seeds(directory):
    os.makedirs(directory, exist_ok=True)
    animated = triangle_gltf()
    times, moves = struct.pack("<2f", 0.0, 1.0), struct.pack("<6f", 0, 0, 0, 1, 0, 0)
    raw = base64.b64decode(animated["buffers"][0]["uri"].split(",", 1)[1]) + times + moves
    offset = animated["buffers"][0]["byteLength"]
    animated["buffers"][0] = {"byteLength": len(raw), "uri": data_uri(raw)}
    animated["bufferViews"] += [{"buffer": 0, "byteOffset": offset, "byteLength": 8},
                                {"buffer": 0, "byteOffset": offset + 8, "byteLength": 24}]
    animated["accessors"] += [{"bufferView": 2, "componentType": 5126, "count": 2, "type": "SCALAR",
                               "min": [0.0], "max": [1.0]},
                              {"bufferView": 3, "componentType": 5126, "count": 2, "type": "VEC3"}]
    animated["animations"] = [{"samplers": [{"input": 2, "output": 3}],
                               "channels": [{"sampler": 0, "target": {"node": 0, "path": "translation"}}]}]
    animated["nodes"].append({"camera": 0, "translation": [0.0, 0.0, 3.0]})
    animated["scenes"][0]["nodes"].append(1)
    animated["cameras"] = [{"type": "perspective", "perspective": {"yfov": 0.8, "znear": 0.1}}]
    animated["materials"] = [{"pbrMetallicRoughness": {"baseColorFactor": [0.8, 0.2, 0.1, 1.0]}}]
    animated["meshes"][0]["primitives"][0]["material"] = 0
    with open(os.path.join(directory, "valid-triangle.gltf"), "w") as f:
        json.dump(triangle_gltf(), f)
    with open(os.path.join(directory, "valid-skinned.gltf"), "w") as f:
        json.dump(skinned_triangle(), f)
    with open(os.path.join(directory, "valid-morphing.gltf"), "w") as f:
        json.dump(morphing_triangle(), f)
    with open(os.path.join(directory, "valid-animated.gltf"), "w") as f:
        json.dump(animated, f)
    pos, idx = triangle_buffer()
    document = triangle_gltf()
    document["buffers"] = [{"byteLength": len(pos) + len(idx)}]
    with open(os.path.join(directory, "valid-triangle.glb"), "wb") as f:
        f.write(glb(document, pos + idx))


if __name__ == "__main__":
    main()
    if len(sys.argv) == 3 and sys.argv[1] == "--seeds":
        write_valid_seeds(sys.argv[2])
