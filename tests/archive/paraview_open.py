"""Run by pvbatch (ParaView's Python) from archive_paraview_check.py: opens
each file named in the JSON list given by its name alone, with
paraview.simple.OpenDataFile (the reader ParaView picks by the name, as
File > Open does), and prints one JSON object per file: the reader's XML
name, the numbers of points and cells and, per CellData and PointData
array, its number of tuples and components and VTK type.

usage: pvbatch paraview_open.py LIST.json
"""
import json
import sys

from paraview import servermanager
from paraview.simple import Delete, OpenDataFile


def arrays(data):
    return {data.GetArrayName(i): [data.GetArray(i).GetNumberOfTuples(),
                                   data.GetArray(i).GetNumberOfComponents(),
                                   data.GetArray(i).GetDataType()]
            for i in range(data.GetNumberOfArrays())}


def main():
    with open(sys.argv[1], encoding="utf-8") as f:
        paths = json.load(f)
    for path in paths:
        result = {"path": path}
        try:
            reader = OpenDataFile(path)
            result["reader"] = reader.GetXMLName()
            reader.UpdatePipeline()
            data = servermanager.Fetch(reader)
            result["points"] = data.GetNumberOfPoints()
            result["cells"] = data.GetNumberOfCells()
            result["cell_data"] = arrays(data.GetCellData())
            result["point_data"] = arrays(data.GetPointData())
            Delete(reader)
        except Exception as e:  # reported per file, the others still run
            result["error"] = str(e)
        print("RESULT " + json.dumps(result), flush=True)


main()
