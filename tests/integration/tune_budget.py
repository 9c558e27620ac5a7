"""bench/tuning's budget and knobs without running anything: the parser knows the physics
limits (stack_drift, physics_ms) beside the wire's and refuses what is malformed, naming the
part; a scene with rigid bodies gets the solver's knobs (and the physics level of detail only
where it has a `lod` section), judged by physics time against stack drift, with a reference
at the most accurate values; choose() picks the cheapest physics value that meets the budget
and names the limit that stopped a cheaper one. Figures here are hand-made inputs to the
choice, not measurements."""
import importlib.util
import sys

import harness as h

sys.path.insert(0, str(h.SOURCE_DIR / "bench"))
from tuning import budget, knobs  # noqa: E402

limits = budget.parse("stack_drift<=0.01, physics_ms<=2,shown_error_p99<=0.3")
h.check([(l.metric, l.most) for l in limits] == [("stack_drift", 0.01), ("physics_ms", 2.0),
                                                 ("shown_error_p99", 0.3)],
        f"the parser reads the physics limits beside the wire's: {limits}")
h.check(limits[0].describe() == "stack_drift <= 0.01 m" and limits[1].describe() == "physics_ms <= 2 ms",
        f"each limit is described with its unit: {[l.describe() for l in limits]}")
for text, words in (("stack_drift<=-1", "finite number >= 0"), ("stack_drift<=x", "'x' is not a number"),
                    ("stack_drift<=1,stack_drift<=2", "stack_drift is limited twice"),
                    ("stack_wobble<=1", "unknown limit 'stack_wobble' (known: shown_error_p99, kbps_per_client, "
                                        "tick_ms_p99, stack_drift, physics_ms)")):
    try:
        budget.parse(text)
        h.check(False, f"'{text}' is refused")
    except budget.BudgetError as e:
        h.check(words in str(e), f"'{text}' is refused naming the fault: {e}")

stacks = knobs.merged_scene(h.SOURCE_DIR / "scenes" / "stacks.yaml")
names = {k.name: k for k in knobs.knobs_for(stacks)}
physics = [n for n, k in names.items() if k.accuracy == "stack_drift"]
h.check(physics == ["velocity iterations", "substeps", "solver", "physics lod period"],
        f"the stacks scene (rigid bodies, a lod section) gets the physics knobs: {physics}")
h.check(all(names[n].cost == "physics_ms" for n in physics) and names["substeps"].scene_value == (1,),
        "physics knobs trade physics time, from the scene's own values")
h.check(knobs.reference_settings(knobs.physics_knobs(stacks)) ==
        {"physics.velocity_iterations": 40, "physics.substeps": 4, "physics.solver": "gauss_seidel",
         "lod.physics_every": 1}, "the reference run is every physics knob at its most accurate")
soft = {**stacks, "physics": {**stacks["physics"], "solver": "soft_step"}}
h.check(knobs.reference_settings(knobs.physics_knobs(soft))["physics.solver"] == "soft_step",
        "the reference keeps the scene's own solver kind")
no_lod = {k: v for k, v in stacks.items() if k != "lod"}
h.check("physics lod period" not in [k.name for k in knobs.knobs_for(no_lod)],
        "without a lod section the physics level of detail is not turned (it would switch on the crowds')")
npc_only = knobs.merged_scene(h.SOURCE_DIR / "scenes" / "skirmish.yaml")
h.check(not any(k.accuracy == "stack_drift" for k in knobs.knobs_for(npc_only)),
        "a scene without rigid bodies gets no physics knob")

spec = importlib.util.spec_from_file_location("tune", h.SOURCE_DIR / "bench" / "tune.py")
tune = importlib.util.module_from_spec(spec)
spec.loader.exec_module(tune)
k = names["substeps"]
k.sweep = [((4,), {"physics_ms": 2.0, "stack_drift": 0.001, "tick_ms_p99": 3}),
           ((2,), {"physics_ms": 1.0, "stack_drift": 0.004, "tick_ms_p99": 2}),
           ((1,), {"physics_ms": 0.5, "stack_drift": 0.05, "tick_ms_p99": 1})]
value, why = tune.choose(k, budget.parse("stack_drift<=0.01"), 0.25)
h.check(value == (2,) and "cheaper values broke stack_drift <= 0.01 m" in why,
        f"the cheapest value meeting the drift limit is chosen, the limit that stopped 1 named: {value} {why}")
k.sweep[0][1]["physics_ms"] = 1.1  # within the 25 % tie of 2 substeps: the more accurate wins
value, _ = tune.choose(k, budget.parse("stack_drift<=0.01"), 0.25)
h.check(value == (4,), f"physics times within the tie count as equal, the smaller drift wins: {value}")
print("tune_budget passed")
