#!/usr/bin/env python3
"""The HDF5 + XDMF animation series (docs/DECK_FORMAT.md, keyword hdf5): runs mpm3d on a
deck with all fourteen outr variables and the hdf5 keyword, parses name_anim.xdmf with
xml.etree and checks that it is a temporal collection of uniform Polyvertex grids whose
every DataItem names an existing dataset of the stated shape in name_anim.h5 (h5ls), and
that each grid's time equals the time attribute of its HDF5 group (h5dump).
usage: check_xdmf.py MPM3D DECK WORKDIR"""
import os
import re
import shutil
import subprocess
import sys
import xml.etree.ElementTree as ET

VARS = "seqv epef mat pres volu engk engi velx vely velz cels fail sspd damg".split()


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
    grids = coll.findall("Grid")
    # small.mpm: endt 0.5, outt 0.25: frames at t = 0, 0.25, 0.5 (to within a step).
    assert len(grids) == 3, len(grids)
    times = [float(g.find("Time").get("Value")) for g in grids]
    dt = 0.5 * 1.0 / 120 ** 0.5
    for t, want in zip(times, [0.0, 0.25, 0.5]):
        assert want - 1e-12 <= t < want + dt, times
    checked = 0
    for k, g in enumerate(grids):
        assert g.get("GridType") == "Uniform"
        topo = g.find("Topology")
        assert topo.get("TopologyType") == "Polyvertex" and topo.get("NumberOfElements") == "128"
        assert g.find("Geometry").get("GeometryType") == "XYZ"
        names = [a.get("Name") for a in g.findall("Attribute")]
        assert names == VARS, names
        for item in g.iter("DataItem"):
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
    assert checked == 3 * 15
    print("XDMF: %d frames, %d DataItems, each an existing dataset of its shape" % (len(grids), checked))


if __name__ == "__main__":
    main()
