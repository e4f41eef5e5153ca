#!/usr/bin/python3
"""meshtopo's picture of a mesh with its defects marked, drawn with VTK's
offscreen rendering from an archive file (VTKHDF with the topology arrays
of format 6, README "The archive"): `meshtopo render` writes that file and
runs this script with Debian's python3 (python3-vtk9).

The mesh is neutral grey; the markers have fixed colours (README, `meshtopo
help render`):
  boundary edges (used by one face)           red      lines    255,0,0
  non-manifold edges (3 or more faces)        magenta  lines    255,0,255
  non-manifold vertices                       magenta  points   255,0,255
  corners of rejected faces                   orange   points   255,140,0
  self-intersecting faces                     yellow   faces    255,220,0 (lit)
  faces oriented against a neighbour          blue     faces    70,130,255 (lit)
Lines and points are drawn unlit, in exactly these colours, over the
surface; the faces are shaded. The defect markers (every line and point
but the red boundary edges) are drawn in a second layer over the picture,
so no boundary line and no face hides one: a boundary edge seen along the
same line of sight (the front view of a fin of faces edge-on, where the
boundary runs in front of the non-manifold edge) or a marker behind the
surface would otherwise leave the legend announcing a marker the picture
does not show.

Debian 12's VTK 9.1 renders through GLX only (no EGL or OSMesa build), so
without a display (DISPLAY unset) the script starts a private Xvfb server
of its own (-displayfd picks a free display number), renders into it
offscreen with Mesa's software rasteriser and stops it. The server admits
only holders of a random cookie (xauth, in a file only this user reads),
as xvfb-run does: no other local user can connect to it.

usage: render.py --out PNG [--view VIEW] [--size WxH] [--title TEXT] FILE
exit: 0 written, 2 usage, 3 VTK or Xvfb missing, the file unreadable or the
picture not written (the message says which).
"""
import argparse
import math
import os
import secrets
import shutil
import subprocess
import sys
import tempfile

EXIT_USAGE = 2
EXIT_FAILED = 3

GREY = (0.72, 0.72, 0.72)
BACK_GREY = (0.45, 0.45, 0.45)
BACKGROUND = (0.11, 0.12, 0.15)
TEXT = (0.86, 0.86, 0.86)
RED = (1.0, 0.0, 0.0)
MAGENTA = (1.0, 0.0, 1.0)
ORANGE = (1.0, 140 / 255, 0.0)
YELLOW = (1.0, 220 / 255, 0.0)
BLUE = (70 / 255, 130 / 255, 1.0)

# Bits of PointData/defects (meshtopo/report.h): the kinds that reject a face.
REJECTING = (1 << 0) | (1 << 1)  # out_of_range_index, degenerate_face

# Camera directions (from the mesh's centre towards the camera) and up
# vectors; +Y is up, as in most mesh files.
VIEWS = {
    "iso": ((1.0, 0.8, 1.0), (0.0, 1.0, 0.0)),
    "front": ((0.0, 0.0, 1.0), (0.0, 1.0, 0.0)),
    "back": ((0.0, 0.0, -1.0), (0.0, 1.0, 0.0)),
    "right": ((1.0, 0.0, 0.0), (0.0, 1.0, 0.0)),
    "left": ((-1.0, 0.0, 0.0), (0.0, 1.0, 0.0)),
    "top": ((0.0, 1.0, 0.0), (0.0, 0.0, -1.0)),
    "bottom": ((0.0, -1.0, 0.0), (0.0, 0.0, 1.0)),
}


def fail(message, code=EXIT_FAILED):
    print("render.py: " + message, file=sys.stderr)
    sys.exit(code)


def parse_size(text):
    try:
        w, h = (int(x) for x in text.lower().split("x"))
    except ValueError:
        fail(f"--size: expected WxH, got '{text}'", EXIT_USAGE)
    if not (16 <= w <= 8192 and 16 <= h <= 8192):
        fail(f"--size: {w}x{h}: each side must be 16 to 8192 pixels", EXIT_USAGE)
    return w, h


class VirtualDisplay:
    """A private Xvfb server for the time of the rendering, when there is no
    display; nothing when DISPLAY is set."""

    def __init__(self, width, height):
        self.process = None
        self.auth_dir = None
        if os.environ.get("DISPLAY"):
            return
        if not shutil.which("xauth"):
            fail("no display (DISPLAY is not set) and no xauth to protect a private Xvfb "
                 "(Debian: apt install xauth)")
        self.auth_dir = tempfile.mkdtemp(prefix="meshtopo-render-")
        auth = os.path.join(self.auth_dir, "Xauthority")
        cookie = secrets.token_hex(16)
        self.add_cookie(auth, ":0", cookie)  # the server reads every cookie of the file
        read_fd, write_fd = os.pipe()
        screen = f"{max(width, 640)}x{max(height, 480)}x24"
        try:
            self.process = subprocess.Popen(
                ["Xvfb", "-displayfd", str(write_fd), "-screen", "0", screen, "-nolisten", "tcp",
                 "-nolisten", "unix", "-noreset", "-auth", auth],
                pass_fds=(write_fd,), stdin=subprocess.DEVNULL, stdout=subprocess.DEVNULL,
                stderr=subprocess.DEVNULL)
        except OSError as e:
            os.close(read_fd)
            os.close(write_fd)
            fail(f"no display (DISPLAY is not set) and Xvfb cannot be started: {e.strerror} "
                 "(Debian: apt install xvfb); VTK 9.1 renders through X")
        os.close(write_fd)
        number = b""
        while not number.endswith(b"\n"):
            chunk = os.read(read_fd, 32)
            if not chunk:
                break
            number += chunk
        os.close(read_fd)
        if not number.strip().isdigit():
            self.stop()
            fail("Xvfb started but named no display")
        display = ":" + number.decode().strip()
        self.add_cookie(auth, display, cookie)  # what this process shows to connect
        os.environ["XAUTHORITY"] = auth
        os.environ["DISPLAY"] = display

    def add_cookie(self, auth, display, cookie):
        result = subprocess.run(["xauth", "-q", "-f", auth, "add", display, ".", cookie],
                                stdin=subprocess.DEVNULL, capture_output=True, text=True)
        if result.returncode != 0:
            self.stop()
            fail("xauth cannot write a cookie for the private Xvfb: " + result.stderr.strip())

    def stop(self):
        if self.auth_dir:
            shutil.rmtree(self.auth_dir, ignore_errors=True)
            self.auth_dir = None
        if self.process:
            self.process.terminate()
            try:
                self.process.wait(timeout=10)
            except subprocess.TimeoutExpired:
                self.process.kill()
                self.process.wait()
            self.process = None


def array_values(data, name):
    """The values of a one-component array of data (point or cell data), or
    None when the file has no such array."""
    a = data.GetArray(name)
    if a is None:
        return None
    return [int(a.GetValue(i)) for i in range(a.GetNumberOfTuples())]


def finite_part(vtk, grid):
    """The cells of grid whose corners all have finite coordinates (a vertex
    at NaN or infinity cannot be drawn), and those vertices' flags."""
    points = grid.GetPoints()
    finite = [all(math.isfinite(c) for c in points.GetPoint(i))
              for i in range(grid.GetNumberOfPoints())] if points else []
    if all(finite):
        return grid, finite
    keep = vtk.vtkIdList()
    ids = vtk.vtkIdList()
    for c in range(grid.GetNumberOfCells()):
        grid.GetCellPoints(c, ids)
        if all(finite[ids.GetId(k)] for k in range(ids.GetNumberOfIds())):
            keep.InsertNextId(c)
    extract = vtk.vtkExtractCells()
    extract.SetInputData(grid)
    extract.SetCellList(keep)
    extract.Update()
    return extract.GetOutput(), finite


def marked_points(vtk, grid, flags, finite):
    """A vertex cloud of the points whose flag is set (finite ones only)."""
    points = vtk.vtkPoints()
    for i, on in enumerate(flags):
        if on and finite[i]:
            points.InsertNextPoint(grid.GetPoint(i))
    cloud = vtk.vtkPolyData()
    cloud.SetPoints(points)
    glyphs = vtk.vtkVertexGlyphFilter()
    glyphs.SetInputData(cloud)
    glyphs.Update()
    return glyphs.GetOutput(), points.GetNumberOfPoints()


def feature_edges(vtk, surface, boundary):
    """Edges used by one face (boundary) or by three or more (non-manifold)."""
    edges = vtk.vtkFeatureEdges()
    edges.SetInputData(surface)
    edges.BoundaryEdgesOn() if boundary else edges.BoundaryEdgesOff()
    edges.NonManifoldEdgesOff() if boundary else edges.NonManifoldEdgesOn()
    edges.FeatureEdgesOff()
    edges.ManifoldEdgesOff()
    edges.ColoringOff()
    edges.Update()
    return edges.GetOutput()


def overlay_actor(vtk, data, colour, line_width=0, point_size=0):
    mapper = vtk.vtkPolyDataMapper()
    mapper.SetInputData(data)
    mapper.ScalarVisibilityOff()
    actor = vtk.vtkActor()
    actor.SetMapper(mapper)
    prop = actor.GetProperty()
    prop.SetColor(*colour)
    prop.LightingOff()
    if line_width:
        prop.SetLineWidth(line_width)
    if point_size:
        prop.SetPointSize(point_size)
    return actor


def surface_actor(vtk, surface, cell_colours):
    colours = vtk.vtkUnsignedCharArray()
    colours.SetName("colour")
    colours.SetNumberOfComponents(3)
    for rgb in cell_colours:
        colours.InsertNextTuple3(*(round(255 * c) for c in rgb))
    surface.GetCellData().SetScalars(colours)
    mapper = vtk.vtkPolyDataMapper()
    mapper.SetInputData(surface)
    mapper.SetScalarModeToUseCellData()
    mapper.SetColorModeToDirectScalars()
    mapper.SetResolveCoincidentTopologyToPolygonOffset()
    actor = vtk.vtkActor()
    actor.SetMapper(mapper)
    actor.GetProperty().SetAmbient(0.25)
    actor.GetProperty().SetDiffuse(0.75)
    back = vtk.vtkProperty()
    back.SetColor(*BACK_GREY)
    back.SetAmbient(0.25)
    back.SetDiffuse(0.75)
    actor.SetBackfaceProperty(back)
    return actor


def counted(n, singular, plural=None):
    """'1 boundary edge', '2 boundary edges'."""
    return f"{n} {singular if n == 1 else plural or singular + 's'}"


def place_camera(renderer, bounds, view):
    direction, up = VIEWS[view]
    centre = [(bounds[2 * k] + bounds[2 * k + 1]) / 2 for k in range(3)]
    camera = renderer.GetActiveCamera()
    camera.SetFocalPoint(*centre)
    camera.SetPosition(*(centre[k] + direction[k] for k in range(3)))
    camera.SetViewUp(*up)
    renderer.ResetCamera(bounds)
    camera.Zoom(0.95)


def main():
    ap = argparse.ArgumentParser(description="Draws an archived mesh with its defects marked.")
    ap.add_argument("--out", required=True)
    ap.add_argument("--view", default="iso", choices=sorted(VIEWS))
    ap.add_argument("--size", default="800x600")
    ap.add_argument("--title", default=None)
    ap.add_argument("file")
    args = ap.parse_args()
    width, height = parse_size(args.size)
    try:
        import vtk
    except ImportError:
        fail(f"the vtk module is not installed for {sys.executable} (Debian: apt install "
             "python3-vtk9)")
    vtk.vtkObject.GlobalWarningDisplayOff()

    reader = vtk.vtkHDFReader()
    if not reader.CanReadFile(args.file):
        fail(f"{args.file}: not a VTKHDF file")
    reader.SetFileName(args.file)
    reader.Update()
    grid = reader.GetOutput()
    cell_data, point_data = grid.GetCellData(), grid.GetPointData()
    n_cells, n_points = grid.GetNumberOfCells(), grid.GetNumberOfPoints()
    selfx = array_values(cell_data, "self_intersecting") or [0] * n_cells
    oriented = array_values(cell_data, "orientation_consistent") or [1] * n_cells
    cell_colours = [YELLOW if selfx[c] else BLUE if not oriented[c] else GREY
                    for c in range(n_cells)]
    non_manifold = array_values(point_data, "non_manifold") or [0] * n_points
    rejected = [bits & REJECTING for bits in (array_values(point_data, "defects") or [0] * n_points)]

    # Cell colours travel with the cells through the extraction below.
    colour_ids = vtk.vtkIntArray()
    colour_ids.SetName("colour_id")
    for c in range(n_cells):
        colour_ids.InsertNextValue(c)
    cell_data.AddArray(colour_ids)
    drawable, finite = finite_part(vtk, grid)
    to_surface = vtk.vtkDataSetSurfaceFilter()
    to_surface.SetInputData(drawable)
    to_surface.PassThroughCellIdsOff()
    to_surface.Update()
    surface = to_surface.GetOutput()
    kept_ids = surface.GetCellData().GetArray("colour_id")
    surface_colours = [cell_colours[int(kept_ids.GetValue(i))]
                       for i in range(surface.GetNumberOfCells())] if kept_ids else []

    renderer = vtk.vtkRenderer()
    renderer.SetBackground(*BACKGROUND)
    renderer.AddActor(surface_actor(vtk, surface, surface_colours))
    # Layer 1 keeps layer 0's colours and starts with a cleared depth buffer:
    # its markers land on top of the surface and the boundary lines, tested
    # for depth only against one another.
    markers = vtk.vtkRenderer()
    markers.SetLayer(1)
    markers.SetPreserveColorBuffer(1)
    markers.SetPreserveDepthBuffer(0)
    markers.InteractiveOff()
    scale = max(1.0, min(width, height) / 400)
    boundary = feature_edges(vtk, surface, True)
    non_manifold_edges = feature_edges(vtk, surface, False)
    nm_points, n_nm_points = marked_points(vtk, grid, non_manifold, finite)
    rejected_points, n_rejected = marked_points(vtk, grid, rejected, finite)
    legend = []
    if boundary.GetNumberOfCells():
        renderer.AddActor(overlay_actor(vtk, boundary, RED, line_width=2.5 * scale))
        legend.append("red: " + counted(boundary.GetNumberOfCells(), "boundary edge"))
    if non_manifold_edges.GetNumberOfCells():
        markers.AddActor(overlay_actor(vtk, non_manifold_edges, MAGENTA, line_width=3.5 * scale))
        legend.append("magenta: " + counted(non_manifold_edges.GetNumberOfCells(), "non-manifold edge"))
    if n_nm_points:
        markers.AddActor(overlay_actor(vtk, nm_points, MAGENTA, point_size=9 * scale))
        legend.append("magenta points: " + counted(n_nm_points, "non-manifold vertex", "non-manifold vertices"))
    if n_rejected:
        markers.AddActor(overlay_actor(vtk, rejected_points, ORANGE, point_size=9 * scale))
        legend.append("orange points: " + counted(n_rejected, "corner") + " of rejected faces")
    if any(selfx):
        legend.append("yellow: " + counted(sum(selfx), "self-intersecting face"))
    elif cell_data.GetArray("self_intersecting") is None:
        legend.append("self-intersections not computed")
    if not all(oriented):
        legend.append("blue: " + counted(oriented.count(0), "face") + " oriented against a neighbour")
    if not legend or legend == ["self-intersections not computed"]:
        legend.insert(0, "no defect to mark")
    title = args.title or os.path.basename(args.file)
    text = vtk.vtkTextActor()
    kept = " kept" if n_rejected else ""  # cells are the faces the build kept
    heading = f"{title}: {counted(n_points, 'vertex', 'vertices')}, {counted(n_cells, 'face')}{kept}"
    text.SetInput("\n".join([heading] + legend))
    text.GetTextProperty().SetColor(*TEXT)
    text.GetTextProperty().SetFontSize(round(13 * scale))
    text.GetTextProperty().SetVerticalJustificationToTop()
    text.SetPosition(10, height - 10)
    renderer.AddActor2D(text)

    bounds = surface.GetBounds() if surface.GetNumberOfPoints() else (-1, 1, -1, 1, -1, 1)
    place_camera(renderer, bounds, args.view)
    # The markers are seen through the mesh's camera (its clipping range too).
    markers.SetActiveCamera(renderer.GetActiveCamera())

    display = VirtualDisplay(width, height)
    window = vtk.vtkRenderWindow()
    try:
        window.SetOffScreenRendering(1)
        window.SetMultiSamples(0)
        window.SetNumberOfLayers(2)
        window.AddRenderer(renderer)
        window.AddRenderer(markers)
        window.SetSize(width, height)
        window.Render()
        grab = vtk.vtkWindowToImageFilter()
        grab.SetInput(window)
        grab.ReadFrontBufferOff()
        grab.Update()
        writer = vtk.vtkPNGWriter()
        writer.SetFileName(args.out)
        writer.SetInputConnection(grab.GetOutputPort())
        writer.Write()
        written = writer.GetErrorCode() == 0
        window.Finalize()
    finally:
        del window
        display.stop()
    if not written or not os.path.exists(args.out):
        fail(f"{args.out}: the picture could not be written")
    return 0


if __name__ == "__main__":
    sys.exit(main())
