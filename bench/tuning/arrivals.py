"""The crowd's error in user terms: when each flow-field NPC reaches its destination in a run
(zone_node --arrivals: `id,tick` lines) against when it does in the reference run, the crowd's
level of detail off (tuning/knobs.py's crowd reference)."""
import math
from pathlib import Path


class ArrivalsError(ValueError):
    pass


def read(path):
    """id -> arrival tick from a zone_node --arrivals file. Raises ArrivalsError naming the file
    and line of anything malformed, or of an id listed twice."""
    path = Path(path)
    lines = path.read_text().splitlines()
    if not lines or lines[0].strip() != "id,tick":
        raise ArrivalsError(f"{path}:1: expected the header 'id,tick'")
    ticks = {}
    for number, line in enumerate(lines[1:], start=2):
        parts = line.split(",")
        try:
            npc, tick = (int(p) for p in parts)
        except ValueError:
            raise ArrivalsError(f"{path}:{number}: expected 'id,tick' (two integers), got '{line}'") from None
        if npc in ticks:
            raise ArrivalsError(f"{path}:{number}: NPC {npc} is listed twice")
        ticks[npc] = tick
    return ticks


def drift(here, reference, ticks, dt):
    """How far arrival times (id -> tick, from read()) of a run of `ticks` ticks of `dt` seconds
    lie from the reference run's of the same length: per NPC that arrived in either, the
    difference in seconds; an NPC that arrived in only one of them arrives in the other at the
    run's end at the earliest, so it counts the time from its arrival to that end (a lower
    bound). Returns the p99, mean and max of those, the NPCs compared, and those that arrived
    in only one run."""
    if ticks < 1 or not dt > 0:
        raise ValueError(f"drift: a run of {ticks} ticks of {dt} s")
    late = [abs(here[i] - reference[i]) * dt for i in here.keys() & reference.keys()]
    only_here = [(ticks - here[i]) * dt for i in here.keys() - reference.keys()]
    only_reference = [(ticks - reference[i]) * dt for i in reference.keys() - here.keys()]
    gaps = sorted(late + only_here + only_reference)
    if not gaps:
        return {"arrival_drift": 0.0, "arrival_drift_mean": 0.0, "arrival_drift_max": 0.0,
                "arrivals_compared": 0, "arrived_here_only": 0, "arrived_reference_only": 0}
    p99 = gaps[min(len(gaps) - 1, max(0, math.ceil(0.99 * len(gaps)) - 1))]
    return {"arrival_drift": p99, "arrival_drift_mean": sum(gaps) / len(gaps),
            "arrival_drift_max": gaps[-1], "arrivals_compared": len(gaps),
            "arrived_here_only": len(only_here), "arrived_reference_only": len(only_reference)}
