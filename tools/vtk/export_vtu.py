#!/usr/bin/python3
"""An archive file (VTKHDF) rewritten as a VTK XML UnstructuredGrid (.vtu)
with VTK's own reader and writer (Debian's python3-vtk9): the same points,
cells and CellData / PointData arrays (original_face_id and the topology
arrays of format 6), for tools that read .vtu but not VTKHDF. `meshtopo
archive export DIR ID OUT.vtu` runs it on the version it exports.

usage: export_vtu.py ARCHIVE-FILE OUT.vtu
exit: 0 written, 2 usage, 3 VTK missing, the file unreadable or OUT not
written (the message says which).
"""
import os
import sys

EXIT_USAGE = 2
EXIT_FAILED = 3


def fail(message, code=EXIT_FAILED):
    print("export_vtu.py: " + message, file=sys.stderr)
    sys.exit(code)


def main():
    if len(sys.argv) != 3:
        fail("usage: export_vtu.py ARCHIVE-FILE OUT.vtu", EXIT_USAGE)
    source, out = sys.argv[1], sys.argv[2]
    try:
        import vtk
    except ImportError:
        fail(f"the vtk module is not installed for {sys.executable} (Debian: apt install "
             "python3-vtk9)")
    vtk.vtkObject.GlobalWarningDisplayOff()
    reader = vtk.vtkHDFReader()
    if not reader.CanReadFile(source):
        fail(f"{source}: not a VTKHDF file")
    reader.SetFileName(source)
    reader.Update()
    part = out + f".part-{os.getpid()}"
    writer = vtk.vtkXMLUnstructuredGridWriter()
    writer.SetFileName(part)
    writer.SetInputData(reader.GetOutput())
    writer.SetDataModeToAppended()
    writer.SetCompressorTypeToZLib()
    if not writer.Write() or writer.GetErrorCode() != 0:
        if os.path.exists(part):
            os.remove(part)
        fail(f"{out}: could not be written")
    try:
        os.replace(part, out)
    except OSError as e:
        os.remove(part)
        fail(f"{out}: {e.strerror}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
