#!/usr/bin/env python3
"""Converts MakeHuman's CC0 base mesh, default skeleton, skin weights and a few body-shape targets
into human.txt, the skinned human of the scene generator (hil/sim/src/skinned_body.hpp reads it;
README.md beside this file says what it holds and where it comes from).

    convert.py MAKEHUMAN_CHECKOUT [--out human.txt]

MAKEHUMAN_CHECKOUT is a clone of github.com/makehumancommunity/makehuman (its makehuman/data
folder is read). Only the asset files are read; none of MakeHuman's code is used.

What it does, and why:
- keeps the faces of the "body" group (the helper geometry for clothes, eyes, teeth and the
  joint cubes is dropped) and splits each quad into two triangles;
- turns MakeHuman's axes (decimetres, Y up, facing +Z, +X the figure's left) into ours (mm, Z up,
  facing -Y, +X the figure's left: hanim_to_world() of host/src/body/hanim_model.cpp);
- places every node of our H-Anim skeleton (hanim_model.cpp) in the mesh as a fixed linear
  combination of mesh vertices, so that a body-shape target moves the joints with the skin.
  MakeHuman defines each bone's head and tail as the mean of a few vertices; our limb joints are
  those heads and tails (the mapping below), the root and the vertebrae lie on the mesh's spine
  (from the hips' midpoint up) at the thesis' height fractions between the hips and skullbase,
  and the heel, toe tip and skull top are single surface vertices;
- merges the weights of MakeHuman's 163 bones onto the H-Anim node whose orientation moves that
  part of the body (the mapping below), and keeps the four largest per vertex;
- stores each target's offsets on the body vertices (0.1 mm; offsets under 0.05 mm dropped) and the
  subjects as sums of targets.
"""
import argparse
import json
import re
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent
HANIM_SOURCE = HERE.parents[2] / "host/src/body/hanim_model.cpp"

# The subjects: target weights on the base mesh. The base mesh is MakeHuman's neutral figure;
# a "<race>-<gender>-young" target makes it a young adult of that gender (MakeHuman's default
# human blends the three); the height and weight targets are those of average muscle. A height
# target at full weight makes a 1.24 m or a 2.47 m adult: a quarter and a fifth of it give
# 1.51 m and 1.89 m (skinned_body_test checks the heights).
SUBJECTS = {
    "average-male": {"caucasian-male-young": 1.0},
    "short-female": {"caucasian-female-young": 1.0,
                     "female-young-averagemuscle-averageweight-minheight": 0.25},
    "tall-male": {"caucasian-male-young": 1.0,
                  "male-young-averagemuscle-averageweight-maxheight": 0.2},
    "heavy-male": {"african-male-young": 1.0,
                   "universal-male-young-averagemuscle-maxweight": 1.0},
    "heavy-female": {"asian-female-young": 1.0,
                     "universal-female-young-averagemuscle-maxweight": 1.0},
}
TARGET_FOLDERS = {
    "caucasian-male-young": "macrodetails",
    "caucasian-female-young": "macrodetails",
    "african-male-young": "macrodetails",
    "asian-female-young": "macrodetails",
    "universal-male-young-averagemuscle-maxweight": "macrodetails",
    "universal-female-young-averagemuscle-maxweight": "macrodetails",
    "female-young-averagemuscle-averageweight-minheight": "macrodetails/height",
    "male-young-averagemuscle-averageweight-maxheight": "macrodetails/height",
}

# H-Anim joint -> MakeHuman joint (a bone's head or tail), per side ("{s}" is l or r, "{S}" L or R).
SIDE_JOINTS = {
    "{s}_hip": "upperleg01.{S}____head",
    "{s}_knee": "lowerleg01.{S}____head",
    "{s}_ankle": "foot.{S}____head",
    "{s}_midtarsal": "foot.{S}____tail",
    "{s}_metatarsal": "toe3-1.{S}____head",
    "{s}_sternoclavicular": "clavicle.{S}____head",
    "{s}_acromioclavicular": "clavicle.{S}____tail",
    "{s}_shoulder": "upperarm01.{S}____head",
    "{s}_elbow": "lowerarm01.{S}____head",
    "{s}_wrist": "wrist.{S}____head",
}
FINGERS = {"thumb": 1, "index": 2, "middle": 3, "ring": 4, "pinky": 5}
for _name, _k in FINGERS.items():
    if _k > 1:
        SIDE_JOINTS["{s}_" + _name + "0"] = f"metacarpal{_k - 1}.{{S}}____head"
    for _j in (1, 2, 3):
        SIDE_JOINTS["{s}_" + _name + str(_j)] = f"finger{_k}-{_j}.{{S}}____head"

# MakeHuman bone -> the H-Anim node whose orientation moves it (a name, or "spine" for the nearest
# vertebra, "skullbase" for the head and everything on it).
SIDE_BONES = {
    "pelvis": "sacroiliac", "upperleg01": "{s}_hip", "upperleg02": "{s}_hip",
    "lowerleg01": "{s}_knee", "lowerleg02": "{s}_knee", "foot": "{s}_ankle",
    "clavicle": "{s}_sternoclavicular", "shoulder01": "{s}_acromioclavicular",
    "upperarm01": "{s}_shoulder", "upperarm02": "{s}_shoulder",
    "lowerarm01": "{s}_elbow", "lowerarm02": "{s}_elbow", "wrist": "{s}_wrist",
    "breast": "spine",
}


def to_world(p_dm):
    """MakeHuman (dm, Y up, +Z front) -> ours (mm, Z up, -Y front)."""
    p = np.asarray(p_dm, dtype=float) * 100.0
    return np.stack([p[..., 0], -p[..., 2], p[..., 1]], axis=-1)


def read_obj(path):
    vertices, faces, group = [], [], None
    for line in path.read_text().splitlines():
        if line.startswith("v "):
            vertices.append([float(x) for x in line.split()[1:4]])
        elif line.startswith("g "):
            group = line.split()[1]
        elif line.startswith("f ") and group == "body":
            faces.append([int(t.split("/")[0]) - 1 for t in line.split()[1:]])
    return np.array(vertices), faces


def read_target(path):
    offsets = {}
    for line in path.read_text().splitlines():
        if line.startswith("#") or not line.strip():
            continue
        i, dx, dy, dz = line.split()
        offsets[int(i)] = [float(dx), float(dy), float(dz)]
    return offsets


def hanim_nodes():
    """(name, parent, thesis y in mm) of every node of hanim_skeleton(), in its order."""
    rows = re.findall(r'\{"(\w+)", "(\w*)", \{([-\d., ]+)\}, \d+\}', HANIM_SOURCE.read_text())
    return [(name, parent, float(xyz.split(",")[1])) for name, parent, xyz in rows]


class Joints:
    """MakeHuman's joints: each the mean of a few vertices, kept as {vertex: coefficient}."""

    def __init__(self, skeleton, vertices):
        self.defs = {k: {i: 1.0 / len(v) for i in v} for k, v in skeleton["joints"].items()}
        self.vertices = vertices

    def at(self, combo):
        return sum(c * self.vertices[i] for i, c in combo.items())

    def __getitem__(self, name):
        return self.defs[name]


def blend(*weighted):
    out = {}
    for w, combo in weighted:
        for i, c in combo.items():
            out[i] = out.get(i, 0.0) + w * c
    return out


def spine_polyline(joints):
    chain = ["spine05", "spine04", "spine03", "spine02", "spine01", "neck01", "neck02",
             "neck03", "head"]
    return [joints[b + "____head"] for b in chain]


def point_on_polyline(joints, points, fraction):
    xyz = [joints.at(p) for p in points]
    lengths = np.array([np.linalg.norm(b - a) for a, b in zip(xyz, xyz[1:])])
    target = fraction * lengths.sum()
    for k, length in enumerate(lengths):
        if target <= length or k == len(lengths) - 1:
            t = min(max(target / length, 0.0), 1.0)
            return blend((1 - t, points[k]), (t, points[k + 1]))
        target -= length
    raise AssertionError("unreachable")


def extreme_vertex(vertices, weights, bones, axis, sign):
    """The vertex moved mostly by `bones` that lies furthest along sign * axis."""
    candidates = [i for i, w in weights.items() if max(w, key=w.get) in bones]
    return max(candidates, key=lambda i: sign * vertices[i][axis])


def node_definitions(nodes, joints, vertices, bone_weights):
    thesis_y = {name: y for name, _, y in nodes}
    # The trunk's nodes lie on the mesh's spine (the hips' midpoint, then the spine05 ... head
    # bone heads) at the thesis' height fractions between the hips and skullbase, so that the
    # root and the vertebrae mean what the fitted model means by them (the thesis root sits 23 %
    # of the way from the hips to skullbase; MakeHuman's spine05 head only 3 % of the way).
    hips = blend((0.5, joints["upperleg01.L____head"]), (0.5, joints["upperleg01.R____head"]))
    spine = [hips] + spine_polyline(joints)
    base = 0.5 * (thesis_y["l_hip"] + thesis_y["r_hip"])
    top = thesis_y["skullbase"]
    defs = {}
    for name, _, y in nodes:
        if name == "skullbase":
            defs[name] = spine[-1]
        elif name in ("HumanoidRoot", "HumanoidRoot2", "sacroiliac") or (
                name[0] == "v" and name[1] in "lct" and name[2:].isdigit()):
            defs[name] = point_on_polyline(joints, spine, (y - base) / (top - base))
    world = to_world(vertices)
    per_vertex = bone_weights_per_vertex(bone_weights)
    for s, S in (("l", "L"), ("r", "R")):
        for ours, theirs in SIDE_JOINTS.items():
            defs[ours.format(s=s)] = joints[theirs.format(S=S)]
        defs[f"{s}_subtalar"] = blend((0.5, joints[f"foot.{S}____head"]),
                                      (0.5, joints[f"foot.{S}____tail"]))
        foot = {f"foot.{S}"} | {b for b in bone_weights if b.startswith("toe") and b.endswith(S)}
        defs[f"{s}_calcaneus_posterior"] = {extreme_vertex(world, per_vertex, foot, 1, +1): 1.0}
        defs[f"{s}_forefoot_tip"] = {extreme_vertex(world, per_vertex, foot, 1, -1): 1.0}
    defs["skull_tip"] = {extreme_vertex(world, per_vertex, {"head"}, 2, +1): 1.0}
    missing = [name for name, _, _ in nodes if name not in defs]
    if missing:
        raise SystemExit(f"convert.py: no place in the mesh for {missing}")
    return defs


def bone_weights_per_vertex(bone_weights):
    per = {}
    for bone, pairs in bone_weights.items():
        for i, w in pairs:
            per.setdefault(i, {})[bone] = w
    return per


def bone_to_node(bone, skeleton, node_xyz, spine_nodes, joints):
    if bone.endswith((".L", ".R")):
        stem, S = bone[:-2], bone[-1]
        s = S.lower()
        if stem.startswith("finger"):
            k, j = (int(x) for x in stem[6:].split("-"))
            name = next(n for n, kk in FINGERS.items() if kk == k)
            return f"{s}_{name}{j}"
        if stem.startswith("metacarpal"):
            name = next(n for n, kk in FINGERS.items() if kk == int(stem[10:]) + 1)
            return f"{s}_{name}0"
        if stem.startswith("toe"):
            return f"{s}_metatarsal"
        if stem in SIDE_BONES and SIDE_BONES[stem] != "spine":
            return SIDE_BONES[stem].format(s=s)
    if bone == "root":
        return "sacroiliac"
    if bone.startswith(("spine", "neck", "breast")):
        head = joints.at(joints[skeleton["bones"][bone]["head"]])
        return min(spine_nodes, key=lambda n: np.linalg.norm(node_xyz[n] - head))
    return "skullbase"  # the head's bones: face, eyes, jaw, tongue


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("makehuman", type=Path)
    parser.add_argument("--out", type=Path, default=HERE / "human.txt")
    args = parser.parse_args()
    data = args.makehuman / "makehuman/data"
    vertices, faces = read_obj(data / "3dobjs/base.obj")
    body = sorted({i for f in faces for i in f})
    assert body == list(range(len(body))), "the body's vertices are expected first"
    count = len(body)
    skeleton = json.loads((data / "rigs/default.mhskel").read_text())
    bone_weights = json.loads((data / "rigs/default_weights.mhw").read_text())["weights"]
    joints = Joints(skeleton, vertices)
    nodes = hanim_nodes()
    defs = node_definitions(nodes, joints, vertices, bone_weights)
    node_index = {name: k for k, (name, _, _) in enumerate(nodes)}
    node_xyz = {n: joints.at(c) for n, c in defs.items()}
    spine_nodes = [n for n in defs if n[0] == "v" and n[1] in "lct" and n[2:].isdigit()]

    merged = [dict() for _ in range(count)]
    for bone, pairs in bone_weights.items():
        node = node_index[bone_to_node(bone, skeleton, node_xyz, spine_nodes, joints)]
        for i, w in pairs:
            if i < count:
                merged[i][node] = merged[i].get(node, 0.0) + w
    for i, m in enumerate(merged):
        if not m:
            raise SystemExit(f"convert.py: body vertex {i} has no skin weight")

    # The joints' helper vertices (MakeHuman's joint cubes) follow the body's: the shape targets
    # move them too, and they are not drawn.
    helpers = sorted({i for combo in defs.values() for i in combo if i >= count})
    renumber = {i: i for i in range(count)}
    renumber.update({i: count + k for k, i in enumerate(helpers)})
    kept_vertices = list(range(count)) + helpers
    world = to_world(vertices[kept_vertices])
    lines = ["syncap-skinned-human 1",
             "# MakeHuman base mesh, default skeleton and weights (CC0 1.0), converted by",
             "# hil/assets/makehuman/convert.py; README.md beside this file says how.",
             f"vertices {len(kept_vertices)} skinned {count}"]
    lines += [f"{x:.2f} {y:.2f} {z:.2f}" for x, y, z in world]
    tris = []
    for f in faces:
        tris += [(f[0], f[1], f[2]), (f[0], f[2], f[3])] if len(f) == 4 else [tuple(f)]
    lines.append(f"triangles {len(tris)}")
    lines += [f"{a} {b} {c}" for a, b, c in tris]
    lines.append(f"nodes {len(nodes)}")
    for name, _, _ in nodes:
        combo = sorted((renumber[i], c) for i, c in defs[name].items())
        lines.append(f"{name} {len(combo)} " + " ".join(f"{i} {c:.6g}" for i, c in combo))
    lines.append(f"weights {count}")
    for m in merged:
        top = sorted(m.items(), key=lambda kv: -kv[1])[:4]
        total = sum(w for _, w in top)
        lines.append(f"{len(top)} " + " ".join(f"{n} {w / total:.4f}" for n, w in top))
    for name, folder in TARGET_FOLDERS.items():
        offsets = read_target(data / "targets" / folder / f"{name}.target")
        kept = []
        for i, d in sorted(offsets.items()):
            if i not in renumber:
                continue
            w = to_world(d)
            if np.abs(w).max() >= 0.05:
                kept.append(f"{renumber[i]} {w[0]:.1f} {w[1]:.1f} {w[2]:.1f}")
        lines.append(f"target {name} {len(kept)}")
        lines += kept
    for name, mix in SUBJECTS.items():
        lines.append(f"subject {name} {len(mix)} " +
                     " ".join(f"{t} {w:g}" for t, w in mix.items()))
    args.out.write_text("\n".join(lines) + "\n")
    print(f"convert.py: {count} vertices, {len(tris)} triangles, {len(nodes)} nodes, "
          f"{len(TARGET_FOLDERS)} targets, {len(SUBJECTS)} subjects -> {args.out}")


if __name__ == "__main__":
    main()
