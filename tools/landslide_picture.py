"""The picture of a landslide run for docs/VERIFICATION.md: one ParaView frame of mpm3d (the
particles as points), coloured by the equivalent plastic strain, seen from the side (along
z, parallel projection): x downstream, y up, the whole 55 m of the grid. Run by pvbatch under xvfb-run:

usage: xvfb-run -a pvbatch tools/landslide_picture.py FRAME.vtu OUT.png TITLE
"""
import sys

from paraview.simple import (ColorBy, GetActiveViewOrCreate, GetColorTransferFunction, GetScalarBar, Render,
                             SaveScreenshot, Show, Text, XMLUnstructuredGridReader)

frame, out, title = sys.argv[1:4]
view = GetActiveViewOrCreate("RenderView")
view.ViewSize = [1000, 230]
view.OrientationAxesVisibility = 1
try:
    view.UseColorPaletteForBackground = 0
except AttributeError:
    pass
view.Background = [1.0, 1.0, 1.0]
reader = XMLUnstructuredGridReader(FileName=[frame])
disp = Show(reader, view)
disp.SetRepresentationType("Points")
disp.PointSize = 3
ColorBy(disp, ("POINTS", "epeff"))
lut = GetColorTransferFunction("epeff")
lut.ApplyPreset("Jet", True)
lut.RescaleTransferFunction(0.0, 2.0)
bar = GetScalarBar(lut, view)
bar.Title = "epeff"
bar.ComponentTitle = ""
bar.TitleColor = bar.LabelColor = [0.0, 0.0, 0.0]
bar.TitleFontSize = bar.LabelFontSize = 14
bar.RangeLabelFormat = "%.1f"
bar.WindowLocation = "Any Location"
bar.Orientation = "Horizontal"
bar.Position = [0.62, 0.68]
bar.ScalarBarLength = 0.3
disp.SetScalarBarVisibility(view, True)
label = Show(Text(Text=title), view)
label.WindowLocation = "Upper Left Corner"
label.FontSize = 14
label.Color = [0.0, 0.0, 0.0]
Render(view)  # the first render resets the camera: set it after
# x downstream, y up, z across: from the side.
view.CameraPosition = [26.0, 3.0, 100.0]
view.CameraFocalPoint = [26.0, 3.0, 2.5]
view.CameraViewUp = [0.0, 1.0, 0.0]
view.CameraParallelProjection = 1
view.CameraParallelScale = 6.0
Render(view)
SaveScreenshot(out, view, ImageResolution=[1000, 230])
