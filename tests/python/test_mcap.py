"""run.mcap from Python (RunResult.write(out, mcap=True)) and from the command line: the same
bag, its topics read from the MCAP summary (by hand: the format's channel records), and every
topic named in docs/OUTPUTS.md. The reference readers check the content (tests/mcap)."""

from __future__ import annotations

import re
import struct

import floornav

from conftest import ROOT, SCENARIOS, run_cli

MAGIC = b"\x89MCAP0\r\n"


def topics(path) -> list[str]:
    """The channels' topics, from the summary: footer -> summary offsets -> the channel group."""
    data = path.read_bytes()
    assert data[:8] == MAGIC and data[-8:] == MAGIC
    footer = len(data) - 8 - 29
    assert data[footer] == 0x02
    offsets = struct.unpack_from("<Q", data, footer + 17)[0]
    out = []
    at = offsets
    while at < footer:
        assert data[at] == 0x0E
        group, start, length = struct.unpack_from("<BQQ", data, at + 9)
        if group == 0x04:  # channel records: id, schema id, topic, encoding, metadata
            c = start
            while c < start + length:
                (size,) = struct.unpack_from("<Q", data, c + 1)
                (n,) = struct.unpack_from("<I", data, c + 13)
                out.append(data[c + 17 : c + 17 + n].decode())
                c += 9 + size
        at += 9 + struct.unpack_from("<Q", data, at + 1)[0]
    return out


def test_write_with_mcap_equals_the_command_lines_bag(tmp_path):
    r = floornav.run(SCENARIOS / "factory_delivery.yaml", mcap=True)
    r.write(tmp_path / "py", mcap=True)
    done = run_cli("run", SCENARIOS / "factory_delivery.yaml", "--mcap", "--quiet",
                   "--out", tmp_path / "cli")
    assert done.returncode == 0, done.stderr
    py, cli = (tmp_path / "py" / "run.mcap").read_bytes(), (tmp_path / "cli" / "run.mcap").read_bytes()
    # The same bag, byte for byte (the header names the same build's version).
    assert py == cli, "the bags differ (is the floornav executable as new as the module?)"
    assert "/ring_scan" in topics(tmp_path / "py" / "run.mcap")


def test_a_run_without_mcap_writes_a_bag_without_sensor_topics(tmp_path):
    r = floornav.run(SCENARIOS / "factory_delivery.yaml")
    r.write(tmp_path, mcap=True)
    names = topics(tmp_path / "run.mcap")
    assert "/odom" in names and "/map" in names
    assert "/ring_scan" not in names
    r.write(tmp_path / "plain")
    assert not (tmp_path / "plain" / "run.mcap").exists()


def test_outputs_md_names_every_topic(tmp_path):
    doc = (ROOT / "docs" / "OUTPUTS.md").read_text()
    named = set(re.findall(r"`(/[a-z_0-9]+)`", doc))
    seen = set()
    for scenario, extra in [("factory_delivery.yaml", []),
                            ("ros/depot_1.yaml", ["--set", "sim.t_max=5"]),
                            ("crowd/factory_people.yaml", ["--set", "sim.t_max=5"])]:
        out = tmp_path / scenario.replace("/", "_")
        done = run_cli("run", SCENARIOS / scenario, "--mcap", "--quiet", "--out", out, *extra)
        assert done.returncode == 0, done.stderr
        for t in topics(out / "run.mcap"):
            # A fleet's robot topics: /<robot name>/odom is documented as /odom.
            seen.add("/" + t.split("/")[-1] if t.count("/") > 1 else t)
    assert seen - named == set()
