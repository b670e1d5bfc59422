#!/usr/bin/env python3
"""What a landslide run did, from one ParaView frame of mpm3d (NAME_anim_K.vtu, ASCII, with the
current version's disx, disy, disz): the sliding mass, its run-out and the scarp it leaves.

usage: tools/landslide_result.py FRAME.vtu [FRAME.vtu ...]

For the newest MPM3D-F90's 3D progressive landslides (docs/VERIFICATION.md): gravity along -y,
the slope's crest at x = 10.0 (the top row), its toe at x = 14.9, 5 m wide in z. A particle
slid when it moved more than 0.5 m. Printed per frame: the sliding volume (0.001 m^3 a
particle), the run-out (the farthest particle's x beyond the initial toe), the scarp (the
smallest initial x of a top-row particle that slid, and its distance behind the crest), the
final height of the ground at the crest's former x, the largest epeff and the share of the
sliding mass at residual strength (epeff > 1: the yield stress within 1 % of kappa_r for eta 5).
"""
import math
import re
import sys

CREST, TOE, TOP = 10.0, 14.9, 5.0


def arrays(path, wanted):
    """name -> list of floats for the wanted PointData arrays and the points (name 'points')."""
    out, name = {}, None
    with open(path) as f:
        for line in f:
            if line.startswith("<DataArray"):
                m = re.search(r'Name="([^"]+)"', line)
                key = m.group(1) if m else ("points" if 'NumberOfComponents="3"' in line else None)
                name = key if key in wanted else None
                if name:
                    out[name] = []
                continue
            if line.startswith("</DataArray"):
                name = None
                continue
            if name:
                out[name].extend(float(v) for v in line.split())
    return out


def summary(path):
    a = arrays(path, {"points", "disx", "disy", "disz", "epeff"})
    pts, n = a["points"], len(a["epeff"])
    slid, vol_res, far, scarp, ground, epmax = 0, 0, -1e9, None, 0.0, 0.0
    for i in range(n):
        x, y = pts[3 * i], pts[3 * i + 1]
        dx, dy, dz = a["disx"][i], a["disy"][i], a["disz"][i]
        x0, y0 = x - dx, y - dy
        moved = math.sqrt(dx * dx + dy * dy + dz * dz) > 0.5
        far = max(far, x)
        epmax = max(epmax, a["epeff"][i])
        if moved:
            slid += 1
            vol_res += a["epeff"][i] > 1.0
            if y0 > TOP - 0.1 and (scarp is None or x0 < scarp):
                scarp = x0
        if abs(x - CREST) < 0.1:
            ground = max(ground, y + 0.05)
    return {"particles": n, "sliding_m3": slid * 1e-3, "runout_m": far + 0.05 - TOE,
            "scarp_x": scarp, "scarp_behind_crest_m": None if scarp is None else CREST - (scarp - 0.05),
            "ground_at_crest_m": ground, "max_epeff": epmax,
            "residual_share": vol_res / slid if slid else 0.0}


def main(argv):
    for path in argv[1:]:
        s = summary(path)
        print(path)
        for k, v in s.items():
            print("  %-22s %s" % (k, "%.3f" % v if isinstance(v, float) else v))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
