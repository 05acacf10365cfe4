#!/usr/bin/env bash
# Reproduces the tables of docs/BENCHMARKS.md. Usage:
#   scripts/benchmarks.sh [chapter|fleet|avoidance|crowd|density|movingai|ros|barn|safety|all]
#   scripts/benchmarks.sh [plan-movingai|plan-barn|plan-floors|plan-fleets|plan]   (the planning layer and DWA)
# Needs ./build (scripts/quickstart.sh); the maps and benchmark data are in data/maps.
set -euo pipefail
cd "$(dirname "$0")/.."
fn=build/floornav
maps=data/maps
out=${FLOORNAV_BENCH_OUT:-out/benchmarks}
what=${1:-all}
kinds=(hybrid hard_switch blended go_to_goal)

row() {  # label aggregate.json
  python3 - "$1" "$2" <<'PY'
import json, sys
a = json.load(open(sys.argv[2]))
f = lambda v, d=3: "–" if v is None else f"{v:.{d}f}"
print(f"| {sys.argv[1]} | {a['runs']} | {f(a['success_rate'])} | {f(a['collision_rate'])} | "
      f"{f(a['timeout_rate'])} | {f(a['stuck_rate'])} | {f(a['mean_time_reached'], 1)} | "
      f"{f(a.get('mean_path_efficiency_reached'))} | {f(a.get('mean_score'))} |")
PY
}
header() {
  echo "| case | runs | success | collision | timeout | stuck | mean time (s) | path efficiency | BARN score |"
  echo "|---|---|---|---|---|---|---|---|---|"
}
kind_rows() {  # name label-prefix batch-arguments...: a batch and a row per controller kind
  local name=$1 prefix=$2 k
  shift 2
  for k in "${kinds[@]}"; do
    $fn batch "$@" --set controller.kind=$k --no-timing --out "$out/$name-$k" >/dev/null
    row "$prefix$k" "$out/$name-$k/aggregate.json"
  done
}
avoidance_rows() {  # name rows-function batch-arguments...: a batch and rows per robot_avoidance
  local name=$1 rows=$2 a
  shift 2
  for a in none orca; do
    $fn batch "$@" --set controller.robot_avoidance=$a --no-timing --out "$out/$name-$a" >/dev/null
    $rows "$a" "$out/$name-$a/results.jsonl"
  done
}
barn_worlds() {  # sets $worlds: BARN's worlds, unpacked on first use
  worlds=${BARN_WORLDS:-/tmp/floornav-barn-worlds}
  if [[ ! -f $worlds/world_299.world ]]; then
    mkdir -p "$worlds" && tar -xJf "$maps/barn/BARN_world_files.tar.xz" -C "$worlds"
  fi
}

if [[ $what == chapter || $what == all ]]; then
  echo "### Chapter scenarios (scenarios/*.yaml, without the templates and fleets)"; header
  kind_rows chapter "" $(ls scenarios/*.yaml | grep -v -e template -e fleet_)
fi
if [[ $what == fleet || $what == all ]]; then
  echo "### Fleets (scenarios/fleet_*.yaml: robots that sense each other)"
  echo "| scenario | controller | robots | reached | collided | robot-robot collisions | deliveries | time (s) | min clearance (m) |"
  echo "|---|---|---|---|---|---|---|---|---|"
  for k in "${kinds[@]}"; do
    $fn batch scenarios/fleet_*.yaml --set controller.kind=$k --no-timing --out "$out/fleet-$k" >/dev/null
    python3 - "$k" "$out/fleet-$k/results.jsonl" <<'PY'
import json, sys
for line in open(sys.argv[2]):
    r = json.loads(line); f = r["fleet"]
    print(f"| {r['scenario']} | {sys.argv[1]} | {f['robots']} | {f['reached']} | {f['collided']} | "
          f"{f['robot_collisions']} | {f['deliveries']}/{f['delivery_count']} | {r['sim_time']:.1f} | "
          f"{r['min_clearance']:.3f} |")
PY
  done
fi
fleet_rows() {  # label results.jsonl
  python3 - "$1" "$2" <<'PY'
import json, sys
for line in open(sys.argv[2]):
    r = json.loads(line); f = r["fleet"]; c = r.get("crowd")
    crowd = (f" {c['person_contacts']} | {c['forklift_contacts']} | {c['intrusions']} | "
             f"{c['min_person_gap']:.3f} | {f['wait_time']:.0f} | {c['people_blocked_time']:.0f} |"
             if c else "")
    print(f"| {r['scenario']} | {sys.argv[1]} | {f['robots']} | {f['reached']} | "
          f"{f['robot_collisions']} | {f['world_collisions']} | {f['deliveries']}/{f['delivery_count']} | "
          f"{r['sim_time']:.1f} | {r['min_clearance']:.3f} |{crowd}")
PY
}
variants_row() {  # label results.jsonl
  python3 - "$1" "$2" <<'PY'
import json, sys
rs = [json.loads(l) for l in open(sys.argv[2])]
d = sum(r["fleet"]["deliveries"] for r in rs); n = sum(r["fleet"]["delivery_count"] for r in rs)
rr = sum(r["fleet"]["robot_collisions"] for r in rs); w = sum(r["fleet"]["world_collisions"] for r in rs)
full = sum(r["fleet"]["deliveries"] == r["fleet"]["delivery_count"] for r in rs)
c = [r["crowd"] for r in rs if "crowd" in r]
people = (f" {sum(x['person_contacts'] for x in c)} | {sum(x['forklift_contacts'] for x in c)} |"
          if c else "")
print(f"| {sys.argv[1]} | {len(rs)} | {full} | {d}/{n} ({100 * d / n:.1f} %) | {rr} | {w} |{people}")
PY
}
if [[ $what == avoidance || $what == all ]]; then
  echo "### Robot avoidance (hybrid; scenarios/fleet_*.yaml)"
  echo "| scenario | robot_avoidance | robots | reached | robot-robot collisions | world collisions | deliveries | time (s) | min clearance (m) |"
  echo "|---|---|---|---|---|---|---|---|---|"
  avoidance_rows avoid fleet_rows scenarios/fleet_*.yaml
  echo "### Generated warehouses (scripts/fleet_variants.py warehouse, seeds 1-10)"
  echo "| robot_avoidance | floors | all deliveries | deliveries | robot-robot collisions | world collisions |"
  echo "|---|---|---|---|---|---|"
  python3 scripts/fleet_variants.py warehouse "$out/warehouses"
  avoidance_rows warehouses variants_row "$out"/warehouses/*.yaml
fi
if [[ $what == crowd || $what == all ]]; then
  echo "### People and forklifts (scenarios/crowd/*.yaml)"
  echo "| scenario | robot_avoidance | robots | reached | robot-robot collisions | world collisions | deliveries | time (s) | min clearance (m) | person contacts | forklift contacts | intrusions | min person gap (m) | robot wait (s) | people blocked (s) |"
  echo "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|"
  avoidance_rows crowd fleet_rows scenarios/crowd/*.yaml
  echo "### Generated factory floors (scripts/fleet_variants.py factory, seeds 1-10)"
  echo "| robot_avoidance | floors | all deliveries | deliveries | robot-robot collisions | world collisions | person contacts | forklift contacts |"
  echo "|---|---|---|---|---|---|---|---|"
  python3 scripts/fleet_variants.py factory "$out/factories"
  avoidance_rows factories variants_row "$out"/factories/*.yaml
fi
if [[ $what == density || $what == all ]]; then
  # factory-people's floor and robots with walkers at 0.1 to 0.5 people per m² of free floor,
  # ten crowds (seeds) each (scenarios/factory_density_template.yaml).
  echo "### People density (scenarios/factory_density_template.yaml, seeds 1-10)"
  echo "| density (people/m²) | people | runs | deliveries | all delivered | stuck robots | robot-person contacts | other contacts | intrusions per robot-minute | intrusion time share | path irregularity (rad) | time not moving share | min person gap (m) |"
  echo "|---|---|---|---|---|---|---|---|---|---|---|---|---|"
  # The first row: the same floor without people (the robots draw nothing from the seed: one run).
  mkdir -p "$out"
  grep -v -e '^random_people:' -e '^  density:' scenarios/factory_density_template.yaml \
    > "$out/factory_no_people.yaml"
  $fn batch "$out/factory_no_people.yaml" --no-timing --out "$out/density-none" >/dev/null
  $fn sweep scenarios/factory_density_template.yaml --grid random_people.density=0.1,0.2,0.3,0.4,0.5 \
    --grid sim.seed=1:10:10 --no-timing --out "$out/density" >/dev/null
  python3 - "$out/density-none/results.jsonl" "$out/density/results.jsonl" <<'PY'
import json, sys
rows = {}
for line in open(sys.argv[1]).readlines() + open(sys.argv[2]).readlines():
    r = json.loads(line)
    rows.setdefault(r.get("swept", {}).get("random_people.density", 0), []).append(r)
for density, rs in sorted(rows.items()):
    f = [r["fleet"] for r in rs]; c = [r["crowd"] for r in rs]
    dt = rs[0]["config"]["sim"]["dt"]
    driving = sum(x["robot_steps"] for x in f) * dt             # s robots ran (before finishing)
    on_floor = sum(x["robots"] * r["sim_time"] for x, r in zip(f, rs))  # s robots were on the floor
    steps = sum(x["robot_steps"] for x in f)
    irregular = sum(x["path_irregularity"] * x["robot_steps"] for x in f) / steps
    d = sum(x["deliveries"] for x in f); n = sum(x["delivery_count"] for x in f)
    other = sum(x["forklift_contacts"] for x in c) + sum(x["robot_collisions"] + x["world_collisions"] for x in f)
    gaps = [x["min_person_gap"] for x in c if x["min_person_gap"] is not None]
    gap = f"{min(gaps):.3f}" if gaps else "–"
    print(f"| {density:g} | {c[0]['people']} | {len(rs)} | {d}/{n} ({100 * d / n:.1f} %) | "
          f"{sum(x['deliveries'] == x['delivery_count'] for x in f)} | {sum(x['stuck'] for x in f)} | "
          f"{sum(x['person_contacts'] for x in c)} | {other} | "
          f"{sum(x['intrusions'] for x in c) / (on_floor / 60):.2f} | "
          f"{sum(x['intrusion_time'] for x in c) / on_floor:.3f} | {irregular:.3f} | "
          f"{sum(x['wait_time'] for x in f) / driving:.3f} | {gap} |")
PY
fi
# The chapter's kinds alone (controller.preset=chapter) on MovingAI and BARN: the templates ship
# the factory preset, measured in the planning layer's tables below.
if [[ $what == movingai || $what == all ]]; then
  echo "### MovingAI (TurtleBot3 Burger, 1 m cells, first 100 rows of random-1)"; header
  for m in room-32-32-4 warehouse-10-20-10-2-1; do
    kind_rows "$m" "$m " scenarios/movingai_template.yaml --set controller.preset=chapter \
      --scen "$maps/movingai-mapf/$m-random-1.scen" --cell-size 1 --limit 100
  done
fi
if [[ $what == ros || $what == all ]]; then
  echo "### ROS map_server maps (scenarios/ros/*.yaml)"; header
  kind_rows ros "" scenarios/ros/*.yaml
fi
if [[ $what == barn || $what == all ]]; then
  barn_worlds
  echo "### BARN, 300 worlds (Jackal; success within 1 m, no collision, 100 s)"; header
  $fn batch scenarios/barn_template.yaml --worlds "$worlds" --barn-paths "$maps/barn/path_files" \
    --set controller.preset=chapter --no-timing --out "$out/barn" >/dev/null
  row "hybrid (floornav, the template's chapter keys)" "$out/barn/aggregate.json"
  python3 - "$maps/barn/dwa_out.txt" <<'PY'
import sys
rows = [l.split() for l in open(sys.argv[1]) if l.strip()]
n = len(rows); s = sum(int(r[1]) for r in rows); c = sum(int(r[2]) for r in rows); t = sum(int(r[3]) for r in rows)
print(f"| DWA baseline (dwa_out.txt, 50 worlds x 10) | {n} | {s/n:.3f} | {c/n:.3f} | {t/n:.3f} | – | "
      f"{sum(float(r[4]) for r in rows if r[1]=='1')/max(s,1):.1f} | – | 0.169 (published) |")
PY
fi

# --- The planning layer (docs/BENCHMARKS.md#planning-layer): the chapter alone, the planner
# stack and DWA on the same worlds. Rows: hybrid (the chapter), hybrid + astar, dwa, dwa + astar.
# The templates ship `controller.preset: factory` (A* planner stack, safety layer, ORCA); the
# chapter's automaton alone is `controller.preset=chapter`.
plan_rows=("chapter|--set controller.preset=chapter"
           "factory|"
           "factory+rrt_connect|--set controller.planner.kind=rrt_connect"
           "dwa|--set controller.kind=dwa --set controller.planner.kind=none"
           "dwa+astar|--set controller.kind=dwa")
if [[ $what == safety || $what == all ]]; then
  echo "### The chapter's seven scenes at eight cruise speeds (v0 = 0.05 to 0.3 m/s), as shipped"
  echo "| scene | runs | reached | collided | timeout | stuck |"
  echo "|---|---|---|---|---|---|"
  for f in circle_obstacle concave_obstacle convex_obstacle point_obstacle practice2_pillars \
    rectangle week7_pocket; do
    $fn sweep scenarios/$f.yaml --grid controller.v0=0.05:0.3:8 --no-timing \
      --out "$out/speeds-$f" >/dev/null
    python3 - "$f" "$out/speeds-$f/aggregate.json" <<'PY'
import json, sys
a = json.load(open(sys.argv[2]))
n = a["runs"]
c = lambda k: round(a[k] * n)
print(f"| {sys.argv[1]} | {n} | {a['reached']} | {c('collision_rate')} | {c('timeout_rate')} | "
      f"{c('stuck_rate')} |")
PY
  done
  echo "### RVO2's Circle with QuickBots (scenarios/circle/circle_N.yaml, as written)"
  echo "| robots | reached | contacts | all home at (s) | min clearance (m) |"
  echo "|---|---|---|---|---|"
  for n in 20 100 300 1000; do
    $fn run scenarios/circle/circle_$n.yaml --no-html -q --out "$out/circle-$n"
    python3 - "$out/circle-$n/summary.json" <<'PY'
import json, sys
s = json.load(open(sys.argv[1]))
f = s["fleet"]
print(f"| {f['robots']} | {f['reached']} | {len(s['collisions'])} | {s['sim_time']:.1f} | "
      f"{s['min_clearance']:.3f} |")
PY
  done
  echo "### Generated shared floors (scenarios/shared_floor_template.yaml, floors 1-1000)"
  $fn batch scenarios/shared_floor_template.yaml --shared-floors 1000 --no-timing \
    --out "$out/shared-floors" >/dev/null
  python3 - "$out/shared-floors/results.jsonl" <<'PY'
import json, sys
floors = robots = reached = contacts = deliveries = asked = 0
for line in open(sys.argv[1]):
    d = json.loads(line)
    f = d["fleet"]
    floors += 1
    robots += f["robots"]
    reached += f["reached"]
    deliveries += f["deliveries"]
    asked += f["delivery_count"]
    contacts += len(d["collisions"])
print("| floors | robots | robots that delivered everything | deliveries | contacts |")
print("|---|---|---|---|---|")
print(f"| {floors} | {robots} | {reached} ({100 * reached / robots:.2f} %) | {deliveries} / {asked} "
      f"| {contacts} |")
PY
fi
if [[ $what == plan-movingai || $what == plan ]]; then
  # Held out: random-3, first 50 rows of every map (rooms, warehouses, game maps); t_max 4000 s so
  # that no run is cut before twice its optimal time. "within 2x" = reached without collision
  # within 2 x octile optimum / 0.22 m/s (the Burger's top speed).
  echo "### MovingAI, 9 maps x 50 rows of random-3 (TurtleBot3 Burger, 1 m cells, known map)"
  echo "| case | runs | within 2x optimal time | success | collision | timeout | stuck | mean time (s) |"
  echo "|---|---|---|---|---|---|---|---|"
  for row in "${plan_rows[@]}"; do
    label=${row%%|*}; sets=${row#*|}
    for m in room-32-32-4 room-64-64-8 room-64-64-16 warehouse-10-20-10-2-1 warehouse-10-20-10-2-2 \
             warehouse-20-40-10-2-1 warehouse-20-40-10-2-2 den312d den520d; do
      $fn batch scenarios/movingai_template.yaml --scen "$maps/movingai-mapf/$m-random-3.scen" \
        --cell-size 1 --limit 50 --set sim.t_max=4000 $sets --no-timing \
        --out "$out/plan-movingai-$label/$m" >/dev/null
    done
    python3 - "$label" "$out/plan-movingai-$label" <<'PY'
import glob, json, sys
rs = [json.loads(l) for f in sorted(glob.glob(sys.argv[2] + "/*/results.jsonl")) for l in open(f)]
n = len(rs); rate = lambda s: sum(r["status"] == s for r in rs) / n
ok = sum(r["status"] == "reached" and r["sim_time"] <= 2 * r["optimal_length"] / 0.22 for r in rs)
t = [r["sim_time"] for r in rs if r["status"] == "reached"]
print(f"| {sys.argv[1]} | {n} | {ok / n:.3f} ({ok}) | {rate('reached'):.3f} | {rate('collision'):.3f} | "
      f"{rate('timeout'):.3f} | {rate('stuck'):.3f} | {sum(t) / max(len(t), 1):.1f} |")
PY
  done
fi
if [[ $what == plan-barn || $what == plan ]]; then
  barn_worlds
  echo "### BARN, 300 worlds, mapless (lidar only; the planner on its rolling grid)"; header
  # The template (the factory row) has the planner's footprint guard (guard_horizon 0.5 s, chosen
  # on every third world: 0, 3, ..., 297; the split is printed after the rows); the last row is
  # without it.
  for row in "${plan_rows[@]}" "factory-guard|--set controller.planner.guard_horizon=0"; do
    label=${row%%|*}; sets=${row#*|}
    start=$(date +%s.%N)
    $fn batch scenarios/barn_template.yaml --worlds "$worlds" --barn-paths "$maps/barn/path_files" \
      $sets --no-timing --out "$out/plan-barn-$label" >/dev/null
    echo "$label: $(python3 -c "import sys; print(f'{float(sys.argv[2]) - float(sys.argv[1]):.1f}')" "$start" "$(date +%s.%N)") s wall" >&2
    row "$label" "$out/plan-barn-$label/aggregate.json"
  done
  python3 - "$out/plan-barn-factory/results.jsonl" <<'PY'
import json, sys
rs = [json.loads(l) for l in open(sys.argv[1])]
world = lambda r: int(r["scenario"].rsplit("_", 1)[1])
for label, keep in (("... every third world (tuning)", lambda w: w % 3 == 0),
                    ("... the other 200 (held out)", lambda w: w % 3 != 0)):
    sel = [r for r in rs if keep(world(r))]; n = len(sel)
    rate = lambda s: sum(r["status"] == s for r in sel) / n
    print(f"| {label} | {n} | {rate('reached'):.3f} | {rate('collision'):.3f} | {rate('timeout'):.3f} | "
          f"{rate('stuck'):.3f} | | | {sum(r.get('score') or 0 for r in sel) / n:.3f} |")
PY
fi
if [[ $what == plan-floors || $what == plan ]]; then
  # Held out: floors 1001-1200 (the planner was tried on floors 1-200).
  echo "### Generated factory floors: 200 floors (seeds 1001-1200), QuickBot with 5 IR, a tour of 4 goals each"; header
  for row in "${plan_rows[@]}" "factory+memory|--set controller.planner.memory_range=0.2"; do
    label=${row%%|*}; sets=${row#*|}
    $fn batch scenarios/floor_template.yaml --floors 200 --floor-seed 1001 $sets --no-timing \
      --no-optimum --out "$out/plan-floors-$label" >/dev/null
    row "$label" "$out/plan-floors-$label/aggregate.json"
  done
fi
if [[ $what == plan-fleets || $what == plan ]]; then
  # The fleet and crowd files as they are (their own robot_avoidance), each row's controller.
  echo "### Fleets, people and forklifts (scenarios/fleet_*.yaml, scenarios/crowd/*.yaml)"
  echo "| scenario | case | robots | reached | robot-robot collisions | world collisions | deliveries | time (s) | min clearance (m) | person contacts | forklift contacts | intrusions | min person gap (m) | robot wait (s) | people blocked (s) |"
  echo "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|"
  for row in "${plan_rows[@]}"; do
    label=${row%%|*}; sets=${row#*|}
    $fn batch scenarios/fleet_*.yaml scenarios/crowd/*.yaml $sets --no-timing \
      --out "$out/plan-fleets-$label" >/dev/null
    fleet_rows "$label" "$out/plan-fleets-$label/results.jsonl"
  done
fi
