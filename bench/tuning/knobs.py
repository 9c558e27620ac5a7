"""The knobs the tuner turns, which of them a scene uses, and the overlay that sets them.

Each knob is a dotted scene key (docs/scene-format.md) with candidate values ordered from the
most accurate to the cheapest guess; the measured sweep decides what is actually cheapest.
"""
from dataclasses import dataclass, field

import yaml


@dataclass
class Knob:
    name: str                 # shown in tables and plots
    keys: tuple               # the dotted scene keys it sets (one value each)
    values: list              # candidate values, each a tuple with one entry per key
    scene_value: tuple = None  # what the scene itself says (or the loader's default)
    why: str = ""
    sweep: list = field(default_factory=list)  # (value, figures) once measured

    def label(self, value):
        return "/".join(fmt(v) for v in value)


def fmt(v):
    return f"{v:g}" if isinstance(v, float) else str(v)


def merged_scene(path):
    """The scene's mapping, its overlay_of chain merged as the loader merges it."""
    with open(path) as f:
        doc = yaml.safe_load(f) or {}
    base = doc.pop("overlay_of", None)
    if base is None:
        return doc
    from pathlib import Path
    under = merged_scene(Path(path).parent / base)
    merge(under, doc)
    return under


def merge(base, overlay):
    for k, v in overlay.items():
        if isinstance(base.get(k), dict) and isinstance(v, dict):
            merge(base[k], v)
        else:
            base[k] = v


def get(scene, dotted, default):
    node = scene
    for part in dotted.split("."):
        if not isinstance(node, dict) or part not in node:
            return default
        node = node[part]
    return node


def scene_uses(scene):
    """Which entity types move in this scene (the dead-reckoning models that matter)."""
    kinds = {p.get("kind") for p in scene.get("populations", []) or []}
    return {"npc": "npc" in kinds or bool(get(scene, "agents.populations", None)),
            "rigid_body": "rigid_body" in kinds or bool(get(scene, "physics.bodies", None)),
            "avatar": True}  # the tuner's runs always have players


def knobs_for(scene):
    """The knobs of this scene, each with its candidates and the scene's own value."""
    uses = scene_uses(scene)
    dr = "dead_reckoning."
    threshold = float(get(scene, dr + "position_threshold", 0.5))
    knobs = [Knob("position threshold m", (dr + "position_threshold",),
                  [(v,) for v in sorted({0.05, 0.1, 0.25, 0.5, 1.0, threshold})],
                  (threshold,), "prediction error before the zone sends an update")]
    for kind, default in (("npc", "first"), ("avatar", "first"), ("rigid_body", "second")):
        if uses[kind]:
            key = f"{dr}models.{kind}.order"
            knobs.append(Knob(f"{kind} order", (key,), [("second",), ("first",)],
                              (get(scene, key, default),), f"the {kind}s' dead-reckoning model"))
    q = dr + "quantisation."
    res_key, bits_key = q + "position_resolution", q + "rotation_bits"
    own = (float(get(scene, res_key, 1 / 512)), int(get(scene, bits_key, 10)))
    pairs = sorted({(1 / 2048, 12), (1 / 512, 10), (1 / 128, 8), (1 / 32, 6), own}, key=lambda p: p[0])
    knobs.append(Knob("quantisation m/bits", (res_key, bits_key), pairs, own,
                      "the wire's position step and orientation bits"))
    for k in knobs:  # the scene's own value is always a candidate (its run is the baseline)
        if k.scene_value not in k.values:
            k.values.append(k.scene_value)
    return knobs


def overlay_text(base_path, settings, header_lines):
    """YAML text of an overlay of base_path setting each dotted key of `settings`."""
    tree = {}
    for dotted, value in settings.items():
        node = tree
        *parents, last = dotted.split(".")
        for p in parents:
            node = node.setdefault(p, {})
        node[last] = value
    body = yaml.safe_dump(tree, default_flow_style=False, sort_keys=True)
    head = "".join(f"# {l}\n" for l in header_lines)
    return f"{head}overlay_of: {base_path}\n{body}"
