#!/usr/bin/env python3
"""Writes RVO2's Circle benchmark as floornav scenarios: N QuickBots evenly on a circle, 0.3 m apart
along it, each bound for its antipode, nothing else on the floor (walls 1 m beyond the circle).

    scripts/make_circle.py N [N ...] [--out scenarios/circle]
"""
import argparse
import math
import pathlib


def circle_scenario(n: int) -> str:
    spacing = 0.3  # m between neighbours along the circle
    radius = spacing * n / (2.0 * math.pi)
    half = radius + 1.0
    t_max = math.ceil(3.0 * 2.0 * radius / 0.15 + 60.0)
    lines = [
        f"# RVO2's Circle benchmark with {n} QuickBots: evenly on a circle of radius {radius:.3f} m",
        f"# ({spacing} m apart), each bound for its antipode; written by scripts/make_circle.py {n}.",
        f"name: circle-{n}",
        "world:",
        f"  bounds: [{-half:.3f}, {-half:.3f}, {half:.3f}, {half:.3f}]",
        "robots:",
    ]
    for i in range(n):
        a = 2.0 * math.pi * i / n
        x, y = radius * math.cos(a), radius * math.sin(a)
        heading = math.atan2(-y, -x)
        lines.append(f"  - {{name: r{i}, start: [{x:.4f}, {y:.4f}, {heading:.4f}], "
                     f"goal: [{-x:.4f}, {-y:.4f}]}}")
    lines += ["sim:", "  dt: 0.01", f"  t_max: {t_max}", "  record_trajectory: "
              + ("true" if n <= 100 else "false"), ""]
    return "\n".join(lines)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("n", type=int, nargs="+")
    parser.add_argument("--out", default=str(pathlib.Path(__file__).resolve().parent.parent
                                             / "scenarios" / "circle"))
    args = parser.parse_args()
    out = pathlib.Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    for n in args.n:
        (out / f"circle_{n}.yaml").write_text(circle_scenario(n))


if __name__ == "__main__":
    main()
