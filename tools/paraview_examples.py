"""The pictures of docs/examples/ (docs/DECK_FORMAT.md, "Animation files"): the coarse Taylor
bar as ParaView shows mpm3d's two animation outputs, coloured by the axial velocity vz.
Run by tools/paraview_examples.sh (pvbatch under xvfb-run).

usage: pvbatch paraview_examples.py RUN_DIR OUT_DIR
  RUN_DIR holds taylor_anim.pvd (deck keyword para) and taylor_anim.xdmf (--hdf5)
  OUT_DIR gets taylor_pvd.png and taylor_xdmf.png (the last time of each series)"""
import os
import sys

from paraview.simple import (ColorBy, ExtractCellsByType, GetActiveViewOrCreate, GetColorTransferFunction,
                             GetScalarBar, Hide, PVDReader, Render, ResetCamera, SaveScreenshot, Show, Text,
                             Xdmf3ReaderT)

run, out = sys.argv[1:3]
SIZE = [480, 400]
LABELS = []


def view_for(t):
    v = GetActiveViewOrCreate("RenderView")
    v.ViewSize = SIZE
    v.OrientationAxesVisibility = 0
    try:
        v.UseColorPaletteForBackground = 0
    except AttributeError:
        pass
    v.Background = [1.0, 1.0, 1.0]
    v.ViewTime = t
    return v


def colour_by_vz(disp, view, title):
    ColorBy(disp, ("POINTS", "vz"))
    lut = GetColorTransferFunction("vz")
    lut.ApplyPreset("Jet", True)
    lut.RescaleTransferFunction(-190.0, 0.0)
    bar = GetScalarBar(lut, view)
    bar.Title = "vz (m/s)"
    bar.ComponentTitle = ""
    bar.TitleColor = bar.LabelColor = [0.0, 0.0, 0.0]
    bar.TitleFontSize = bar.LabelFontSize = 14
    bar.RangeLabelFormat = "%.0f"
    bar.WindowLocation = "Any Location"
    bar.Position = [0.78, 0.12]
    bar.ScalarBarLength = 0.6
    label = Text(Text=title)
    shown = Show(label, view)
    shown.WindowLocation = "Upper Left Corner"
    shown.FontSize = 14
    shown.Color = [0.0, 0.0, 0.0]
    LABELS.append(label)
    disp.SetScalarBarVisibility(view, True)
    disp.PointSize = 2


def camera(view):
    view.CameraPosition = [30.0, -60.0, 25.0]
    view.CameraFocalPoint = [0.0, 0.0, 9.0]
    view.CameraViewUp = [0.0, 0.0, 1.0]
    ResetCamera(view)


# The .pvd series: the particles of the last frame, one vertex each.
pvd = PVDReader(FileName=os.path.join(run, "taylor_anim.pvd"))
t = pvd.TimestepValues[-1]
view = view_for(t)
d = Show(pvd, view)
colour_by_vz(d, view, "taylor_anim.pvd, t = %.3f ms" % t)
camera(view)
SaveScreenshot(os.path.join(out, "taylor_pvd.png"), view, ImageResolution=SIZE)
Hide(pvd, view)
for label in LABELS:
    Hide(label, view)

# The XDMF series: its two blocks, the particles (coloured) and the background grid (outline).
x = Xdmf3ReaderT(FileName=[os.path.join(run, "taylor_anim.xdmf")])
t = x.TimestepValues[-1]
view.ViewTime = t
parts = ExtractCellsByType(Input=x, CellTypes=["Polyvertex"])
grid = ExtractCellsByType(Input=x, CellTypes=["Hexahedron"])
d = Show(parts, view)
colour_by_vz(d, view, "taylor_anim.xdmf, t = %.3f ms\nparticles + grid (outline)" % t)
g = Show(grid, view)
g.SetRepresentationType("Outline")
g.AmbientColor = g.DiffuseColor = [0.3, 0.3, 0.3]
camera(view)
Render(view)
SaveScreenshot(os.path.join(out, "taylor_xdmf.png"), view, ImageResolution=SIZE)
