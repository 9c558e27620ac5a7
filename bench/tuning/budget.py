"""A budget: error and cost limits in user terms, each checked against one run's figures.

Written on the command line as NAME<=VALUE pairs, comma-separated, e.g.
    shown_error_p99<=0.25,kbps_per_client<=120
"""
from dataclasses import dataclass

# What a run measures (tuning/measure.py), with its unit and what it means.
METRICS = {
    "shown_error_p99": ("m", "p99 distance between where clients showed sampled entities and where "
                             "the zones had them (deploy/truth_error.py)"),
    "kbps_per_client": ("kbit/s", "mean download per player"),
    "tick_ms_p99": ("ms", "slowest zone's p99 tick time"),
    "stack_drift": ("m", "the largest distance any body resting at the end of the reference run "
                         "(the physics knobs at their most accurate) ends from where that run ends it"),
    "physics_ms": ("ms", "mean physics phase time per tick, summed over the zone ranks"),
    "arrival_drift": ("s", "p99 over the flow-field NPCs of how much earlier or later each reaches its "
                           "destination than in the reference run (the crowd level of detail at full "
                           "detail everywhere)"),
    "arrival_drift_mean": ("s", "the same, the mean over the NPCs"),
    "ai_ms": ("ms", "mean AI phase time per tick (crowds, their level of detail, agents, planners), "
                    "summed over the zone ranks"),
    "path_overhead": ("", "the largest length over the A* optimum, minus 1, of any path the agents' planner "
                          "planned (agents.paths.audit; 0.01: 1 % longer)"),
    "path_overhead_mean": ("", "the same, the mean over the planned paths"),
    "planner_ms": ("ms", "mean time in the path planner per tick (the audit left out), summed over the zone ranks"),
    "gpu_error": ("m", "the largest distance between where a run ends an entity and where the same settings "
                       "on the CPU reference (gpu.mode off: double) end it, over every entity (runs of the "
                       "zones alone: the particles' and flocks' float error, grown over the run)"),
}

# The metrics that only a scene with rigid bodies measures (tuning/measure.py's reference run).
PHYSICS_METRICS = ("stack_drift",)
# The metrics of a scene's flow-field crowds, measured on runs of the zones alone (no players:
# the crowd's level of detail then follows the scene's lod.observers), against a reference run.
CROWD_METRICS = ("arrival_drift", "arrival_drift_mean")
# The metrics of the agents' path planner, measured on runs of the zones alone with
# agents.paths.audit on.
PATH_METRICS = ("path_overhead", "path_overhead_mean")
# The metric of the device's float arithmetic, measured on runs of the zones alone against a
# reference run on the CPU.
GPU_METRICS = ("gpu_error",)
# The metrics that need players (a gateway and a fleet), which zone-only runs do not measure.
PLAYER_METRICS = ("shown_error_p99", "kbps_per_client")


class BudgetError(ValueError):
    pass


@dataclass(frozen=True)
class Limit:
    metric: str
    most: float

    def met(self, figures):
        return figures[self.metric] <= self.most

    def slack(self, figures):
        """How much of the limit is left (1: all of it, 0: right at it, below 0: broken)."""
        return 1.0 - figures[self.metric] / self.most if self.most > 0 else -figures[self.metric]

    def describe(self):
        unit = METRICS[self.metric][0]
        return f"{self.metric} <= {self.most:g}" + (f" {unit}" if unit else "")


def parse(text):
    """The limits of 'a<=1,b<=2'; '=' is taken as '<='. Raises BudgetError naming the bad part."""
    limits = []
    for part in filter(None, (p.strip() for p in text.split(","))):
        name, sep, value = part.replace("<=", "=").partition("=")
        name = name.strip()
        if not sep:
            raise BudgetError(f"budget '{part}': expected NAME<=VALUE")
        if name not in METRICS:
            raise BudgetError(f"budget '{part}': unknown limit '{name}' (known: {', '.join(METRICS)})")
        try:
            most = float(value)
        except ValueError:
            raise BudgetError(f"budget '{part}': '{value.strip()}' is not a number") from None
        if not most >= 0 or most == float("inf"):
            raise BudgetError(f"budget '{part}': the limit must be a finite number >= 0")
        if any(l.metric == name for l in limits):
            raise BudgetError(f"budget '{part}': {name} is limited twice")
        limits.append(Limit(name, most))
    if not limits:
        raise BudgetError("the budget is empty: give at least one NAME<=VALUE")
    return limits


def broken(limits, figures):
    """The limits these figures break."""
    return [l for l in limits if not l.met(figures)]


def binding(limits, figures):
    """The limit with the least slack left."""
    return min(limits, key=lambda l: l.slack(figures))
