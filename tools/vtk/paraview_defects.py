"""ParaView colouring of a meshtopo archive file by defect kind: the faces
(or vertices) coloured by the `defects` bitmask as categories, with a legend
naming the kinds of each value, and a screenshot. Run by ParaView's Python:

  xvfb-run -a -s "-screen 0 1280x1024x24" pvbatch paraview_defects.py FILE.hdf --out PNG

(Debian 12's ParaView renders through GLX only, hence the X server; see the
README, "The archive".) In the ParaView GUI (View > Python Shell), with the
archive file opened and selected:

  import sys; sys.path.insert(0, "/usr/share/meshtopo")   # this file's folder
  from paraview_defects import color_by_defect_kind
  color_by_defect_kind(GetActiveSource(), GetActiveView()); Render()

Why a script: VTKHDF stores arrays, not a lookup table, and vtkHDFReader
does not turn HDF5 attributes (the bitmask's `bits`) into anything ParaView
shows, so a file alone can only give ParaView the arrays. It does name them:
the format 8 per-kind arrays `defect_<key>` (0/1) are listed by name in
ParaView's colouring menu with no script. A legend naming the kinds of the
bitmask's values needs the lookup table's categories and annotations, set
here. The names come from the file: for each bitmask value present, the
per-kind arrays that are 1 on a row holding it (the file's verification
guarantees they agree with the bitmask on every row); no table of kinds is
kept here, so the script names whatever kinds the file has. A file of
format 6 or 7 has no per-kind arrays: its values are labelled by bit
number.

Prints one line `RESULT {json}` (association, array, annotations as
[value, label] pairs, colours, picture) for the tests.

usage: pvbatch paraview_defects.py FILE [--out PNG] [--points] [--size WxH] [--view iso|front|...]
"""
import argparse
import json
import sys

# Category colours: no defect grey, then one colour per bitmask value present,
# in ascending order (render.py's marker colours first, then others).
NO_DEFECT = (0.75, 0.75, 0.75)
PALETTE = [(1.0, 0.0, 1.0), (1.0, 140 / 255, 0.0), (70 / 255, 130 / 255, 1.0),
           (1.0, 220 / 255, 0.0), (0.0, 0.75, 0.45), (0.0, 0.8, 0.85), (0.6, 0.35, 0.85),
           (0.85, 0.1, 0.1), (0.55, 0.35, 0.15), (1.0, 0.6, 0.75)]

# Camera directions from the mesh's centre and up vectors, as render.py's.
VIEWS = {
    "iso": ((1.0, 0.8, 1.0), (0.0, 1.0, 0.0)),
    "front": ((0.0, 0.0, 1.0), (0.0, 1.0, 0.0)),
    "back": ((0.0, 0.0, -1.0), (0.0, 1.0, 0.0)),
    "right": ((1.0, 0.0, 0.0), (0.0, 1.0, 0.0)),
    "left": ((-1.0, 0.0, 0.0), (0.0, 1.0, 0.0)),
    "top": ((0.0, 1.0, 0.0), (0.0, 0.0, -1.0)),
    "bottom": ((0.0, -1.0, 0.0), (0.0, 0.0, 1.0)),
}


def defect_categories(data):
    """[(value, label)] for each value of the `defects` array of data (a
    vtkCellData or vtkPointData), ascending; the label joins the names of the
    per-kind arrays defect_<key> that are 1 on a row holding the value."""
    import numpy as np
    from vtkmodules.util.numpy_support import vtk_to_numpy
    mask_array = data.GetArray("defects")
    if mask_array is None:
        raise ValueError("no defects array: not a meshtopo archive file of format 6 or later")
    mask = vtk_to_numpy(mask_array)
    kinds = sorted((data.GetArrayName(i)[len("defect_"):], vtk_to_numpy(data.GetArray(i)))
                   for i in range(data.GetNumberOfArrays())
                   if (data.GetArrayName(i) or "").startswith("defect_"))
    values, rows = np.unique(mask, return_index=True)
    categories = []
    for value, row in zip(values.tolist(), rows.tolist()):
        if kinds:
            names = [key for key, flags in kinds if flags[row]]
        else:  # format 6 or 7: bits only
            names = [f"bit {k}" for k in range(32) if value >> k & 1]
        categories.append((int(value), " + ".join(names) or "no defect"))
    return categories


def source_categories(source, points=False):
    """defect_categories of a ParaView source's cells (or points); raises
    ValueError when it has no defects array."""
    from paraview import servermanager
    source.UpdatePipeline()
    data = servermanager.Fetch(source)
    return defect_categories(data.GetPointData() if points else data.GetCellData())


def color_by_defect_kind(source, view, points=False, categories=None):
    """Colours source's representation in view by its `defects` array (cells,
    or points) as categories, with a scalar bar naming each value's kinds;
    returns the categories [(value, label)] (source_categories unless
    given) and their colours."""
    from paraview import simple
    association = "POINTS" if points else "CELLS"
    if categories is None:
        categories = source_categories(source, points)
    colours, others = [], iter(PALETTE * (1 + len(categories) // len(PALETTE)))
    for value, _ in categories:
        colours.append(NO_DEFECT if value == 0 else next(others))
    display = simple.GetDisplayProperties(source, view)
    if points:
        # Vertex colours would blend across the faces: the surface stays
        # grey and the vertices with a defect are drawn as balls.
        display.ColorArrayName = ["POINTS", ""]
        display.AmbientColor = display.DiffuseColor = list(NO_DEFECT)
        vertices = simple.MaskPoints(Input=source, OnRatio=1, RandomSampling=0,
                                     MaximumNumberofPoints=2**31 - 1, GenerateVertices=1,
                                     SingleVertexPerCell=1)
        marked = simple.Threshold(Input=vertices, Scalars=["POINTS", "defects"],
                                  LowerThreshold=1, UpperThreshold=2**32 - 1,
                                  ThresholdMethod="Between")
        display = simple.Show(marked, view)
        display.Representation = "Points"
        display.RenderPointsAsSpheres = 1
        display.PointSize = 14
    simple.ColorBy(display, (association, "defects"))
    lut = simple.GetColorTransferFunction("defects")
    lut.InterpretValuesAsCategories = 1
    lut.AnnotationsInitialized = 1
    lut.Annotations = [str(x) for value, label in categories for x in (value, label)]
    lut.IndexedColors = [c for colour in colours for c in colour]
    bar = simple.GetScalarBar(lut, view)
    bar.Title = "defect kinds of the " + ("vertices" if points else "faces")
    bar.ComponentTitle = ""
    bar.TitleFontSize = 18
    bar.LabelFontSize = 16
    bar.TitleColor = bar.LabelColor = [0.9, 0.9, 0.9]
    display.SetScalarBarVisibility(view, True)
    return categories, colours


def place_camera(view, bounds, direction, up):
    centre = [(bounds[2 * k] + bounds[2 * k + 1]) / 2 for k in range(3)]
    view.CameraFocalPoint = centre
    view.CameraPosition = [centre[k] + direction[k] for k in range(3)]
    view.CameraViewUp = list(up)
    view.ResetCamera(False)


def main():
    ap = argparse.ArgumentParser(description="Colours a meshtopo archive file by defect kind.")
    ap.add_argument("file")
    ap.add_argument("--out", help="the screenshot to write (PNG)")
    ap.add_argument("--points", action="store_true", help="colour the vertices, not the faces")
    ap.add_argument("--size", default="1024x768")
    ap.add_argument("--view", default="iso", choices=sorted(VIEWS))
    args = ap.parse_args()
    try:
        width, height = (int(x) for x in args.size.lower().split("x"))
    except ValueError:
        print(f"paraview_defects.py: --size: expected WxH, got '{args.size}'", file=sys.stderr)
        return 2
    from paraview import simple
    source, why = None, "ParaView has no reader for it"
    try:
        source = simple.OpenDataFile(args.file)
    except RuntimeError as e:  # no reader, or not readable
        why = str(e).strip()
    if source is None:
        print(f"paraview_defects.py: {args.file}: {why}", file=sys.stderr)
        return 3
    try:
        categories = source_categories(source, args.points)
    except ValueError as e:
        print(f"paraview_defects.py: {args.file}: {e}", file=sys.stderr)
        return 3
    view = simple.GetActiveViewOrCreate("RenderView")
    view.ViewSize = [width, height]
    view.UseColorPaletteForBackground = 0
    view.Background = [0.11, 0.12, 0.15]
    view.OrientationAxesVisibility = 0
    simple.Show(source, view)
    categories, colours = color_by_defect_kind(source, view, args.points, categories)
    direction, up = VIEWS[args.view]
    place_camera(view, source.GetDataInformation().GetBounds(), direction, up)
    if args.out:
        simple.SaveScreenshot(args.out, view, ImageResolution=[width, height])
    lut = simple.GetColorTransferFunction("defects")
    annotations = list(lut.Annotations)
    print("RESULT " + json.dumps({
        "array": "defects",
        "association": "points" if args.points else "cells",
        "categorical": int(lut.InterpretValuesAsCategories),
        "annotations": [[annotations[i], annotations[i + 1]]
                        for i in range(0, len(annotations), 2)],
        "colours": [[round(255 * c) for c in colour] for colour in colours],
        "scalar_bar": bool(simple.GetScalarBar(lut, view).Visibility),
        "picture": args.out}), flush=True)
    return 0


if __name__ == "__main__":
    # sys.exit after rendering makes pvbatch 5.11 tear its X window down in
    # the wrong order (GLXBadContext, exit 1): exit only on errors, which
    # come before the view exists.
    code = main()
    if code:
        sys.exit(code)
