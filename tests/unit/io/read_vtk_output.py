#!/usr/bin/env python3
"""Reads a run's vtk/ folder with VTK's own XML readers and checks it (used by vtu_output_test).

Usage: read_vtk_output.py OUT_DIR BLOCK_COUNT WEIGHT_N VTK_INTERVAL
Checks: every frame of blocks.pvd and contacts.pvd opens with vtkXMLUnstructuredGridReader;
model times increase, frames within the stage are VTK_INTERVAL steps apart (the time step from
time_history.csv), the last frame is at the stage end of time_history.csv's last row, and each
frame's TimeValue field is its .pvd time; each block is one polyhedron cell whose volume (vtkCellSizeFilter) is the
block's volume from blocks.csv's size (boxes: the product of the sizes, given via VOLUMES); the
fields have their components; in the last frame the contact normal forces carry WEIGHT_N
(statics, 1e-4), statuses are 0..3 and displacements equal blocks.csv's last rows.
Exit 0 when all holds, 1 with a message otherwise (python3-vtk9 missing included: the test
fails rather than skips; scripts/install-deps.sh installs it).
"""
import csv
import os
import sys
import xml.etree.ElementTree as ET

try:
    import vtk
    from vtk.util.numpy_support import vtk_to_numpy
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
    out = [(float(d.get("timestep")), d.get("file")) for d in root.iter("DataSet")]
    times = [t for t, _ in out]
    if not out or any(b <= a for a, b in zip(times, times[1:])):
        fail(pvd + ": model times must increase: %s" % times)
    return out


def read(path):
    r = vtk.vtkXMLUnstructuredGridReader()
    r.SetFileName(path)
    r.Update()
    if r.GetErrorCode() != 0:
        fail("VTK could not read " + path)
    return r.GetOutput()


def time_value(grid, path):
    a = grid.GetFieldData().GetArray("TimeValue")
    if a is None or a.GetNumberOfTuples() != 1:
        fail(path + ": no TimeValue field")
    return a.GetValue(0)


def check_times(out, pvd_frames, interval):
    """The frames' model times against time_history.csv (an independent writer of the same run)."""
    with open(os.path.join(out, "time_history.csv")) as fh:
        rows = list(csv.DictReader(fh))
    dts = {float(r["time_step_s"]) for r in rows}
    if len(dts) != 1:
        fail("the check assumes a constant time step, time_history.csv has %s" % sorted(dts))
    dt = dts.pop()
    times = [t for t, _ in pvd_frames]
    # Frames every `interval` steps: consecutive times differ by interval * dt (round-off of the
    # summed time, 1e-9 relative).
    for a, b in zip(times[:-2], times[1:-1]):
        if abs((b - a) - interval * dt) > 1e-9 * interval * dt:
            fail("frames %.17g and %.17g are not %d steps of %.17g s apart" % (a, b, interval, dt))
    # The last frame is the stage end, the instant of time_history.csv's last row (12 digits).
    end = float(rows[-1]["time_s"])
    if abs(times[-1] - end) > 1e-11 * end:
        fail("last frame at %.17g s, the stage ends at %.17g s" % (times[-1], end))


def array(data, name, comps):
    a = data.GetArray(name)
    if a is None:
        fail("no array " + name)
    if a.GetNumberOfComponents() != comps:
        fail("%s has %d components, expected %d" % (name, a.GetNumberOfComponents(), comps))
    return a


def main():
    out, nblocks, weight = sys.argv[1], int(sys.argv[2]), float(sys.argv[3])
    interval = int(sys.argv[4])
    volumes = [float(v) for v in os.environ["VOLUMES"].split(",")]
    vtkdir = os.path.join(out, "vtk")
    block_frames = frames(os.path.join(vtkdir, "blocks.pvd"))
    contact_frames = frames(os.path.join(vtkdir, "contacts.pvd"))
    if [t for t, _ in block_frames] != [t for t, _ in contact_frames]:
        fail("blocks.pvd and contacts.pvd list different times")
    if len(block_frames) < 3:
        fail("expected frames every %d steps and at the stage end, found %d"
             % (interval, len(block_frames)))
    check_times(out, block_frames, interval)
    for t, f in block_frames + contact_frames:
        if time_value(read(os.path.join(vtkdir, f)), f) != t:
            fail("%s: TimeValue differs from its .pvd time %.17g" % (f, t))
    for _, f in block_frames:
        g = read(os.path.join(vtkdir, f))
        if g.GetNumberOfCells() != nblocks:
            fail("%s: %d cells, expected %d" % (f, g.GetNumberOfCells(), nblocks))
        for c in range(nblocks):
            if g.GetCellType(c) != vtk.VTK_POLYHEDRON:
                fail("%s: cell %d is not a polyhedron" % (f, c))
        cd = g.GetCellData()
        for name, comps in [("block_id", 1), ("stage", 1), ("displacement", 3), ("velocity", 3),
                            ("rotation", 3), ("angular_velocity", 3)]:
            array(cd, name, comps)
        for name in ("name", "group"):
            a = cd.GetAbstractArray(name)
            if a is None or a.GetNumberOfValues() != nblocks:
                fail("%s: string array %s missing or short" % (f, name))
        sizes = vtk.vtkCellSizeFilter()
        sizes.SetInputData(g)
        sizes.ComputeVolumeOn()
        sizes.Update()
        vol = vtk_to_numpy(sizes.GetOutput().GetCellData().GetArray("Volume"))
        for c in range(nblocks):
            if abs(vol[c] - volumes[c]) > 1e-9 * volumes[c]:
                fail("%s: block %d volume %.12g, expected %.12g" % (f, c, vol[c], volumes[c]))
    for _, f in contact_frames:
        g = read(os.path.join(vtkdir, f))
        pd = g.GetPointData()
        for name, comps in [("block_a", 1), ("block_b", 1), ("normal", 3), ("normal_force", 1),
                            ("shear_force", 3), ("normal_stress", 1), ("closure", 1),
                            ("area", 1), ("status", 1)]:
            if g.GetNumberOfPoints() > 0:
                array(pd, name, comps)
    # Last frame: statics and the CSV rows at the same instant.
    last = read(os.path.join(vtkdir, contact_frames[-1][1]))
    pd = last.GetPointData()
    fn = vtk_to_numpy(pd.GetArray("normal_force"))
    normal = vtk_to_numpy(pd.GetArray("normal"))
    status = vtk_to_numpy(pd.GetArray("status"))
    a = vtk_to_numpy(pd.GetArray("block_a"))
    base_load = sum(fn[i] * normal[i][2] for i in range(len(fn)) if a[i] == 0)
    if abs(base_load - weight) > 1e-4 * weight:
        fail("the base carries %.9g N, the blocks weigh %.9g N" % (base_load, weight))
    if any(s not in (0, 1, 2, 3) for s in status):
        fail("status outside 0..3: %s" % status)
    blocks = read(os.path.join(vtkdir, block_frames[-1][1]))
    disp = vtk_to_numpy(blocks.GetCellData().GetArray("displacement"))
    with open(os.path.join(out, "blocks.csv")) as fh:
        rows = list(csv.DictReader(fh))
    last_level = rows[-1]["level"]
    rows = [r for r in rows if r["level"] == last_level]
    names = blocks.GetCellData().GetAbstractArray("name")
    for i, r in enumerate(rows):
        if names.GetValue(i) != r["block"]:
            fail("block %d is named %s in VTK, %s in blocks.csv" % (i, names.GetValue(i), r["block"]))
        for k, axis in enumerate("xyz"):
            if abs(1e3 * disp[i][k] - float(r["u%s_mm" % axis])) > 1e-9 + 1e-9 * abs(disp[i][k]):
                fail("block %d displacement %s differs from blocks.csv" % (i, axis))
    print("OK: %d frames, %.6g s to %.6g s" % (len(block_frames), block_frames[0][0],
                                               block_frames[-1][0]))


main()
