"""The knobs the tuner turns, which of them a scene uses, and the overlay that sets them.

Each knob is a dotted scene key (docs/scene-format.md) with candidate values ordered from the
most accurate to the cheapest guess; the measured sweep decides what is actually cheapest.
A knob says which figure it trades against which (tuning/budget.py's metrics): the wire's
knobs trade download against the error players are shown, the physics knobs physics time
against how far resting bodies end from the reference run (each physics knob at its first,
most accurate, value).
"""
import math
from dataclasses import dataclass, field

import yaml


@dataclass
class Knob:
    name: str                 # shown in tables and plots
    keys: tuple               # the dotted scene keys it sets (one value each)
    values: list              # candidate values, each a tuple with one entry per key
    scene_value: tuple = None  # what the scene itself says (or the loader's default)
    why: str = ""
    cost: str = "kbps_per_client"       # the figure a cheaper value lowers
    accuracy: str = "shown_error_p99"   # the figure it costs, and which wins a tie
    sweep: list = field(default_factory=list)  # (value, figures) once measured
    failed: list = field(default_factory=list)  # (value, why) of the runs that did not finish
    # Values measured for the frontier but never chosen: what they do depends on the machine's
    # load at start-up (gpu.mode auto probes), so one run's figures do not hold for the next.
    unsettled: tuple = ()

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
    populations = scene.get("populations", []) or []
    kinds = {p.get("kind") for p in populations}
    return {"npc": "npc" in kinds or bool(get(scene, "agents.populations", None)),
            "rigid_body": "rigid_body" in kinds or bool(get(scene, "physics.bodies", None)),
            "flow": any(isinstance(p, dict) and isinstance(p.get("flow"), dict) for p in populations),
            "paths": isinstance(scene.get("map"), dict) and bool(get(scene, "agents.populations", None)) and
            any(isinstance(t, dict) and t.get("navigate") for t in get(scene, "agents.types", []) or []),
            "flock": any(isinstance(p, dict) and isinstance(p.get("flock"), dict) for p in populations),
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
    if uses["rigid_body"]:
        knobs += physics_knobs(scene)
    if uses["flow"] and isinstance(scene.get("lod"), dict):
        knobs += crowd_knobs(scene)
    if uses["paths"]:
        knobs += path_knobs(scene)
    if uses["flock"]:
        knobs.append(gpu_knob(scene))
    for k in knobs:  # the scene's own value is always a candidate (its run is the baseline)
        if k.scene_value not in k.values:
            k.values.append(k.scene_value)
    return knobs


def physics_knobs(scene):
    """The solver's knobs (docs/scene-format.md, `physics`), and the physics level of detail
    where the scene has a `lod` section (setting lod.physics_every without one would switch on
    the crowds' level of detail too). Values most accurate first: the first of each is the
    reference run's."""
    ph = "physics."

    def knob(name, key, values, default, why):
        own = get(scene, key, default)
        return Knob(name, (key,), [(v,) for v in values], (own,), why,
                    cost="physics_ms", accuracy="stack_drift")

    # No solver kind is the more accurate as such: the reference keeps the scene's own. The wide
    # soft step does not solve rolling resistance: the loader's default gives way to the soft
    # step in a scene with some, and naming the wide step there is refused.
    rolls = any((b or {}).get("rolling_resistance", 0) > 0
                for b in (get(scene, ph + "bodies", []) or []) + (scene.get("populations", []) or []))
    default_solver = "soft_step" if rolls else "soft_step_wide"
    kinds = ("gauss_seidel", "soft_step") if rolls else ("gauss_seidel", "soft_step", "soft_step_wide")
    own_solver = get(scene, ph + "solver", default_solver)
    solvers = [own_solver] + [s for s in kinds if s != own_solver]

    knobs = [knob("velocity iterations", ph + "velocity_iterations", [40, 20, 10, 5, 2], 10,
                  "sequential-impulse iterations per substep"),
             knob("substeps", ph + "substeps", [4, 2, 1], 1, "engine steps per tick"),
             knob("solver", ph + "solver", solvers, default_solver, "the contact solver")]
    if isinstance(scene.get("lod"), dict):
        knobs.append(knob("physics lod period", "lod.physics_every", [1, 2, 4], 1,
                          "ticks between steps of islands no player is near"))
    return knobs


# The reference that arrival_drift is measured against: the level of detail off (lod.enabled,
# docs/scene-format.md), every NPC every tick with its neighbour terms. On
# scenes/courtyard_flow_lod.yaml it ends bitwise equal to the scene without its lod section.
CROWD_FULL_DETAIL = {"lod.enabled": False}


def crowd_knobs(scene):
    """The crowd level of detail's knobs (docs/scene-format.md, `lod`) of a scene with flow-field
    populations and a `lod` section, judged by AI time against arrival drift; values most
    accurate first. The bands are scaled to the world: the first puts every NPC within the near
    band of a player or observer. The last knob switches the whole section off (`lod.enabled`;
    with it the physics level of detail, which a scene tuned for its crowd should then check)."""
    world = scene.get("world", {}) or {}
    lo, hi = world.get("min", [0, 0, 0]), world.get("max", [0, 0, 0])
    side = float(max(hi[0] - lo[0], hi[2] - lo[2]))
    diagonal = float(math.ceil(math.hypot(hi[0] - lo[0], hi[2] - lo[2])))

    def knob(name, keys, values, own, why):
        values = [v if isinstance(v, tuple) else (v,) for v in values]
        return Knob(name, keys, values, own, why, cost="ai_ms", accuracy="arrival_drift")

    own_bands = (float(get(scene, "lod.near_radius", 40)), float(get(scene, "lod.far_radius", 120)))
    bands = [(diagonal, diagonal)] + sorted({(side / 2, side), (side / 4, side / 2), (side / 8, side / 4),
                                             own_bands}, reverse=True)
    # Periods and steering first, the bands last: with the bands at full detail first, every NPC
    # would be near and the later knobs would change nothing.
    return [knob("lod far period", ("lod.far_every",), [1, 2, 4, 8, 16], (int(get(scene, "lod.far_every", 8)),),
                 "ticks between steps of the far band"),
            knob("lod mid period", ("lod.mid_every",), [1, 2, 4, 8], (int(get(scene, "lod.mid_every", 2)),),
                 "ticks between steps of the middle band"),
            knob("lod far steers", ("lod.far_steers",), [True, False], (bool(get(scene, "lod.far_steers", False)),),
                 "the far band keeps its neighbour terms"),
            knob("lod crowded count", ("lod.crowded_count",), [2, 4, 8, 16, 0],
                 (int(get(scene, "lod.crowded_count", 0)),),
                 "NPCs in a cell that bring it to full detail (0: off)"),
            knob("lod bands m", ("lod.near_radius", "lod.far_radius"), bands, own_bands,
                 "near and far radius around players and observers"),
            # Last: whether the level of detail, as the knobs before left it, pays for its own
            # planning (each NPC's band, each tick) at all.
            knob("lod on", ("lod.enabled",), [False, True], (bool(get(scene, "lod.enabled", True)),),
                 "the crowd level of detail at all (false: every NPC every tick)")]


def path_knobs(scene):
    """The agents' path planner's knobs (docs/scene-format.md, `map.navigation` and
    `agents.paths`), judged by AI time (planning and following the paths: a grid path is
    followed along a spline, a navmesh path along its segments, and the planner's own time is
    the smaller part) against path overhead; values most accurate first. The planner is set with the key the scene names it by (`agents.paths.planner`,
    the older spelling, takes no navmesh); landmarks with a navmesh are refused by the loader, so
    such a run fails and is skipped; the HPA* cluster size only where the scene plans with HPA*."""
    def knob(name, keys, values, own, why):
        return Knob(name, keys, [(v,) for v in values], (own,), why, cost="ai_ms", accuracy="path_overhead")

    if get(scene, "agents.paths.planner", None) is not None:
        planner = knob("planner", ("agents.paths.planner",), ["astar", "jps", "hpa"],
                       get(scene, "agents.paths.planner", "astar"), "the path planner (agents.paths.planner)")
    else:
        planner = knob("planner", ("map.navigation",), ["grid", "jps", "hpa", "navmesh"],
                       get(scene, "map.navigation", "grid"), "the path planner (map.navigation)")
    knobs = [planner,
             knob("landmarks", ("agents.paths.landmarks",), [0, 4, 8, 16], int(get(scene, "agents.paths.landmarks", 0)),
                  "landmark cells that sharpen the grid planners' estimate")]
    if planner.scene_value[0] == "hpa":
        knobs.append(knob("hpa cluster size", ("agents.paths.cluster_size",), [8, 16, 32],
                          int(get(scene, "agents.paths.cluster_size", 16)), "the side of HPA*'s clusters, cells"))
    return knobs


def gpu_knob(scene):
    """Where the scene's flocks step (docs/scene-format.md, `gpu`), judged by AI time (the flocks
    step in the AI phase) against gpu_error: how far the device's float run ends from the CPU's
    double one. Most accurate first; the scene's own (absent: auto) is added after, measured
    but never chosen: auto and probe decide by timing both paths at start-up, so they end as
    off or as on depending on the load."""
    return Knob("gpu", ("gpu.mode",), [("off",), ("on",)], (get(scene, "gpu.mode", "auto"),),
                "where flocks step: the CPU (double) or the OpenCL device (float)", cost="ai_ms",
                accuracy="gpu_error", unsettled=(("auto",), ("probe",)))


# The reference that gpu_error is measured against: every workload on the CPU, in double.
GPU_REFERENCE = {"gpu.mode": "off"}


def reference_settings(knobs):
    """The dotted-key settings of the reference run: every physics knob at its most accurate
    value, so that the tuner measures stack_drift against the best the engine does; where
    crowd knobs are turned, the crowd level of detail off (CROWD_FULL_DETAIL); where the gpu
    knob is, everything on the CPU (GPU_REFERENCE)."""
    settings = {key: v for k in knobs if k.accuracy == "stack_drift" for key, v in zip(k.keys, k.values[0])}
    if any(k.accuracy == "arrival_drift" for k in knobs):
        settings.update(CROWD_FULL_DETAIL)
    if any(k.accuracy == "gpu_error" for k in knobs):
        settings.update(GPU_REFERENCE)
    return settings


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
