#!/usr/bin/env python3
"""The layers of cxx/ and fortran_ref/ point one way (docs/ARCHITECTURE.md, "Layers").

usage: tests/layers.py [REPO_ROOT]

Reads the layer order from the line "Layer order (lowest first): `a < b < ...`" of
docs/ARCHITECTURE.md and fails (exit 1, one line per offence) when
- a file of cxx/ includes ("#include "folder/...") a file of a folder above its own, or an
  include names a folder that is not a layer, or a path with "..";
- a folder of cxx/ is not in the order (a new folder must be placed);
- a module of fortran_ref/ uses a module of a layer above its own (FORTRAN_LAYERS below
  places each file), or a file there is not placed.
The cxx/ root (mpm3d.hpp, the library's one include) counts as the solver layer it gathers.
"""
import os
import re
import sys

ROOT = os.path.abspath(sys.argv[1] if len(sys.argv) > 1 else os.path.join(os.path.dirname(__file__), ".."))
ORDER_RE = re.compile(r"Layer order \(lowest first\): `([^`]+)`")
INCLUDE_RE = re.compile(r'^\s*#\s*include\s+"([^"]+)"', re.M)
USE_RE = re.compile(r"^\s*use\s+(mpm3d_\w+)", re.M | re.I)
MODULE_RE = re.compile(r"^\s*module\s+(mpm3d_\w+)\s*$", re.M | re.I)
ROOT_LAYER = "solver"

# The Fortran reference has no folders: each file's layer, as its C++ twin's folder.
FORTRAN_LAYERS = {
    "grid.f90": "core", "particle.f90": "core", "rules.f90": "core",
    "material.f90": "materials", "eos.f90": "materials", "j2_plasticity.f90": "materials",
    "drucker_prager.f90": "materials", "neo_hookean.f90": "materials", "stress_ops.f90": "materials",
    "constitution.f90": "materials", "material_models.f90": "materials",
    # step_context (the step state) with the patch buffers, stencils and assembly the
    # stages share: the C++ core/ and transfer/transfer_common.hpp in one module.
    "stage_common.f90": "transfer", "stage_sg.f90": "transfer",
    "stage_bin.f90": "stages", "stage_p2g.f90": "stages", "stage_grid.f90": "stages",
    "stage_g2p.f90": "stages", "stage_stress.f90": "stages", "stage_energy.f90": "stages",
    "update_step.f90": "stages",
    "ffi.f90": "input", "particle_gen.f90": "input", "data_in.f90": "input",
    "data_in_cards.f90": "input", "data_in_finish.f90": "input",
    "data_out.f90": "io",
    "mpm3d_ref.f90": "app",
}


def layer_order():
    path = os.path.join(ROOT, "docs", "ARCHITECTURE.md")
    with open(path, encoding="utf-8") as f:
        m = ORDER_RE.search(f.read())
    if not m:
        sys.exit("docs/ARCHITECTURE.md: no line 'Layer order (lowest first): `a < b < ...`'")
    return [name.strip() for name in m.group(1).split("<")]


def check_cxx(rank, errors):
    cxx = os.path.join(ROOT, "cxx")
    for folder in sorted(os.listdir(cxx)):
        if os.path.isdir(os.path.join(cxx, folder)) and folder not in rank:
            errors.append(f"cxx/{folder}/: a folder not in the layer order")
    edges = 0
    for dirpath, _, files in os.walk(cxx):
        rel_dir = os.path.relpath(dirpath, cxx)
        own = ROOT_LAYER if rel_dir == "." else rel_dir.split(os.sep)[0]
        for name in sorted(files):
            if not name.endswith((".hpp", ".cpp", ".h", ".c")):
                continue
            rel = os.path.join("cxx", os.path.relpath(os.path.join(dirpath, name), cxx))
            with open(os.path.join(dirpath, name), encoding="utf-8") as f:
                text = f.read()
            for lineno, inc in ((text.count("\n", 0, m.start()) + 1, m.group(1)) for m in INCLUDE_RE.finditer(text)):
                if ".." in inc.split("/"):
                    errors.append(f"{rel}:{lineno}: includes \"{inc}\": a path with '..'")
                    continue
                if "/" in inc:
                    target = inc.split("/")[0]
                else:  # a file of the including folder, or the root's mpm3d.hpp
                    target = ROOT_LAYER if inc == "mpm3d.hpp" else own
                if target not in rank:
                    if os.path.exists(os.path.join(cxx, inc)):
                        errors.append(f"{rel}:{lineno}: includes \"{inc}\" of a folder not in the layer order")
                    continue  # a system or generated header
                if own not in rank:
                    continue  # reported above
                edges += 1
                if rank[target] > rank[own]:
                    errors.append(f"{rel}:{lineno}: includes \"{inc}\": {own} includes {target}, a layer above it")
    return edges


def check_fortran(rank, errors):
    ref = os.path.join(ROOT, "fortran_ref")
    module_file = {}
    texts = {}
    for name in sorted(os.listdir(ref)):
        if not name.endswith(".f90"):
            continue
        with open(os.path.join(ref, name), encoding="utf-8") as f:
            texts[name] = f.read()
        for m in MODULE_RE.finditer(texts[name]):
            module_file[m.group(1).lower()] = name
        if name not in FORTRAN_LAYERS:
            errors.append(f"fortran_ref/{name}: not placed in a layer (tests/layers.py FORTRAN_LAYERS)")
    edges = 0
    for name, text in texts.items():
        own = FORTRAN_LAYERS.get(name)
        if own is None:
            continue
        for m in USE_RE.finditer(text):
            used = module_file.get(m.group(1).lower())
            if used is None or used == name:
                continue
            edges += 1
            target = FORTRAN_LAYERS.get(used)
            if target is not None and rank[target] > rank[own]:
                lineno = text.count("\n", 0, m.start()) + 1
                errors.append(f"fortran_ref/{name}:{lineno}: uses {m.group(1)} ({used}): {own} uses {target}, a layer above it")
    return edges


def main():
    order = layer_order()
    rank = {name: i for i, name in enumerate(order)}
    for layer in set(FORTRAN_LAYERS.values()) | {ROOT_LAYER}:
        if layer not in rank:
            sys.exit(f"tests/layers.py places files in '{layer}', which docs/ARCHITECTURE.md's order lacks")
    errors = []
    n_cxx = check_cxx(rank, errors)
    n_f = check_fortran(rank, errors)
    for e in errors:
        print(e)
    if errors:
        print(f"{len(errors)} include(s) or use(s) against the layer order {' < '.join(order)}")
        return 1
    print(f"layers {' < '.join(order)}: {n_cxx} includes of cxx/ and {n_f} uses of fortran_ref/ point down or sideways")
    return 0


if __name__ == "__main__":
    sys.exit(main())
