# SPDX-License-Identifier: MIT
# SPDX-FileCopyrightText: 2026 dalembert engineers
# dalembert --format json read as JSON (Debian's /usr/bin/python3, json module): each command's
# document parses, has the members docs/cli.md lists, agrees with the command's CSV form and with
# closed forms (the bead on a ring), and docs/cli.md's example is the command's output.
# usage: /usr/bin/python3 cli_json.py <dalembert> <scenes dir> <docs/cli.md>
import json
import math
import re
import subprocess
import sys

cli, scenes, doc = sys.argv[1], sys.argv[2], sys.argv[3]
failed = 0


def check(ok, what):
    global failed
    print(("ok   " if ok else "FAIL ") + what)
    failed += not ok


def run(*args):
    p = subprocess.run([cli, *args, "--no-progress"], capture_output=True, text=True)
    return p.returncode, p.stdout, p.stderr


def doc_json(args):
    out = run(*args, "--format", "json")
    check(out[0] == 0, "%s --format json: exit %d %s" % (" ".join(args), out[0], out[2]))
    return json.loads(out[1])


def csv_rows(args):
    out = run(*args)
    return [l.split(",") for l in out[1].splitlines() if l and l[0] in "-0123456789"]


def close(a, b, tol):
    return a is not None and b is not None and abs(a - b) <= tol * max(1.0, abs(b))


def same(a, b, tol):  # two parsed JSON values, numbers within tol
    if isinstance(a, dict):
        return isinstance(b, dict) and a.keys() == b.keys() and all(same(a[k], b[k], tol) for k in a)
    if isinstance(a, list):
        return isinstance(b, list) and len(a) == len(b) and all(same(x, y, tol) for x, y in zip(a, b))
    if isinstance(a, float) or isinstance(b, float):
        return close(float(a), float(b), tol)
    return a == b


below, above, dp = scenes + "/bead_ring_below.scene", scenes + "/bead_ring_above.scene", \
    scenes + "/driven_pendulum.scene"

# modes: omega^2 = g/R - w^2, and docs/cli.md's example is this output (the path aside)
m = doc_json(["modes", below])
check(m["command"] == "modes" and m["at"] == "equilibrium" and m["verdict"] == "neutral",
      "modes: command, at, verdict")
check(close(m["modes"][0]["omega2"], 9.81 - 4.0, 1e-13), "modes: omega2 = g/R - w^2")
block = re.search(r"--format json` prints.*?```json\n(.*?)```", open(doc).read(), re.S)
example = json.loads(block.group(1)) if block else None
if example:
    example["scene"] = m["scene"]
check(example is not None and same(example, m, 1e-12), "docs/cli.md's modes example is the output")

# equilibria of the bead above its critical rate: cos theta* = g/(R w^2), the bottom unstable
e = doc_json(["equilibria", above, "--scan", "theta=-1.5:1.5:7"])
ts = math.acos(9.81 / 25)
star = [x for x in e["equilibria"] if close(x["q"]["theta"], ts, 1e-12)]
bottom = [x for x in e["equilibria"] if abs(x["q"]["theta"]) < 1e-12]
check(len(star) == 1 and close(star[0]["omega2_min"], 25 * math.sin(ts) ** 2, 1e-12),
      "equilibria: theta* = acos(g/(R w^2)) with omega2 = w^2 sin^2 theta*")
check(len(bottom) == 1 and bottom[0]["stability"] == "unstable" and
      close(bottom[0]["omega2_min"], 9.81 - 25, 1e-12), "equilibria: the bottom, unstable")
check(e["starts"] == 8 and e["complete"] is True, "equilibria: 8 starts, complete")

# lyapunov: the CSV's numbers, and lambda_1 + lambda_2 = 0 (a Hamiltonian flow)
args = ["lyapunov", dp, "--t1", "40", "--method", "rk4", "--h", "0.00390625"]
l, rows = doc_json(args), csv_rows(args)
check(len(l["exponents"]) == 2 and len(rows) == 2 and
      all(close(x["value"], float(r[1]), 0) and close(x["error95"], float(r[2]), 0)
          for x, r in zip(l["exponents"], rows)), "lyapunov: the CSV's exponents")
check(abs(l["exponents"][0]["value"] + l["exponents"][1]["value"]) < 1e-9 and
      l["method"] == "rk4" and l["t1"] == 40 and l["complete"] is True, "lyapunov: sum 0, members")

# section: the CSV's points, stroboscopic and surface
for extra, kind in (([], "stroboscopic"), (["--surface"], "surface")):
    s, rows = doc_json(["section", dp, *extra]), csv_rows(["section", dp, *extra])
    col = 2 if kind == "surface" else 1  # the CSV's theta column
    check(s["kind"] == kind and len(s["points"]) == len(rows) > 5 and
          all(close(p["t"], float(r[0]), 0) and close(p["q"]["theta"], float(r[col]), 0)
              for p, r in zip(s["points"], rows)), "section %s: the CSV's points" % kind)

# sweep: the CSV's final states; a failing value has its status, null state, the file's line
sw, rows = doc_json(["sweep", below, "--param", "omega=1:3:3"]), \
    csv_rows(["sweep", below, "--param", "omega=1:3:3"])
check(sw["param"] == "omega" and len(sw["runs"]) == 3 and sw["failed"] == 0 and
      all(x["status"] == "DAL_OK" and close(x["q"]["theta"], float(r[3]), 0)
          for x, r in zip(sw["runs"], rows)), "sweep: the CSV's final states")
bad = doc_json(["sweep", below, "--param", "m=-1:1:3"])
line = [i + 1 for i, t in enumerate(open(below)) if t.startswith("particle bead")][0]
check(bad["failed"] == 2 and bad["runs"][0]["status"] == "DAL_E_ARG" and
      bad["runs"][0]["q"]["theta"] is None and
      ("bead_ring_below.scene:%d: particle 'bead'" % line) in bad["runs"][0]["message"],
      "sweep: a failing value's status, null state and the file's line")

# a format the command does not have
rc, _, err = run("modes", below, "--format", "xml")
check(rc == 64 and "--format xml: one of csv|json" in err, "modes --format xml refused")
print("cli_json: %d failed" % failed)
sys.exit(1 if failed else 0)
