"""Opens an lsi snapshot XDMF in ParaView (pvpython) and renders one frame.

usage: pvpython paraview_snapshots.py FILE.xdmf OUT.png POINTS

Checks what a user sees: the reader finds the time steps, the points block has POINTS points
with the point fields of io/mpm_snapshots.hpp, the barrier block one quadrilateral cell, the
barrier_face block one line segment per face band (2 m in 0.5 m bands) with its face_pressure,
and a frame at the last time renders to a PNG. Exit 1 with a message on any failure.
"""
import sys

from paraview import simple as pv
from paraview import servermanager as sm


def fail(msg):
    print("FAIL: " + msg)
    sys.exit(1)


xdmf, png, points = sys.argv[1], sys.argv[2], int(sys.argv[3])
reader = pv.XDMFReader(FileNames=[xdmf])
reader.UpdatePipelineInformation()
times = list(reader.TimestepValues) if reader.TimestepValues else []
if len(times) < 2:
    fail("expected several time steps, got %r" % (times,))
reader.UpdatePipeline(times[-1])
data = sm.Fetch(reader)
blocks = [data.GetBlock(i) for i in range(data.GetNumberOfBlocks())]
names = [data.GetMetaData(i).Get(data.NAME()) for i in range(data.GetNumberOfBlocks())]
if "mpm_particles" not in names or "barrier" not in names:
    fail("expected blocks mpm_particles and barrier, got %r" % (names,))
particles = blocks[names.index("mpm_particles")]
barrier = blocks[names.index("barrier")]
if particles.GetNumberOfPoints() != points:
    fail("%d points, expected %d" % (particles.GetNumberOfPoints(), points))
fields = {particles.GetPointData().GetArrayName(i)
          for i in range(particles.GetPointData().GetNumberOfArrays())}
for name in ("velocity", "displacement", "id", "material", "mass", "volume", "volumetric_strain",
             "deviatoric_strain", "plastic_work", "stress_xx"):
    if name not in fields:
        fail("point field %s missing (have %s)" % (name, sorted(fields)))
if barrier.GetNumberOfCells() != 1 or barrier.GetNumberOfPoints() != 4:
    fail("barrier: %d cells, %d points" % (barrier.GetNumberOfCells(), barrier.GetNumberOfPoints()))
if "barrier_face" not in names:
    fail("expected a block barrier_face, got %r" % (names,))
face = blocks[names.index("barrier_face")]
if face.GetNumberOfCells() != 4 or face.GetNumberOfPoints() != 5:
    fail("barrier_face: %d cells, %d points" % (face.GetNumberOfCells(), face.GetNumberOfPoints()))
if face.GetCellData().GetArray("face_pressure") is None:
    fail("barrier_face: no cell field face_pressure")
view = pv.CreateRenderView()
view.ViewSize = [640, 360]
view.ViewTime = times[-1]
display = pv.Show(reader, view)
pv.ColorBy(display, ("POINTS", "velocity", "Magnitude"))
pv.ResetCamera(view)
pv.SaveScreenshot(png, view, ImageResolution=[640, 360])
print("rendered %s: %d time steps, %d points" % (png, len(times), points))
