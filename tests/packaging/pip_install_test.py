#!/usr/bin/env python3
"""`pip install --no-build-isolation .` into a fresh virtual environment, then a scenario run
from outside the repository with the installed package.

    pip_install_test.py REPO_ROOT [CMAKE_BUILD_DIR]

A venv made by Debian's /usr/bin/python3 with --system-site-packages (numpy and setuptools from
Debian), pip offline (--no-index: nothing is downloaded), the repository installed as a wheel
built by its setup.py (CMake). With CMAKE_BUILD_DIR (ctest passes its own build folder), the
extension comes from that build (FLOORNAV_CMAKE_BUILD_DIR; it is already built, so the test takes
seconds); without it the extension is built from scratch in the repository's build-pip/.
Then, in a temporary folder with no PYTHONPATH: `import floornav` must come from the venv's
site-packages, and a scenario of the repository must run to its expected outcome and write
its files (run.mcap too) there; with a build that has OMPL, a fleet must plan with rrt_connect
(the planner's module is loaded from beside the installed extension).
"""
import json
import os
import subprocess
import sys
import tempfile
from pathlib import Path


def main() -> int:
    repo = Path(sys.argv[1]).resolve()
    build = Path(sys.argv[2]).resolve() if len(sys.argv) > 2 else None
    # A build with OMPL has the rrt_connect planner: the installed package must have it too.
    ompl = build is not None and (build / "libfloornav_rrt_connect.so").exists()
    env = {k: v for k, v in os.environ.items() if k not in ("PYTHONPATH", "PYTHONHOME")}
    env["PIP_NO_INDEX"] = "1"  # never the network
    env["PIP_DISABLE_PIP_VERSION_CHECK"] = "1"
    if build:
        env["FLOORNAV_CMAKE_BUILD_DIR"] = str(build)
    with tempfile.TemporaryDirectory(prefix="floornav-pip-") as tmp:
        tmp = Path(tmp)
        venv = tmp / "venv"
        subprocess.run(["/usr/bin/python3", "-m", "venv", "--system-site-packages", str(venv)],
                       check=True, env=env)
        python = venv / "bin" / "python"
        subprocess.run([str(python), "-m", "pip", "install", "--no-build-isolation", "--no-index",
                        "-q", str(repo)], check=True, env=env, cwd=tmp)
        work = tmp / "elsewhere"
        work.mkdir()
        script = f"""
import json, os, floornav
print(json.dumps({{"file": floornav.__file__, "version": floornav.__version__}}))
r = floornav.run({str(repo / 'scenarios' / 'factory_delivery.yaml')!r}, out="out", mcap=True)
print(json.dumps({{"status": r.status, "files": sorted(os.listdir("out"))}}))
"""
        if ompl:  # the rrt_connect planner's module, loaded from beside the installed extension
            script += f"""
s = floornav.load_scenario({str(repo / 'scenarios' / 'fleet_crossing.yaml')!r},
                           {{"controller.planner.kind": "rrt_connect"}})
r = floornav.run(s)
module = [l.split()[-1] for l in open("/proc/self/maps") if "libfloornav_rrt_connect" in l]
print(json.dumps({{"rrt_connect": [x["status"] for x in r.summary["robots"]], "module": module}}))
"""
        done = subprocess.run([str(python), "-c", script], env=env, cwd=work,
                              capture_output=True, text=True)
        if done.returncode != 0:
            print(f"FAIL: the installed package did not run:\n{done.stderr}", file=sys.stderr)
            return 1
        where, outcome, *planned = (json.loads(line) for line in done.stdout.strip().splitlines())
    site = str(venv / "lib")
    failures = []
    if not where["file"].startswith(site):
        failures.append(f"floornav was imported from {where['file']}, not the venv ({site})")
    if outcome["status"] != "reached":
        failures.append(f"factory_delivery ended {outcome['status']}, not reached")
    for f in ("summary.json", "trajectory.csv", "trajectory.svg", "run.mcap"):
        if f not in outcome["files"]:
            failures.append(f"the run wrote no {f} ({outcome['files']})")
    if ompl and (not planned or set(planned[0]["rrt_connect"]) != {"reached"}):
        failures.append(f"fleet_crossing with rrt_connect: {planned}, not every robot reached")
    if ompl and planned and not all(m.startswith(site) for m in planned[0]["module"] or [""]):
        failures.append(f"the rrt_connect module was loaded from {planned[0]['module']}, not from "
                        f"the installed package ({site})")
    for f in failures:
        print(f"FAIL: {f}", file=sys.stderr)
    if not failures:
        print(f"floornav {where['version']} installed with pip into a fresh venv and ran "
              f"factory_delivery from outside the repository: {outcome['status']}" +
              (", and a fleet planned with rrt_connect from the package's module" if ompl else ""))
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
