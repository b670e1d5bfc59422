#!/usr/bin/env python3
"""The HDF5 + XDMF animation series (docs/DECK_FORMAT.md, keyword hdf5): runs mpm3d on a
deck with all fourteen outr variables and the hdf5 keyword, parses name_anim.xdmf with
xml.etree and checks that it is a temporal collection whose every step is a spatial
collection of the particles (Polyvertex with its connectivity, the book version's fields
then the outr variables) and the background grid (Hexahedron), whose every DataItem names
an existing dataset of the stated shape in name_anim.h5 (h5ls), and that each step's time
equals the time attribute of its HDF5 group (h5dump).
usage: check_xdmf.py MPM3D DECK WORKDIR"""
import os
import re
import shutil
import subprocess
import sys
import xml.etree.ElementTree as ET

VARS = "seqv epef mat pres volu engk engi velx vely velz cels fail sspd damg".split()
BOOK = "seqv epeff pressure vx vy vz vol celsius_t damage".split()


def main():
    exe, deck, work = sys.argv[1:4]
    shutil.rmtree(work, ignore_errors=True)
    os.makedirs(work)
    text = open(deck).read()
    extra = "hdf5\n" + "".join("outr %s\n" % v for v in VARS)
    i = text.rindex("endi")
    path = os.path.join(work, "series.mpm")
    open(path, "w").write(text[:i] + extra + text[i:])
    subprocess.run([exe, "--quiet", "--no-output", "--hdf5", "--out-dir", work, path], check=True)
    # --no-output with --hdf5: the series only.
    assert sorted(os.listdir(work)) == ["series.mpm", "series_anim.h5", "series_anim.xdmf"], os.listdir(work)

    root = ET.parse(os.path.join(work, "series_anim.xdmf")).getroot()
    assert root.tag == "Xdmf" and root.get("Version") == "3.0"
    coll = root.find("Domain/Grid")
    assert coll.get("GridType") == "Collection" and coll.get("CollectionType") == "Temporal"
    steps = coll.findall("Grid")
    # small.mpm: endt 0.5, outt 0.25: frames at t = 0, 0.25, 0.5 (to within a step).
    assert len(steps) == 3, len(steps)
    times = [float(g.find("Time").get("Value")) for g in steps]
    dt = 0.5 * 1.0 / 120 ** 0.5
    for t, want in zip(times, [0.0, 0.25, 0.5]):
        assert want - 1e-12 <= t < want + dt, times
    checked = 0
    for k, step in enumerate(steps):
        assert step.get("GridType") == "Collection" and step.get("CollectionType") == "Spatial"
        parts, grid = step.findall("Grid")
        assert parts.get("Name") == "particles" and parts.get("GridType") == "Uniform"
        topo = parts.find("Topology")
        assert topo.get("TopologyType") == "Polyvertex" and topo.get("NumberOfElements") == "128"
        assert topo.find("DataItem").text.strip().endswith(":/cells")  # without it ParaView draws nothing
        assert parts.find("Geometry").get("GeometryType") == "XYZ"
        names = [a.get("Name") for a in parts.findall("Attribute")]
        assert names == BOOK + [v for v in VARS if v not in BOOK], names
        assert grid.get("Name") == "grid" and grid.find("Topology").get("TopologyType") == "Hexahedron"
        assert grid.find("Topology").get("NumberOfElements") == "128"  # small.mpm: 8 x 4 x 4 cells
        for item in step.iter("DataItem"):
            assert item.get("Format") == "HDF"
            dims = [int(d) for d in item.get("Dimensions").split()]
            fname, dset = item.text.strip().split(":")
            out = subprocess.run(["h5ls", os.path.join(work, fname) + dset], capture_output=True, text=True).stdout
            m = re.search(r"Dataset \{([0-9, ]+)\}", out)
            assert m, "no dataset %s in %s: %s" % (dset, fname, out)
            assert [int(d) for d in m.group(1).split(",")] == dims, (dset, out, dims)
            checked += 1
        out = subprocess.run(["h5dump", "-m", "%.17g", "-a", "/frames/%d/time" % k, os.path.join(work, "series_anim.h5")],
                             capture_output=True, text=True, check=True).stdout
        assert float(re.search(r"\(0\): (\S+)", out).group(1)) == times[k], (out, times[k])
    # Per step: connectivity, positions, 9 + 13 fields, the grid's cells and points.
    assert checked == 3 * (2 + 9 + 13 + 2), checked
    print("XDMF: %d frames, %d DataItems, each an existing dataset of its shape" % (len(steps), checked))


if __name__ == "__main__":
    main()
