"""The OFF reader and writer of the plugin (Plugin/ShockReaders.xml) as a
ParaView user meets them: File > Open picks the reader by the extension, File >
Save Data the writer; a damaged file gives an error, not a crash.

    pvpython TestShockReadersPlugin.py PLUGIN WORKDIR
"""
import os
import sys

from paraview import servermanager
from paraview.simple import LoadPlugin, OpenDataFile, SaveData

plugin, work = sys.argv[1], sys.argv[2]
LoadPlugin(plugin, ns=globals())
os.makedirs(work, exist_ok=True)

# A tetrahedron with vertex colours, outward faces.
tetra = os.path.join(work, "tetra.off")
with open(tetra, "w") as f:
    f.write("COFF\n# a tetrahedron\n4 4 0\n0 0 0 255 0 0\n1 0 0 0 255 0\n0 1 0 0 0 255\n0 0 1 255 255 255\n"
            "3 0 2 1\n3 0 1 3\n3 1 2 3\n3 0 3 2\n")
reader = OpenDataFile(tetra)
assert reader is not None and reader.GetXMLName() == "OFFReader", reader
reader.UpdatePipeline()
info = reader.GetDataInformation()
assert info.GetNumberOfPoints() == 4 and info.GetNumberOfCells() == 4, (info.GetNumberOfPoints(), info.GetNumberOfCells())
assert "Colors" in reader.PointData.keys(), reader.PointData.keys()
assert list(reader.PointData["Colors"].GetRange(0)) == [0.0, 255.0]

copy = os.path.join(work, "copy.off")
if os.path.exists(copy):
    os.remove(copy)
SaveData(copy, proxy=reader)
with open(copy) as f:
    text = f.read()
assert text.startswith("COFF\n4 4 0\n0 0 0 255 0 0\n"), text
back = OpenDataFile(copy)
back.UpdatePipeline()
mesh = servermanager.Fetch(back)
assert mesh.GetNumberOfPoints() == 4 and mesh.GetNumberOfPolys() == 4
assert [mesh.GetPoint(3)[c] for c in range(3)] == [0.0, 0.0, 1.0]

damaged = os.path.join(work, "damaged.off")
with open(damaged, "w") as f:
    f.write("OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 9\n")
broken = OpenDataFile(damaged)
broken.UpdatePipeline()
assert broken.GetDataInformation().GetNumberOfPoints() == 0
print("OK: OFF reader and writer")
