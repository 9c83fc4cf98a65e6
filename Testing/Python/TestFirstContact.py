"""First contact: the shock filters written the way a newcomer writes them.

Runs unchanged in pvpython, pvbatch, `mpirun -np 2 pvbatch --mpi` and the
GUI (`paraview --script`), from a folder holding the files a user brings
(MakeUserFixtures.py: photo.png, scan.ply). Environment:
  SHOCK_PLUGIN  the plugin library;  SHOCK_OUTPUT  where SaveData writes;
  SHOCK_IN_GUI  1 inside the GUI (the script then ends the application).

The user's lines come first in each block: one-liners with defaults, no
InputArray, no UpdatePipeline() before creating a filter, another source
active, Input= and positional inputs, files opened with OpenDataFile. The
checks after them read what a user would look at: the array the filter
chose, the errors ParaView reported, and the files SaveData wrote
(CompareFirstContact.py compares the parallel files with the serial ones and
checks that the filters changed the data).
"""
import os
import sys
import traceback

TERMINAL = sys.__stderr__  # inside the GUI, sys.stdout is the Output Messages window
IN_GUI = os.environ.get("SHOCK_IN_GUI") == "1"
failures = []
passed = 0


def log(*words):
    TERMINAL.write(" ".join(str(w) for w in words) + "\n")
    TERMINAL.flush()


def check(condition, message):
    global passed
    if condition:
        passed += 1
    else:
        failures.append(message)
        log("FAIL:", message)


status = 1
try:
    from paraview.simple import *  # noqa: F401,F403
    from vtkmodules.util.misc import calldata_type
    from vtkmodules.util.vtkConstants import VTK_STRING
    from vtkmodules.vtkCommonCore import vtkOutputWindow

    errors = []

    @calldata_type(VTK_STRING)
    def on_error(caller, event, text):
        errors.append(text)

    vtkOutputWindow.GetInstance().AddObserver("ErrorEvent", on_error)
    output = os.environ["SHOCK_OUTPUT"]
    os.makedirs(output, exist_ok=True)

    def saved(name, proxy):
        """SaveData as a user does; parallel formats so MPI pieces are kept."""
        del errors[:]
        SaveData(os.path.join(output, name), proxy=proxy)
        check(not errors, "%s: no errors, got %s" % (name, errors))

    # ---- the user's script -------------------------------------------------
    LoadPlugin(os.environ["SHOCK_PLUGIN"], ns=globals())

    # One-liners with defaults.
    image = ImageShockAdvection(Input=Wavelet())
    check(list(image.InputArray) == ["POINTS", "RTData"], "Input=Wavelet(): RTData, got %s" % image.InputArray)
    saved("image.pvti", image)

    positional = ImageShockAdvection(Wavelet(), FlowTime=256)
    check(list(positional.InputArray) == ["POINTS", "RTData"], "positional: RTData, got %s" % positional.InputArray)
    saved("positional.pvti", positional)

    surface = SurfaceShockAdvection(Input=Elevation(Input=Sphere(ThetaResolution=64, PhiResolution=64)))
    check(list(surface.InputArray) == ["POINTS", "Elevation"], "surface: Elevation, got %s" % surface.InputArray)
    saved("surface.pvtp", surface)

    # Another source active, whose arrays are known (a PLY with colours).
    wavelet = Wavelet()
    scan = OpenDataFile("scan.ply")
    scan.UpdatePipeline()
    other = ImageShockAdvection(Input=wavelet)
    check(list(other.InputArray) == ["POINTS", "RTData"], "another source active: RTData, got %s" % other.InputArray)
    saved("other_active.pvti", other)

    # Files: a PLY with colours, a PNG photo.
    colours = SurfaceShockAdvection(Input=scan, FlowTime=4096)
    check(list(colours.InputArray) == ["POINTS", "RGB"], "scan.ply: RGB, got %s" % colours.InputArray)
    saved("colours.pvtp", colours)

    photo_file = OpenDataFile("photo.png")
    photo = ImageShockAdvection(Input=photo_file, FlowTime=1024)
    photo_file.UpdatePipeline()
    photo_arrays = [["POINTS", a] for a in photo_file.PointData.keys()] + \
        [["CELLS", a] for a in photo_file.CellData.keys()]
    check(list(photo.InputArray) in photo_arrays, "photo.png: one of %s, got %s" % (photo_arrays, photo.InputArray))
    saved("photo.pvti", photo)

    # An array chosen by the user is kept, before or after Input=.
    normals = SurfaceShockAdvection(Input=Elevation(Input=Sphere()), InputArray=["POINTS", "Normals"])
    check(list(normals.InputArray) == ["POINTS", "Normals"], "InputArray= kept, got %s" % normals.InputArray)
    chosen_first = ImageShockAdvection(InputArray=["POINTS", "RTData"], Input=Wavelet())
    check(list(chosen_first.InputArray) == ["POINTS", "RTData"], "InputArray before Input kept, got %s"
          % chosen_first.InputArray)

    # A mesh with normals and no scalars: normals are no signal to sharpen, so no
    # default array (the filter asks for one, as the VTK class does).
    only_normals = SurfaceShockAdvection(Input=GenerateSurfaceNormals(Input=Sphere()))
    check(list(only_normals.InputArray)[1] == "", "only Normals: no default array, got %s" % only_normals.InputArray)
    # Normals beside another array: that array.
    normals_and_heat = SurfaceShockAdvection(Input=GenerateSurfaceNormals(Input=Elevation(Input=Sphere())))
    check(list(normals_and_heat.InputArray) == ["POINTS", "Elevation"], "Normals and Elevation: Elevation, got %s"
          % normals_and_heat.InputArray)

    # The colours changed (serial runs; the MPI run is compared file by file;
    # the images are compared with the Wavelet there; Elevation is linear on
    # the sphere, a ramp the shock filter leaves nearly as it is).
    if servermanager.vtkProcessModule.GetProcessModule().GetNumberOfLocalPartitions() == 1:
        from vtkmodules.numpy_interface import dataset_adapter as dsa
        for proxy, name in ((colours, "RGB"),):
            before = dsa.WrapDataObject(servermanager.Fetch(proxy.Input)).PointData[name]
            after = dsa.WrapDataObject(servermanager.Fetch(proxy)).PointData[name]
            check(abs(after.astype(float) - before.astype(float)).max() > 0.01 * (before.max() - before.min()),
                  "%s changed by %s" % (name, proxy.GetXMLLabel()))

    log("%d passed, %d failed" % (passed, len(failures)))
    status = 0 if not failures else 1
except BaseException:  # report anything, and never leave the GUI hanging
    log(traceback.format_exc())
    status = 1
finally:
    TERMINAL.flush()
    if IN_GUI:
        os._exit(status)
# On success the script just ends, so that pvbatch finalizes MPI and releases
# the other process; on failure a non-zero exit makes mpirun stop them all.
if status:
    sys.exit(status)
