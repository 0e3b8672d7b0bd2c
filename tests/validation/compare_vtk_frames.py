#!/usr/bin/env python3
"""Compares the VTK frames of a run on several processes with those of one process, through VTK's
own XML readers (used by mpi_vtk_test and mpi_run_test).

Usage: compare_vtk_frames.py ONE_PROCESS_OUT OTHER_OUT PROCESSES
ONE_PROCESS_OUT/vtk holds whole frames (.vtu); OTHER_OUT/vtk, for PROCESSES > 1, one .pvtu index
per frame naming PROCESSES pieces NAME_pK.vtu (K = 0 .. PROCESSES-1), for PROCESSES = 1 whole
frames too; PROCESSES = 0: either, each index with its own count of pieces (a run restarted on
another number of processes).
Each frame is opened as ParaView opens it: the file its .pvd lists, with the reader of its kind
(vtkXMLUnstructuredGridReader for .vtu, vtkXMLPUnstructuredGridReader for .pvtu).
Checks: blocks.pvd and contacts.pvd list the same model times; each frame has the same number
of points and cells and, after sorting the cells by block index (contacts by their blocks' pair),
the same cell types, the same point coordinates and the same values of every data array, to 0
difference (the block states of a distributed run are bit-identical to one process's); and each
frame's TimeValue (in every piece) is its .pvd time.
Exit 0 when all holds, 1 with a message otherwise (python3-vtk9 missing included).
"""
import os
import sys
import xml.etree.ElementTree as ET

try:
    import vtk
except ImportError:
    print("FAIL: VTK's Python module cannot be imported by %s: install python3-vtk9 "
          "(scripts/install-deps.sh)" % sys.executable)
    sys.exit(1)


def fail(msg):
    print("FAIL: " + msg)
    sys.exit(1)


def frames(pvd):
    root = ET.parse(pvd).getroot()
    if root.get("type") != "Collection":
        fail(pvd + " is not a VTK collection")
    return [(float(d.get("timestep")), d.get("file")) for d in root.iter("DataSet")]


def read(path, processes):
    if path.endswith(".pvtu"):
        root = ET.parse(path).getroot()
        pieces = [p.get("Source") for p in root.iter("Piece")]
        stem = os.path.basename(path)[:-len(".pvtu")]
        count = processes if processes > 0 else len(pieces)
        expected = ["%s_p%d.vtu" % (stem, k) for k in range(max(count, 2))]
        if pieces != expected:
            fail("%s names the pieces %s, expected %s" % (path, pieces, expected))
        for p in pieces:
            if not os.path.isfile(os.path.join(os.path.dirname(path), p)):
                fail("%s: piece %s missing" % (path, p))
        r = vtk.vtkXMLPUnstructuredGridReader()
    else:
        if processes > 1 or (processes == 1 and path.endswith(".pvtu")):
            fail("%s: a run on %d processes should write a .pvtu index" % (path, processes))
        r = vtk.vtkXMLUnstructuredGridReader()
    r.SetFileName(path)
    r.Update()
    if r.GetErrorCode() != 0:
        fail("VTK could not read " + path)
    return r.GetOutput()


def piece_times(path):
    """TimeValue of each file of a frame: the .vtu, or every piece of a .pvtu."""
    files = [path]
    if path.endswith(".pvtu"):
        files = [os.path.join(os.path.dirname(path), p.get("Source"))
                 for p in ET.parse(path).getroot().iter("Piece")]
    out = []
    for f in files:
        r = vtk.vtkXMLUnstructuredGridReader()
        r.SetFileName(f)
        r.Update()
        a = r.GetOutput().GetFieldData().GetArray("TimeValue")
        if a is None or a.GetNumberOfTuples() != 1:
            fail(f + ": no TimeValue field")
        out.append(a.GetValue(0))
    return out


def values(array, i):
    """Tuple i of a numeric or string array."""
    if isinstance(array, vtk.vtkStringArray):
        return (array.GetValue(i),)
    return tuple(array.GetComponent(i, k) for k in range(array.GetNumberOfComponents()))


def cell_points(grid, c):
    ids = grid.GetCell(c).GetPointIds()
    return [grid.GetPoint(ids.GetId(k)) for k in range(ids.GetNumberOfIds())]


def polyhedron_faces(grid, c):
    """The faces of a polyhedron cell as coordinates (point ids differ between pieces)."""
    cell = grid.GetCell(c)
    if cell.GetCellType() != vtk.VTK_POLYHEDRON:
        return []
    out = []
    for f in range(cell.GetNumberOfFaces()):
        face = cell.GetFace(f)
        out.append([face.GetPoints().GetPoint(k) for k in range(face.GetNumberOfPoints())])
    return out


def compare(ref, other, data_of, key, what):
    if ref.GetNumberOfPoints() != other.GetNumberOfPoints():
        fail("%s: %d points, one process %d" % (what, other.GetNumberOfPoints(),
                                               ref.GetNumberOfPoints()))
    if ref.GetNumberOfCells() != other.GetNumberOfCells():
        fail("%s: %d cells, one process %d" % (what, other.GetNumberOfCells(),
                                              ref.GetNumberOfCells()))
    rd, od = data_of(ref), data_of(other)
    names = sorted(rd.GetAbstractArray(i).GetName() for i in range(rd.GetNumberOfArrays()))
    other_names = sorted(od.GetAbstractArray(i).GetName() for i in range(od.GetNumberOfArrays()))
    if names != other_names:
        fail("%s: arrays %s, one process %s" % (what, other_names, names))
    ro = sorted(range(ref.GetNumberOfCells()), key=lambda c: key(ref, rd, c))
    oo = sorted(range(other.GetNumberOfCells()), key=lambda c: key(other, od, c))
    for r, o in zip(ro, oo):
        if ref.GetCellType(r) != other.GetCellType(o):
            fail("%s: cell %d is of another type" % (what, r))
        if cell_points(ref, r) != cell_points(other, o):
            fail("%s: the points of cell %s differ" % (what, key(ref, rd, r)))
        if polyhedron_faces(ref, r) != polyhedron_faces(other, o):
            fail("%s: the faces of cell %s differ" % (what, key(ref, rd, r)))
        for n in names:
            a, b = values(rd.GetAbstractArray(n), r), values(od.GetAbstractArray(n), o)
            if a != b:
                fail("%s: %s of cell %s is %s, one process %s" % (what, n, key(ref, rd, r), b, a))


def block_key(grid, data, c):
    return data.GetArray("block_id").GetValue(c)


def contact_key(grid, data, c):
    return (data.GetArray("block_a").GetValue(c), data.GetArray("block_b").GetValue(c))


def check_vertex_layout(grid, what):
    """Contacts carry point data and compare() reads tuple c for cell c: each vertex cell c must
    be point c (the writer's layout)."""
    for c in range(grid.GetNumberOfCells()):
        if grid.GetCell(c).GetPointId(0) != c:
            fail("%s: vertex cell %d is not point %d" % (what, c, c))


def main():
    ref_dir, other_dir = os.path.join(sys.argv[1], "vtk"), os.path.join(sys.argv[2], "vtk")
    processes = int(sys.argv[3])
    count = 0
    for kind in ("blocks", "contacts"):
        ref_frames = frames(os.path.join(ref_dir, kind + ".pvd"))
        other_frames = frames(os.path.join(other_dir, kind + ".pvd"))
        if [t for t, _ in ref_frames] != [t for t, _ in other_frames]:
            fail("%s.pvd: model times %s, one process %s"
                 % (kind, [t for t, _ in other_frames], [t for t, _ in ref_frames]))
        if not ref_frames:
            fail("%s.pvd lists no frame" % kind)
        for (t, rf), (_, of) in zip(ref_frames, other_frames):
            ref = read(os.path.join(ref_dir, rf), 1)
            other_path = os.path.join(other_dir, of)
            other = read(other_path, processes)
            if any(v != t for v in piece_times(other_path)):
                fail("%s: TimeValue differs from its .pvd time %.17g" % (of, t))
            if kind == "blocks":
                compare(ref, other, lambda g: g.GetCellData(), block_key, of)
            else:
                check_vertex_layout(ref, rf)
                check_vertex_layout(other, of)
                compare(ref, other, lambda g: g.GetPointData(), contact_key, of)
            count += 1
    print("OK: %d frames equal to one process's" % count)


main()
