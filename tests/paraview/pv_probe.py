"""What ParaView reads from an mpm3d output file (run by pvbatch, under xvfb-run -a).

usage: pvbatch pv_probe.py KIND FILE JSON [PNG [COLOUR]]
  KIND   pvd (the ParaView series, PVD reader), xdmf (the HDF5 + XDMF series, Xdmf3 reader
         "T", whose blocks keep their names) or vtu (one .vtu file, the grid)
  JSON   written: {"times": [...], "frames": [{"time": t, "blocks": {name: {...}}}]} for
         the first and the last time, each block with its number of points and cells,
         the cell types present, the points and every point array (full values: the
         decks of the tests are small), and for vtu files the sum of the cell volumes
  PNG    a picture of the last time, coloured by the point array COLOUR; the JSON then
         also holds "png": the number of pixels that differ from the background and the
         picture's size, read back with vtkPNGReader
"""
import json
import sys

from paraview import servermanager as sm
from paraview.simple import (ColorBy, CellSize, ExtractCellsByType, GetActiveViewOrCreate, Hide, PVDReader, ResetCamera,
                             SaveScreenshot, Show, UpdatePipeline, Xdmf3ReaderT, XMLUnstructuredGridReader)
from vtkmodules.vtkIOImage import vtkPNGReader

BACKGROUND = [1.0, 1.0, 1.0]


def block_info(ds, with_volume):
    info = {"points": ds.GetNumberOfPoints(), "cells": ds.GetNumberOfCells()}
    types = set()
    for c in range(ds.GetNumberOfCells()):
        types.add(ds.GetCellType(c))
    info["cell_types"] = sorted(types)
    pts = ds.GetPoints()
    info["xyz"] = [pts.GetPoint(i) for i in range(ds.GetNumberOfPoints())] if pts else []
    pd = ds.GetPointData()
    arrays = {}
    for a in range(pd.GetNumberOfArrays()):
        arr = pd.GetArray(a)
        if arr is None:
            continue
        arrays[arr.GetName()] = [arr.GetComponent(i, 0) for i in range(arr.GetNumberOfTuples())]
    info["arrays"] = arrays
    return info


def blocks(data, with_volume=False):
    """name -> info of each leaf dataset (one leaf: name 'all')."""
    if not data.IsA("vtkCompositeDataSet"):
        return {"all": block_info(data, with_volume)}
    out = {}
    it = data.NewIterator()
    it.InitTraversal()
    while not it.IsDoneWithTraversal():
        ds = it.GetCurrentDataObject()
        name = it.GetCurrentMetaData().Get(data.NAME()) if it.HasCurrentMetaData() else None
        out[name or "block%d" % len(out)] = block_info(ds, with_volume)
        it.GoToNextItem()
    return out


def main():
    kind, path, out = sys.argv[1:4]
    png = sys.argv[4] if len(sys.argv) > 4 else None
    colour = sys.argv[5] if len(sys.argv) > 5 else None
    if kind == "pvd":
        reader = PVDReader(FileName=path)
    elif kind == "xdmf":
        reader = Xdmf3ReaderT(FileName=[path])
    else:
        reader = XMLUnstructuredGridReader(FileName=[path])
    times = list(reader.TimestepValues) if kind != "vtu" else []
    result = {"times": times, "frames": []}
    for t in ([times[0], times[-1]] if times else [0.0]):
        reader.UpdatePipeline(t)
        entry = {"time": t, "blocks": blocks(sm.Fetch(reader))}
        if kind == "vtu":
            size = CellSize(Input=reader)
            size.UpdatePipeline(t)
            vol = sm.Fetch(size).GetCellData().GetArray("Volume")
            entry["volume"] = sum(vol.GetValue(i) for i in range(vol.GetNumberOfTuples()))
        result["frames"].append(entry)
    if png:
        view = GetActiveViewOrCreate("RenderView")
        view.ViewSize = [400, 300]
        view.OrientationAxesVisibility = 0
        view.Background = BACKGROUND
        try:
            view.UseColorPaletteForBackground = 0
        except AttributeError:
            pass
        if times:
            view.ViewTime = times[-1]
        shown = reader
        if kind == "xdmf":  # the particles only: the grid's hexahedra would hide them
            shown = ExtractCellsByType(Input=reader, CellTypes=["Polyvertex"])
        disp = Show(shown, view)
        if kind == "vtu":
            disp.SetRepresentationType("Wireframe")
            disp.AmbientColor = disp.DiffuseColor = [0.0, 0.0, 0.0]
        if colour:
            ColorBy(disp, ("POINTS", colour))
        disp.PointSize = 3
        view.CameraPosition = [1, -2, 1.2]
        view.CameraViewUp = [0, 0, 1]
        ResetCamera(view)
        SaveScreenshot(png, view, ImageResolution=[400, 300])
        r = vtkPNGReader()
        r.SetFileName(png)
        r.Update()
        img = r.GetOutput()
        sc = img.GetPointData().GetScalars()
        bg = [int(round(255 * c)) for c in BACKGROUND]
        nc = sc.GetNumberOfComponents()
        drawn = sum(1 for i in range(sc.GetNumberOfTuples())
                    if any(abs(sc.GetComponent(i, c) - bg[c]) > 2 for c in range(3)))
        result["png"] = {"drawn": drawn, "pixels": sc.GetNumberOfTuples(), "components": nc}
    with open(out, "w") as f:
        json.dump(result, f)


main()
