"""Scenes end in the same state, bit for bit, on 1, 2 and 4 ranks: entity ids, initial states
and per-entity random streams do not depend on the decomposition, migration carries state
exactly, and (scenes/crowd.yaml) walkers that keep apart read their neighbours across zone
borders from ghosts that are bitwise the owners' state; (scenes/crowd_flock.yaml) flocking NPCs
do the same through the crowd library's Flock, whose sums run in a canonical order;
(scenes/courtyard_flow.yaml) a flow-field crowd on an obstacle map pushes apart across borders
through ghosts and decides arrivals from positions alone, and (scenes/courtyard_flow_bodies.yaml)
keeps its bodies apart from them, as do the flockers of (scenes/crowd_flock_bodies.yaml);
(scenes/courtyard_flow_lod.yaml) the same under level of detail, with crowded cells counted over agents and ghosts kept at full
detail; (scenes/courtyard_flow_navmesh.yaml) the same crowd aiming at the corners of funnelled
navigation-mesh paths, built alike on every rank, and (scenes/courtyard_formation_navmesh.yaml) a
formation whose centre walks the mesh path; (scenes/flock_lod.yaml) a flock with
a goal under level of detail, whose plan (from ids, positions, the tick and a scripted
observer) is the same on every rank;
(scenes/particles.yaml, --gpu off) fountains whose sprays cross zone borders end with the same
live particles (positions and velocities, bit for bit); (crowd_flock with --gpu on) the same
flock on the OpenCL device (gpu/planar_flock.h: float, but its sums also run in cell-then-id
order on global cells, so a rank's other agents change nothing); (scenes/agents.yaml) AI agents
that see wanderers across borders through ghosts and carry their machine states and plans with
them when they migrate; (scenes/agents_sliced.yaml) the same with time-sliced decisions, each
agent carrying what it last perceived; (scenes/agents_paths.yaml) couriers whose A* paths migrate with them
and are re-planned when a door closes; (scenes/agents_paths_budget.yaml) the same couriers under
a path budget that binds, shared by the cluster, with HPA* and its path cache;
(scenes/agents_jps.yaml) the couriers planned by jump point search with landmarks, whose table
every rank rebuilds alike after the door, and (scenes/agents_hpa.yaml) by HPA* with landmarks;
(scenes/agents_navmesh.yaml) the couriers on navigation-mesh paths, whose corners migrate with
them and whose mesh every rank rebuilds alike when the door closes;
(scenes/courtyard_formation.yaml) a formation whose centre every rank computes alike, whose
members carry their rejoin paths when they migrate and push apart through ghosts;
(scenes/courtyard_ants.yaml) ants that carry their routes across borders and lay trail on a grid
summed over the ranks in integers every tick; (scenes/courtyard_groups_lod.yaml) both under level
of detail, members and ants far from an observer stepping every 2 or 4 ticks; (scenes/roads.yaml) NPCs on a waypoint graph whose
next node and goal migrate with them, deciding at each node from the graph and its timed closure
alone; (scenes/skirmish.yaml) NPCs hitting each other where four zones meet, by messages to the
target's owner (the entity mail) that are forwarded when the target crosses a border in the
same tick: health, kills and knockback end bitwise equal only if every hit lands once, in the
same order, and unique items claimed by several in one tick go to the same claimant;
(scenes/duel_adaptive.yaml) duels against NPCs that adapt to the player, run by the zone that
holds each arena, whose rounds, wins and final NPCs (the zone summaries' `duels`) are the same
on every decomposition; (scenes/border_pile.yaml) 400 spheres piled where four zones meet,
whose contacts across borders are solved island by island, each island whole on the rank holding
its lowest id, with each body carrying its sleep and warm starts to whichever rank solves it;
(scenes/physics_objects.yaml) a pendulum, a hinged door and a dumbbell whose joints carry their
warm starts the same way, and cloths stepped on one rank with the bodies that may touch them."""
import json
import tempfile
from pathlib import Path

import harness as h

SCENES = {"test_npc_only": 300, "crowd": 300, "crowd_flock": 300, "courtyard_flow": 300,
          "courtyard_flow_lod": 300, "courtyard_flow_navmesh": 300,
          "courtyard_flow_bodies": 300, "crowd_flock_bodies": 300,
          "particles": 300, "crowd_flock_gpu": 300, "agents": 300, "agents_sliced": 300,
          "agents_paths": 600, "agents_paths_budget": 600, "agents_navmesh": 600, "agents_jps": 600,
          "agents_hpa": 600,
          "courtyard_formation": 700, "courtyard_formation_navmesh": 700, "courtyard_ants": 1200, "courtyard_groups_lod": 1200,
          "flock_lod": 300, "roads": 1200, "skirmish": 300,
          "duel_adaptive": 1200, "border_pile": 600, "border_pile_recycled": 600,
          "physics_objects": 600}
FILES = {"crowd_flock_gpu": "crowd_flock"}  # a case that runs another case's scene
EXTRA = {"particles": ["--gpu", "off"],  # double precision on the CPU: no float device rounding
         "crowd_flock": ["--gpu", "off"], "crowd_flock_gpu": ["--gpu", "on"],
         "flock_lod": ["--gpu", "off"]}
GHOST_SCENES = ("crowd", "crowd_flock", "crowd_flock_bodies", "courtyard_flow", "courtyard_flow_lod",
                "courtyard_flow_navmesh",
                "courtyard_flow_bodies", "crowd_flock_gpu", "agents", "agents_sliced",
                "courtyard_formation", "courtyard_formation_navmesh", "courtyard_groups_lod", "flock_lod", "skirmish")
MAIL_SCENES = ("skirmish",)  # entity messages: the same totals on every decomposition
MAIL_FIGURES = ("hits", "kills", "pickups", "pickups_contested", "pickups_denied", "mail_posted",
                "mail_applied", "mail_refused")
# No ghosts read: the ants' trails are summed instead; road NPCs decide from the graph alone.
MIGRATION_SCENES = ("courtyard_ants", "roads")

with tempfile.TemporaryDirectory(prefix="zs_decomp_") as tmp:
    out = Path(tmp)
    for scene, ticks in SCENES.items():
        dumps = {}
        ghosts_sent = {}
        migrated = {}
        mail = {}
        duels = {}  # ranks -> every zone's duels, by index
        islands = {}  # ranks -> bodies solved in another zone's islands, and physics steps
        for ranks in (1, 2, 4):
            dump = out / f"{scene}_{ranks}.jsonl"
            metrics = out / f"{scene}_{ranks}_metrics"
            h.run(h.mpirun(ranks, h.bin_dir() / "zone_node", "--scene",
                           h.SOURCE_DIR / f"scenes/{FILES.get(scene, scene)}.yaml", "--ticks",
                           ticks, "--no-dds",
                           "--dump-state", dump, "--metrics", metrics, *EXTRA.get(scene, [])),
                  out / f"{scene}_{ranks}.log", h.base_env(), timeout=300)
            dumps[ranks] = dump.read_text()
            summaries = [json.loads(p.read_text()) for p in metrics.glob("zone_*_summary.json")]
            if scene == "crowd_flock_gpu":
                backends = {z["flock_backend"] for z in summaries}
                h.check(backends == {"opencl"}, f"{scene}: flocks on OpenCL ({sorted(backends)})")
            duels[ranks] = sorted((d for z in summaries for d in z.get("duels", [])),
                                  key=lambda d: d["duel"])
            ghosts_sent[ranks] = sum(s.get("ghosts_sent", 0) for s in summaries)
            islands[ranks] = (sum(s.get("island_bodies_out", 0) for s in summaries),
                              min(s.get("physics_steps", 0) for s in summaries))
            migrated[ranks] = sum(s.get("migrated_out", 0) for s in summaries)
            mail[ranks] = {k: sum(s.get(k, 0) for s in summaries)
                           for k in MAIL_FIGURES + ("mail_cross_zone", "mail_forwarded",
                                                    "mail_failures")}
            if scene == "agents_paths_budget" and ranks == 4:
                waiting = {}  # tick -> zones with requests still waiting after it
                for p in metrics.glob("zone_*.jsonl"):
                    for row in map(json.loads, p.read_text().splitlines()):
                        if row.get("paths_queued", 0) > 0:
                            waiting[row["tick"]] = waiting.get(row["tick"], 0) + 1
                shared = sum(1 for n in waiting.values() if n >= 2)
                h.check(shared > 10, f"{scene}: requests waited in several zones at once in "
                        f"{shared} ticks (the budget is shared)")
        lines = dumps[1].count("\n")
        h.check(lines > 0, f"{scene}: the dump lists {lines} entities")
        if scene == "particles":
            rows = [json.loads(line) for line in dumps[1].splitlines()]
            emitters = [r["pos"] for r in rows if r["kind"] == "emitter"]
            particles = [r["pos"] for r in rows if r["kind"] == "particle"]
            h.check(len(particles) > 1000, f"{scene}: {len(particles)} live particles are in the dump")
            # On the scene's 2x2 grid (borders at x = 50 and z = 50): particles in another zone
            # than the emitter nearest to them, i.e. sprays that crossed a border.
            zone = lambda p: (p[0] >= 50, p[2] >= 50)
            nearest = lambda p: min(emitters, key=lambda e: (e[0] - p[0]) ** 2 + (e[2] - p[2]) ** 2)
            crossed = sum(zone(p) != zone(nearest(p)) for p in particles)
            h.check(crossed > len(particles) // 20,
                    f"{scene}: {crossed} of {len(particles)} particles are over a border from the "
                    "emitter nearest to them")
        h.check(dumps[1] == dumps[2], f"{scene}: 2 ranks end bitwise equal to 1 rank")
        h.check(dumps[1] == dumps[4], f"{scene}: 4 ranks end bitwise equal to 1 rank")
        if scene in GHOST_SCENES:
            h.check(ghosts_sent[2] > 0 and ghosts_sent[4] > 0,
                    f"{scene}: ghosts were exchanged ({ghosts_sent[2]} copies on 2 ranks, "
                    f"{ghosts_sent[4]} on 4)")
            h.check(migrated[4] > 0, f"{scene}: {migrated[4]} NPCs crossed borders on 4 ranks")
        if scene in MAIL_SCENES:
            same = {k: {r: mail[r][k] for r in mail} for k in MAIL_FIGURES}
            for k, by_ranks in same.items():
                h.check(len(set(by_ranks.values())) == 1, f"{scene}: {k} the same on 1, 2 and 4 "
                        f"ranks ({by_ranks})")
            h.check(mail[1]["hits"] > 1000 and mail[1]["kills"] > 100,
                    f"{scene}: {mail[1]['hits']} hits, {mail[1]['kills']} kills")
            h.check(mail[1]["pickups"] > 0 and mail[1]["pickups_contested"] > 0,
                    f"{scene}: {mail[1]['pickups']} items taken, {mail[1]['pickups_contested']} of "
                    f"them contested ({mail[1]['pickups_denied']} claims denied), alike everywhere")
            h.check(mail[4]["mail_cross_zone"] > 100 and mail[4]["mail_forwarded"] > 0,
                    f"{scene}: on 4 ranks {mail[4]['mail_cross_zone']} messages crossed a border,"
                    f" {mail[4]['mail_forwarded']} followed a target that crossed in that tick")
            h.check(all(m["mail_failures"] == 0 for m in mail.values()),
                    f"{scene}: every audit of the mail balanced")
        if scene == "border_pile":
            h.check(islands[2][0] > 1000 and islands[4][0] > 1000,
                    f"{scene}: bodies were solved in other zones' islands ({islands[2][0]} times "
                    f"on 2 ranks, {islands[4][0]} on 4)")
            h.check(islands[4][1] < ticks, f"{scene}: on 4 ranks a zone slept whole while others "
                    f"stepped (it stepped {islands[4][1]} of {ticks} ticks): sleep and the warm "
                    "starts of sleeping islands carried across borders")
        if scene == "duel_adaptive":
            h.check(len(duels[1]) == 10 and all(d["rounds"] > 50 for d in duels[1]),
                    f"{scene}: 10 duels played {[d['rounds'] for d in duels[1]]} rounds")
            h.check(duels[1] == duels[2] == duels[4],
                    f"{scene}: every duel's rounds, wins and final NPC the same on 1, 2 and 4 ranks")
        if scene in MIGRATION_SCENES:
            h.check(migrated[4] > 0, f"{scene}: {migrated[4]} NPCs crossed borders on 4 ranks")
print("decomposition invariance passed")
