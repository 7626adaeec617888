#!/usr/bin/python3
"""Check the H5MD 1.1 layout of a grano result file with h5py.

The file is written by `test_h5md --sample FILE` (5 frames of 40 grains, 7
observable samples, a field, a result table). Exits 77 (skipped) when h5py
is missing. With --paraview, opens the XDMF sidecar in ParaView's XDMF
reader instead (pvpython; skipped when absent).
Usage: check_h5md.py [--paraview] [TEST_H5MD_EXE]
"""
import os
import shutil
import subprocess
import sys
import tempfile
import xml.etree.ElementTree as ET

try:
    import h5py
    import numpy as np
except ImportError:
    print("h5py is not available to this python: skipped")
    sys.exit(77)

NFR, NP, NOBS = 5, 40, 7
SCENE = ("# test scene\n[domain]\nwidth = 20\nheight = 10\n"
         "# accents survive: caída, orificio\n")
OBS = ["n_mobile", "ekin_trans", "ekin_rot", "epot_grav", "temperature",
       "momentum", "outflow", "wall_pressure", "max_overlap"]

failures = []


def check(cond, what):
    print(("ok      " if cond else "FAILED  ") + what)
    if not cond:
        failures.append(what)


def addr(obj):
    return h5py.h5o.get_info(obj.id).addr


def fixed_str_attr(obj, name):
    info = h5py.check_string_dtype(obj.attrs.get_id(name).dtype)
    if info is None or info.length is None:
        return None
    v = obj.attrs[name]
    if isinstance(v, np.ndarray):
        return [x.decode() for x in v]
    return v.decode()


def check_file(path):
    f = h5py.File(path, "r")
    h = f["h5md"]
    check(list(h.attrs["version"]) == [1, 1] and h.attrs["version"].dtype.kind == "i",
          "h5md/version is the integer pair [1, 1]")
    check(fixed_str_attr(h["author"], "name") == "Test Author", "h5md/author name")
    check(fixed_str_attr(h["creator"], "name") == "grano", "h5md/creator name is grano")
    check(fixed_str_attr(h["creator"], "version") == "0.1.0-test", "h5md/creator version")
    u = h["modules/units"]
    check(list(u.attrs["version"]) == [1, 0] and fixed_str_attr(u, "system") is not None,
          "h5md/modules/units declares its version and unit system")

    t = f["particles/trajectory"]
    pos = t["position"]
    check(pos["value"].shape == (NFR, NP, 2) and pos["value"].dtype == np.float64,
          "position/value is float64 (frames, N, 2)")
    check(pos["step"].shape == (NFR,) and pos["step"].dtype.kind == "i",
          "position/step is integer (frames,)")
    check(pos["time"].shape == (NFR,) and pos["time"].dtype == np.float64,
          "position/time is float64 (frames,)")
    check(list(pos["step"][()]) == [100 * k for k in range(NFR)] and
          list(pos["time"][()]) == [0.5 * k for k in range(NFR)], "frame steps and times")
    check(pos["value"].chunks is not None and pos["value"].maxshape[0] is None,
          "position/value is chunked and extendible")

    box = t["box"]
    check(int(box.attrs["dimension"]) == 2, "box dimension 2")
    check(fixed_str_attr(box, "boundary") == ["periodic", "none"],
          "box boundary per axis (fixed-length strings)")
    edges = box["edges/value"]
    check(edges.shape == (NFR, 2) and np.all(edges[()] == [20.0, 10.0]), "box edges [width, height]")

    shared = ["velocity", "omega", "flags", "box/edges"]
    for name in shared:
        g = t[name]
        same = all(addr(g[k]) == addr(pos[k]) for k in ("step", "time"))
        check(same, f"{name} step/time are hard links to position's (same object)")
    check(h5py.h5o.get_info(pos["step"].id).rc == 1 + len(shared),
          "position/step has one link per element sharing it")

    check(t["velocity/value"].shape == (NFR, NP, 2), "velocity/value (frames, N, 2)")
    check(t["omega/value"].shape == (NFR, NP), "omega/value (frames, N)")
    check(t["flags/value"].shape == (NFR, NP) and t["flags/value"].dtype == np.uint32,
          "flags/value uint32 (frames, N)")
    gone = t["flags/value"][()] & 4
    check(not gone[0].any() and gone[-1].any(), "grains that left carry the GONE flag")
    for name, kind in [("radius", "f"), ("mass", "f"), ("inertia", "f"), ("species", "i"),
                       ("id", "i")]:
        d = t[name]
        check(isinstance(d, h5py.Dataset) and d.shape == (NP,) and d.dtype.kind == kind,
              f"{name} is a time-independent ({NP},) dataset")
    check(list(t["id"][:3]) == [1000, 1001, 1002], "ids stored as given")

    units = {"position/value": "d", "velocity/value": "d tau-1", "omega/value": "tau-1",
             "flags/value": "1", "radius": "d", "mass": "m", "inertia": "m d+2",
             "species": "1", "id": "1", "position/time": "tau", "box/edges/value": "d"}
    for p, want in units.items():
        check(fixed_str_attr(t[p], "unit") == want, f"trajectory/{p} unit '{want}' (fixed-length string, H5MD 1.1)")

    o = f["observables"]
    check(sorted(o.keys()) == sorted(OBS), "observables: " + ", ".join(OBS))
    for name in OBS:
        g = o[name]
        shape = (NOBS, 2) if name == "momentum" else (NOBS,)
        check(g["value"].shape == shape and g["step"].shape == (NOBS,),
              f"observables/{name} step/time/value with {NOBS} samples")
        check(addr(g["step"]) == addr(o["n_mobile/step"]) and
              addr(g["time"]) == addr(o["n_mobile/time"]),
              f"observables/{name} shares step/time")
        check(fixed_str_attr(g["value"], "unit") is not None, f"observables/{name} has a unit")
    check(fixed_str_attr(o["temperature/value"], "unit") == "m d+2 tau-2", "temperature unit")
    check(np.all(np.isnan(o["wall_pressure/value"][()])), "NaN kept for an absent quantity")

    par = f["parameters"]
    sd = par["scene"]
    info = h5py.check_string_dtype(sd.dtype)
    check(info is not None and info.length is None and info.encoding == "utf-8",
          "parameters/scene is a variable-length UTF-8 string")
    check(sd.asstr()[()] == SCENE, "parameters/scene holds the scene text")
    check(par["method"].asstr()[()] == "dem", "parameters/method")
    check(int(par["seed"][()]) == 12345678901234567 and par["seed"].dtype == np.uint64,
          "parameters/seed uint64")
    check(par["scene_name"].asstr()[()] == "testbox", "parameters/scene_name")
    check(par["grano_version"].asstr()[()] == "0.1.0-test", "parameters/grano_version")

    fl = f["fields/packing_fraction"]
    check(list(fl.attrs["grid"]) == [4, 2] and list(fl.attrs["cell"]) == [5.0, 5.0] and
          list(fl.attrs["origin"]) == [0.0, 0.0] and int(fl.attrs["components"]) == 1,
          "field grid attributes")
    check(fl["value"].shape == (2, 2, 4) and fl["step"].shape == (2,),
          "field value is (samples, ny, nx)")
    check(fixed_str_attr(fl["value"], "unit") == "1", "field unit")
    res = f["results/flow"]
    check(res.shape == (4, 2) and [c.decode() if isinstance(c, bytes) else c
                                   for c in res.attrs["columns"]] == ["D", "Q"],
          "results/flow table with column names")
    f.close()


def check_xdmf(path):
    x = path + ".xdmf"
    check(os.path.exists(x), "XDMF sidecar exists")
    root = ET.parse(x).getroot()
    coll = root.find("Domain/Grid")
    check(coll is not None and coll.get("CollectionType") == "Temporal", "temporal collection")
    grids = coll.findall("Grid")
    check(len(grids) == NFR, f"{NFR} grids, one per frame")
    times = [float(g.find("Time").get("Value")) for g in grids]
    check(times == [0.5 * k for k in range(NFR)], "grid times are the frame times")
    g = grids[-1]
    topo = g.find("Topology")
    check(topo.get("TopologyType") == "Polyvertex" and topo.get("NumberOfElements") == str(NP),
          "Polyvertex topology of N nodes")
    geo = g.find("Geometry")
    check(geo.get("GeometryType") == "XY", "XY geometry")
    f = h5py.File(path, "r")
    ok = True
    for item in g.iter("DataItem"):
        if item.get("Format") != "HDF":
            continue
        fname, dset = item.text.strip().split(":", 1)
        dims = tuple(int(v) for v in item.get("Dimensions").split())
        ok = ok and fname == os.path.basename(path) and dset in f and f[dset].shape == dims
    check(ok, "every XDMF data item names an existing dataset with its shape")
    names = {a.get("Name") for a in g.findall("Attribute")}
    check({"velocity", "radius", "flags", "id"} <= names, "XDMF attributes include velocity and radius")
    fields = [c for c in root.findall("Domain/Grid") if c.get("Name") == "field packing_fraction"]
    check(len(fields) == 1 and len(fields[0].findall("Grid")) == 2 and
          fields[0].find("Grid/Topology").get("Dimensions") == "2 3 5",
          "XDMF field collection: 2 samples on a one-cell-thick 4 x 2 image")
    f.close()


def check_info(path, build):
    """`grano info` on the sample, on a missing file and on a non-HDF5 file."""
    grano = os.path.join(build, "experiments", "grano")
    if not os.path.exists(grano):
        print("ok      (grano not built: grano info not checked)")
        return
    p = subprocess.run([grano, "info", path], capture_output=True, text=True)
    out = p.stdout
    check(p.returncode == 0 and "frames       5, t = 0 .. 2 tau (steps 0 .. 400)" in out and
          "particles    40 per frame" in out and "method       dem, seed 12345678901234567" in out and
          "fields       packing_fraction: 4 x 2 cells" in out and "results      flow [4 x 2]" in out,
          "grano info describes the sample")
    p = subprocess.run([grano, "info", path + ".missing"], capture_output=True, text=True)
    check(p.returncode == 2 and "no such file" in p.stderr, "grano info: a missing file exits 2")
    p = subprocess.run([grano, "info", path + ".xdmf"], capture_output=True, text=True)
    check(p.returncode == 2 and "not an HDF5 file" in p.stderr, "grano info: a text file exits 2")
    p = subprocess.run([grano, "info", "--help"], capture_output=True, text=True)
    check(p.returncode == 0 and p.stdout.startswith("usage: grano info"), "grano info --help exits 0")
    os.unlink(path + ".xdmf")
    p = subprocess.run([grano, "info", "--xdmf", path], capture_output=True, text=True)
    check(p.returncode == 0 and os.path.exists(path + ".xdmf"), "grano info --xdmf rewrites the sidecar")


PV_PROBE = r"""
import sys
from paraview.simple import XDMFReader
from paraview import servermanager as sm
from paraview.vtk.numpy_interface import dataset_adapter as dsa
r = XDMFReader(FileNames=[sys.argv[1]])
r.UpdatePipelineInformation()
print("TIMES", " ".join(repr(t) for t in r.TimestepValues))
r.UpdatePipeline(1.0)
d = sm.Fetch(r)
blocks = [d.GetBlock(i) for i in range(d.GetNumberOfBlocks())]
for b in blocks:
    if b is None:
        continue
    w = dsa.WrapDataObject(b)
    if b.IsA("vtkUnstructuredGrid"):
        print("POINTS", b.GetNumberOfPoints(), b.GetNumberOfCells(), " ".join(sorted(w.PointData.keys())))
        print("P3", repr(w.Points[3][0]), repr(w.Points[3][1]), repr(w.PointData["velocity"][3][0]),
              repr(w.PointData["radius"][3]))
    else:
        print("IMAGE", b.GetNumberOfCells(), " ".join(repr(x) for x in b.GetBounds()),
              repr(w.CellData["packing_fraction"][5]))
"""


def check_paraview(path):
    pv = shutil.which("pvpython")
    if not pv:
        print("pvpython (ParaView) is not installed: skipped")
        sys.exit(77)
    out = subprocess.run([pv, "-c", PV_PROBE, os.path.abspath(path + ".xdmf")],
                         capture_output=True, text=True, timeout=300).stdout
    lines = {l.split()[0]: l.split()[1:] for l in out.splitlines() if l.split()}
    check("TIMES" in lines and [float(t) for t in lines["TIMES"]] == [0.5 * k for k in range(NFR)],
          "ParaView's XDMF reader sees the frame times")
    pts = lines.get("POINTS", [])
    check(pts[:2] == [str(NP), str(NP)] and {"velocity", "radius", "flags", "id"} <= set(pts[2:]),
          "ParaView reads N vertices with velocity, radius, flags, id")
    f = h5py.File(path, "r")
    t = f["particles/trajectory"]
    want = [t["position/value"][2, 3, 0], t["position/value"][2, 3, 1],
            t["velocity/value"][2, 3, 0], t["radius"][3]]
    got = [float(v) for v in lines.get("P3", [])]
    check(got == [float(v) for v in want], "ParaView values of grain 3 at t = 1 equal the file's")
    img = [float(v) for v in lines.get("IMAGE", [])]
    check(len(img) == 8 and img[0] == 8 and img[1:5] == [0.0, 20.0, 0.0, 10.0] and
          img[7] == f["fields/packing_fraction/value"][1, 1, 1],
          "ParaView reads the field as a 4 x 2 image over [0, 20] x [0, 10], cell (1, 1) right")
    f.close()


def main():
    args = [a for a in sys.argv[1:] if a != "--paraview"]
    paraview = len(args) != len(sys.argv) - 1
    build = os.environ.get("GRANO_BUILD_ROOT", "../..")
    exe = args[0] if args else os.path.join(build, "tests", "unit", "test_h5md")
    with tempfile.TemporaryDirectory(prefix="h5md-layout-", dir=".") as d:
        path = os.path.join(d, "sample.h5")
        subprocess.run([exe, "--sample", path], check=True)
        if paraview:
            check_paraview(path)
        else:
            check_file(path)
            check_xdmf(path)
            check_info(path, build)
    if failures:
        print(f"{len(failures)} check(s) failed")
        return 1
    print("all layout checks passed")
    return 0


if __name__ == "__main__":
    sys.exit(main())
