"""The ShockFilters plugin in the real ParaView GUI (paraview, under Xvfb).

Run by CTest as
  xvfb-run -a paraview --dr --plugin-search-paths=PLUGIN_DIR --plugins=ShockFilters
           --script=TestShockFiltersGUI.py
with SHOCK_GUI_OUTPUT set to the folder for the screenshots. The GUI's own
--plugins option loads the plugin at start-up; this script checks that the
three filters are there, applies each one in the GUI session (the Pipeline
Browser and Properties panel track them), saves one screenshot per filter and
checks that each is a real picture (many colours, not the bare background).

ParaView 5.11 does not quit after --script and does not run .py files given to
--test-script, so this script ends the application itself with os._exit(),
whatever happens, with status 0 only when every check passed.
"""
import os
import sys
import traceback

# Inside the GUI, sys.stdout goes to the Output Messages window, which is not
# flushed to the terminal before os._exit(): write to the process's stderr.
TERMINAL = sys.__stderr__


def log(*words):
    TERMINAL.write(" ".join(str(w) for w in words) + "\n")
    TERMINAL.flush()


status = 1
try:
    import numpy as np
    from paraview import simple
    from paraview import servermanager
    from vtkmodules.numpy_interface import dataset_adapter as dsa
    from vtkmodules.vtkIOImage import vtkPNGReader

    output = os.environ.get("SHOCK_GUI_OUTPUT", os.path.join(os.getcwd(), "gui-screenshots"))
    os.makedirs(output, exist_ok=True)
    failures = []
    passed = 0

    def check(condition, message):
        global passed
        if condition:
            passed += 1
        else:
            failures.append(message)
            log("FAIL:", message)

    def picture_stats(path):
        reader = vtkPNGReader()
        reader.SetFileName(path)
        reader.Update()
        image = reader.GetOutput()
        width, height, _ = image.GetDimensions()
        pixels = np.asarray(dsa.WrapDataObject(image).PointData[0])[:, :3].astype(np.int64)
        codes = pixels[:, 0] * 65536 + pixels[:, 1] * 256 + pixels[:, 2]
        background = np.bincount(codes).argmax()
        covered = float(np.mean(codes != background))
        return width, height, len(np.unique(codes)), covered

    for label in ["ImageShockAdvection", "SurfaceShockAdvection", "SurfaceShockSharpen"]:
        check(hasattr(simple, label), "GUI --plugins loaded %s into paraview.simple" % label)
        check(servermanager.ProxyManager().GetPrototypeProxy("filters", label) is not None,
              "GUI proxy definition " + label)

    view = simple.GetActiveViewOrCreate("RenderView")
    view.OrientationAxesVisibility = 0

    def shoot(name, proxy, array, association, camera, component=None):
        for source in simple.GetSources().values():
            simple.Hide(source, view)
        simple.SetActiveSource(proxy)
        display = simple.Show(proxy, view)
        simple.ColorBy(display, (association, array) + ((component,) if component else ()))
        display.RescaleTransferFunctionToDataRange(True, False)
        camera(view)
        simple.Render(view)
        path = os.path.join(output, name + ".png")
        if os.path.exists(path):
            os.remove(path)
        simple.SaveScreenshot(path, view, ImageResolution=[640, 480])
        check(os.path.exists(path), name + ": screenshot written")
        if os.path.exists(path):
            width, height, colours, covered = picture_stats(path)
            log("%s: %dx%d, %d colours, %.0f%% covered" % (name, width, height, colours, 100 * covered))
            check((width, height) == (640, 480), name + ": size %dx%d" % (width, height))
            check(colours > 100, name + ": %d distinct colours" % colours)
            check(covered > 0.2, name + ": %.2f of the picture differs from the background" % covered)

    def front(v):
        simple.ResetCamera(v)

    def oblique(v):
        v.CameraPosition = [2.5, 2.0, 3.0]
        v.CameraFocalPoint = [0, 0, 0]
        v.CameraViewUp = [0, 1, 0]
        simple.ResetCamera(v)

    def close(v):
        oblique(v)
        v.GetActiveCamera().Dolly(1.4)

    # Image Shock Advection on a Wavelet, applied in the GUI session.
    wavelet = simple.Wavelet(WholeExtent=[0, 127, 0, 127, 0, 0])
    image = simple.ImageShockAdvection(Input=wavelet, FlowTime=512.0)
    check(list(image.InputArray) == ["POINTS", "RTData"], "GUI image: default input array RTData")
    image.UpdatePipeline()
    shoot("gui-image-shock-advection", image, "RTData", "POINTS", front)

    # Surface Shock Advection of a colour pattern on a sphere.
    sphere = simple.Sphere(ThetaResolution=128, PhiResolution=64)
    colour = simple.Calculator(Input=sphere, ResultArrayName="Pattern",
                               Function="tanh(12*sin(9*coordsX)*sin(9*coordsY)*sin(9*coordsZ))")
    surface = simple.SurfaceShockAdvection(Input=colour, FlowTime=1024.0)
    check(list(surface.InputArray) == ["POINTS", "Pattern"], "GUI surface: default input array Pattern")
    surface.UpdatePipeline()
    shoot("gui-surface-shock-advection", surface, "Pattern", "POINTS", close)

    # Surface Shock Sharpen of a rounded box.
    box = simple.Box()
    rounded = simple.Smooth(Input=simple.Subdivide(Input=simple.Triangulate(Input=simple.Clean(Input=box)),
                                                   NumberofSubdivisions=4), NumberofIterations=40)
    sharpen = simple.SurfaceShockSharpen(Input=rounded, GenerateSharpenedNormals=1)
    sharpen.UpdatePipeline()
    sharpen.UpdatePropertyInformation()
    check(sharpen.LastSolverIterations == 25, "GUI sharpen: measurements readable")
    shoot("gui-surface-shock-sharpen", sharpen, "ShockNormals", "CELLS", oblique, "X")

    log("%d passed, %d failed" % (passed, len(failures)))
    status = 0 if not failures else 1
except BaseException:  # anything at all: report and leave, never hang the GUI
    log(traceback.format_exc())
    status = 1
finally:
    TERMINAL.flush()
    os._exit(status)
