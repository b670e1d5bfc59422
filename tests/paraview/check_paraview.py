#!/usr/bin/env python3
"""ParaView reads mpm3d's animation files (ctest family paraview.*, docs/DECK_FORMAT.md
"Animation files"): runs mpm3d on a small deck, then ParaView's pvbatch under xvfb-run on
one of its files (pv_probe.py beside this script), and checks what ParaView read against
the run's HDF5 state (--state, read with h5dump): the number of points and cells, the cell
types, the field names, every field's values at the last frame, the times, and that a
rendered picture is not all background.

usage: check_paraview.py MODE MPM3D DECK WORKDIR
  pvd         the ParaView series (deck keyword para, ASCII): the book version's fields
  pvd_binary  the same with --vtu-binary on the deck made a current-version one (smoo):
              the current version's fields, exact values
  xdmf        the HDF5 + XDMF series (--hdf5) of the deck without outr variables: the
              particles and the background grid as the two blocks of every time
  grid        name_Grid.vtu: the deck's grid as voxels filling the box
  deck_book, deck_current  a deck of inputs/ that writes its own series (para), run as it is
              with --hdf5: the .pvd and the XDMF series, each with the version's fields
Exit 77 (ctest: skipped) when pvbatch, xvfb-run or h5dump is missing."""
import json
import math
import os
import random
import re
import shutil
import subprocess
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
SKIP = 77
BOOK = ["seqv", "epeff", "pressure", "vx", "vy", "vz", "vol", "celsius_t", "damage"]
CURRENT = ["seqv", "epeff", "pressure", "Smoothpressure", "MeanNormalStress", "SmoothMeanNormalStress", "vx", "vy",
           "vz", "disx", "disy", "disz", "fxpx", "fxpy", "fxpz", "vol", "celsius_t", "damage", "stressx"]
# The outr lines added to the deck in the pvd modes (kept under their own names too).
OUTR = ["velz", "pres", "epef", "mat"]
VTK_VERTEX, VTK_POLY_VERTEX, VTK_VOXEL, VTK_HEXAHEDRON = 1, 2, 11, 12
X_RACE = ("bad X server connection", "Xvfb failed to start", "cannot open display", "Can't open display")


def fail(msg):
    print("FAIL: " + msg)
    sys.exit(1)


def need_tools():
    missing = [t for t in ("pvbatch", "xvfb-run", "h5dump") if shutil.which(t) is None]
    if missing:
        pkgs = {"pvbatch": "paraview", "xvfb-run": "xvfb", "h5dump": "hdf5-tools"}
        print("SKIP: %s not found (Debian packages: %s)" % (", ".join(missing), " ".join(pkgs[m] for m in missing)))
        sys.exit(SKIP)


def h5_values(path, obj, attribute=False):
    """The values of a dataset or an attribute, flat, read with h5dump at 17 digits."""
    args = ["h5dump", "-m", "%.17g", "-w", "0", "-y"] + (["-a", obj] if attribute else ["-d", obj]) + [path]
    out = subprocess.run(args, capture_output=True, text=True, check=True).stdout
    body = out[out.index("DATA {") + len("DATA {"):]
    body = body[:body.index("}")]
    return [float(v) for v in re.split(r"[,\s]+", body.replace("(0):", "").strip()) if v]


def state(path):
    s = {k: h5_values(path, "/particles/" + k) for k in ("position", "velocity", "stress", "volume", "epeff", "material")}
    s["time"] = h5_values(path, "/particles/time", attribute=True)[0]
    s["np"] = len(s["volume"])
    return s


def rows(flat, n):
    return [flat[i * n:(i + 1) * n] for i in range(len(flat) // n)]


def expected_fields(s, current):
    """Each field of the last frame computed from the state (deck order, as the files)."""
    sig = rows(s["stress"], 6)
    vel = rows(s["velocity"], 3)
    pres = [-((a[0] + a[1]) + a[2]) / 3.0 for a in sig]
    f = {"epeff": s["epeff"], "pressure": pres, "vol": s["volume"],
         "vx": [v[0] for v in vel], "vy": [v[1] for v in vel], "vz": [v[2] for v in vel],
         "celsius_t": [293.0] * s["np"], "damage": [0.0] * s["np"]}
    seqv = []
    for a, p in zip(sig, pres):
        d = [a[0] + p, a[1] + p, a[2] + p]
        seqv.append(math.sqrt(1.5 * ((d[0] * d[0] + d[1] * d[1] + d[2] * d[2]) + 2.0 * (a[3] * a[3] + a[4] * a[4] + a[5] * a[5]))))
    f["seqv"] = seqv
    if current:
        f["MeanNormalStress"] = [-p for p in pres]
        f["stressx"] = [a[0] for a in sig]
    f.update({"velz": f["vz"], "pres": pres, "epef": s["epeff"], "mat": s["material"]})
    return f


def close(name, got, want, rel):
    if len(got) != len(want):
        fail("%s: %d values, the state has %d" % (name, len(got), len(want)))
    scale = max([abs(w) for w in want] + [1e-300])
    worst = max(abs(g - w) for g, w in zip(got, want)) if want else 0.0
    if worst > rel * scale:
        fail("%s: differs from the state by up to %.3g (values %.6g..%.6g, state %.6g..%.6g)" %
             (name, worst, min(got), max(got), min(want), max(want)))
    print("  %-24s %d values in %.6g..%.6g, as the state (largest difference %.3g)" %
          (name, len(got), min(got), max(got), worst))


def probe(kind, path, work, colour=None):
    out, png = os.path.join(work, kind + ".json"), os.path.join(work, kind + ".png")
    cmd = ["xvfb-run", "-a", "pvbatch", os.path.join(HERE, "pv_probe.py"), kind, os.path.abspath(path), out, png]
    if colour:
        cmd.append(colour)
    # xvfb-run -a picks the first display without a lock file: two started at once (other
    # runs on the machine) may pick the same one, and the loser's pvbatch finds no X server.
    # Any other failure is retried once, its output printed: a failure of what ParaView reads
    # repeats, a start-up failure of the X server or pvbatch (seen once in a full run, not
    # reproduced) does not.
    retried = False
    for attempt in range(5):
        if os.path.exists(out):
            os.remove(out)
        r = subprocess.run(cmd, capture_output=True, text=True)
        text = r.stdout + r.stderr
        if r.returncode == 0 and os.path.exists(out):
            break
        if any(m in text for m in X_RACE):
            print("  (X server not reachable, try %d: %s)" % (attempt + 1, [m for m in X_RACE if m in text][0]))
        elif not retried and "No module named 'paraview'" not in text:
            retried = True
            print("  (pvbatch failed (%d), retried once:\n%s)" % (r.returncode, text[-2000:]))
        else:
            break
        time.sleep(1.0 + 2.0 * random.random())
    if "No module named 'paraview'" in r.stdout + r.stderr:
        print("SKIP: pvbatch finds no ParaView Python modules (Debian package: python3-paraview)")
        sys.exit(SKIP)
    if r.returncode != 0 or not os.path.exists(out):
        fail("pvbatch failed (%d):\n%s%s" % (r.returncode, r.stdout[-3000:], r.stderr[-3000:]))
    return json.load(open(out))


def check_picture(res):
    png = res.get("png")
    if not png or png["drawn"] < 0.01 * png["pixels"]:
        fail("the rendered picture is (nearly) all background: %s" % png)
    print("  picture: %d of %d pixels drawn" % (png["drawn"], png["pixels"]))


def check_times(times, want, what):
    if len(times) != len(want) or any(abs(a - b) > 1e-15 * max(1.0, abs(b)) for a, b in zip(times, want)):
        fail("times %s, %s %s" % (times, what, want))
    print("  times: %d, %s" % (len(times), ", ".join("%.6g" % t for t in times)))


def check_particles(block, s, names, current, rel, kind_of_cell):
    if block["points"] != s["np"] or block["cells"] != s["np"]:
        fail("%d points and %d cells, the deck has %d particles" % (block["points"], block["cells"], s["np"]))
    if block["cell_types"] != [kind_of_cell]:
        fail("cell types %s, want [%d]" % (block["cell_types"], kind_of_cell))
    print("  %d points, %d cells of type %d" % (block["points"], block["cells"], kind_of_cell))
    have = set(block["arrays"])
    missing = [n for n in names if n not in have]
    if missing:
        fail("fields missing: %s (ParaView read %s)" % (missing, sorted(have)))
    close("points", [c for p in block["xyz"] for c in p], s["position"], rel)
    want = expected_fields(s, current)
    for n in names:
        if n in want:
            close(n, block["arrays"][n], want[n], rel)


def run(cmd):
    r = subprocess.run(cmd, capture_output=True, text=True)
    if r.returncode != 0:
        fail("%s: exit %d\n%s" % (" ".join(cmd), r.returncode, r.stderr))


def deck_with(deck, work, extra):
    text = open(deck).read()
    i = text.lower().rindex("endi")
    path = os.path.join(work, "pv.mpm")
    open(path, "w").write(text[:i] + extra + text[i:])
    return path


def main():
    mode, exe, deck, work = sys.argv[1:5]
    need_tools()
    shutil.rmtree(work, ignore_errors=True)
    os.makedirs(work)
    st = os.path.join(work, "state.h5")
    outr = "".join("outr %s\n" % v for v in OUTR)
    if mode in ("pvd", "pvd_binary"):
        current = mode == "pvd_binary"
        d = deck_with(deck, work, "para\noutt 0.005\n" + outr + ("smoo\n" if current else ""))
        run([exe, "--quiet", "--out-dir", work, "--state", st, d] + (["--vtu-binary"] if current else []))
        s = state(st)
        res = probe("pvd", os.path.join(work, "pv_anim.pvd"), work, "vz")
        # The .pvd lists frames 1, 2, ... with their times; the last is the final state.
        listed = re.findall(r'timestep="([^"]+)"[^>]*file="([^"]+)"', open(os.path.join(work, "pv_anim.pvd")).read())
        if [f for _, f in listed] != ["pv_anim_%d.vtu" % k for k in range(1, len(listed) + 1)]:
            fail("the .pvd lists %s, want pv_anim_1.vtu, pv_anim_2.vtu, ..." % [f for _, f in listed])
        check_times(res["times"], [float(t) for t, _ in listed], "the .pvd lists")
        if res["times"][0] != 0.0 or res["times"][-1] != s["time"] or len(res["times"]) < 3:
            fail("times %s: want 0 first and the state's %r last" % (res["times"], s["time"]))
        last = res["frames"][-1]["blocks"]["all"]
        names = (CURRENT if current else BOOK) + OUTR
        check_particles(last, s, names, current, 0.0 if current else 1e-9, VTK_VERTEX)
        if current:
            first = res["frames"][0]["blocks"]["all"]
            x0 = [c for p in first["xyz"] for c in p]
            x1 = [c for p in last["xyz"] for c in p]
            for a, n in enumerate(("disx", "disy", "disz")):
                close(n, last["arrays"][n], [x1[3 * i + a] - x0[3 * i + a] for i in range(s["np"])], 1e-12)
            sp = last["arrays"]["Smoothpressure"]
            if max(abs(v) for v in sp) == 0.0:
                fail("Smoothpressure is 0 everywhere with smoo")
            close("SmoothMeanNormalStress", last["arrays"]["SmoothMeanNormalStress"], [-v for v in sp], 0.0)
            # two_blocks.mpm: load node 1 0 0 -0.5 (deck particle 1) and nothing else.
            f = [0.0] * s["np"]
            f[0] = -0.5
            close("fxpz", last["arrays"]["fxpz"], f, 0.0)
            close("fxpx", last["arrays"]["fxpx"], [0.0] * s["np"], 0.0)
        check_picture(res)
    elif mode == "xdmf":
        run([exe, "--quiet", "--no-output", "--hdf5", "--out-dir", work, "--state", st, deck])
        s = state(st)
        base = os.path.splitext(os.path.basename(deck))[0]
        h5 = os.path.join(work, base + "_anim.h5")
        frames = []
        while True:
            try:
                frames.append(h5_values(h5, "/frames/%d/time" % len(frames), attribute=True)[0])
            except (subprocess.CalledProcessError, ValueError):
                break
        res = probe("xdmf", os.path.join(work, base + "_anim.xdmf"), work, "vz")
        check_times(res["times"], frames, "the .h5 frames have")
        if res["times"][-1] != s["time"] or len(frames) < 2:
            fail("last time %r, the state's %r" % (res["times"][-1], s["time"]))
        blocks = res["frames"][-1]["blocks"]
        parts = [b for n, b in blocks.items() if n.startswith("particles")]
        grids = [b for n, b in blocks.items() if n.startswith("grid")]
        if len(parts) != 1 or len(grids) != 1:
            fail("blocks %s: want one 'particles' and one 'grid'" % list(blocks))
        check_particles(parts[0], s, BOOK, False, 0.0, VTK_POLY_VERTEX)
        nodes, cells = lattice(deck)
        g = grids[0]
        if (g["points"], g["cells"], g["cell_types"]) != (nodes, cells, [VTK_HEXAHEDRON]):
            fail("grid block: %d points, %d cells of types %s; the deck's grid has %d nodes, %d cells" %
                 (g["points"], g["cells"], g["cell_types"], nodes, cells))
        print("  grid block: %d nodes, %d hexahedra" % (nodes, cells))
        check_picture(res)
    elif mode == "grid":
        d = deck_with(deck, work, "para\n")
        run([exe, "--quiet", "--steps", "1", "--out-dir", work, d])
        res = probe("vtu", os.path.join(work, "pv_Grid.vtu"), work)
        g = res["frames"][0]["blocks"]["all"]
        nodes, cells = lattice(deck)
        lo, hi, h = box(deck)
        if (g["points"], g["cells"], g["cell_types"]) != (nodes, cells, [VTK_VOXEL]):
            fail("%d points, %d cells of types %s; the deck's grid has %d nodes, %d voxels" %
                 (g["points"], g["cells"], g["cell_types"], nodes, cells))
        print("  %d nodes, %d voxels" % (nodes, cells))
        for a in range(3):
            c = [p[a] for p in g["xyz"]]
            if abs(min(c) - lo[a]) > 1e-9 * h or abs(max(c) - hi[a]) > 1e-9 * h:
                fail("nodes span %g..%g along axis %d, the box %g..%g" % (min(c), max(c), a, lo[a], hi[a]))
        vol = (hi[0] - lo[0]) * (hi[1] - lo[1]) * (hi[2] - lo[2])
        if abs(res["frames"][0]["volume"] - vol) > 1e-9 * vol:
            fail("the cells' volumes sum to %r, the box's is %r" % (res["frames"][0]["volume"], vol))
        print("  the voxels fill the box: volume %g" % vol)
        check_picture(res)
    elif mode in ("deck_book", "deck_current"):
        current = mode == "deck_current"
        run([exe, "--quiet", "--hdf5", "--out-dir", work, "--state", st, deck])
        s = state(st)
        base = os.path.splitext(os.path.basename(deck))[0]
        names = CURRENT if current else BOOK
        pvd = probe("pvd", os.path.join(work, base + "_anim.pvd"), work, "vz")
        check_particles(pvd["frames"][-1]["blocks"]["all"], s, names, current, 1e-9, VTK_VERTEX)
        check_picture(pvd)
        xdmf = probe("xdmf", os.path.join(work, base + "_anim.xdmf"), work, "vz")
        parts = [b for n, b in xdmf["frames"][-1]["blocks"].items() if n.startswith("particles")]
        if len(parts) != 1:
            fail("XDMF blocks %s: want one 'particles'" % list(xdmf["frames"][-1]["blocks"]))
        check_particles(parts[0], s, names, current, 0.0, VTK_POLY_VERTEX)
        check_times(xdmf["times"], pvd["times"], "the .pvd has")
        check_picture(xdmf)
    else:
        fail("unknown mode " + mode)
    print("OK")


def box(deck):
    lo, hi, h = [0.0] * 3, [0.0] * 3, None
    for line in open(deck):
        w = line.split("!")[0].split()
        if not w:
            continue
        k = w[0].lower()[:4]
        if k in ("spx", "spy", "spz"):
            a = "xyz".index(k[2])
            lo[a], hi[a] = float(w[1].replace("d", "e")), float(w[2].replace("d", "e"))
        elif k == "dcel":
            h = float(w[1].replace("d", "e"))
    return lo, hi, h


def lattice(deck):
    lo, hi, h = box(deck)
    n = [int(math.floor((hi[a] - lo[a]) / h + 0.5)) for a in range(3)]
    return (n[0] + 1) * (n[1] + 1) * (n[2] + 1), n[0] * n[1] * n[2]


if __name__ == "__main__":
    main()
