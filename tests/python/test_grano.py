"""The Python module's tests under pytest: each part of api_check.py and
each method's parity run of cli_parity.py as one pytest test, a failed
check failing it with its name and detail. Meson runs this as
python-pytest (`/usr/bin/python3 -m pytest`, Debian's python3-pytest,
which ./grano.sh deps installs); GRANO_EXE and GRANO_SOURCE_ROOT name the
program and the tree, PYTHONPATH the built module."""
import os
import subprocess
import sys

import pytest

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import api_check  # noqa: E402
import cli_parity  # noqa: E402

EXE = os.environ.get("GRANO_EXE", "")
ROOT = os.environ.get("GRANO_SOURCE_ROOT", "")


class Checks:
    """The TAP scripts' check(), as an assertion."""

    def check(self, ok, what, detail=""):
        assert ok, "%s\n%s" % (what, detail)


@pytest.fixture
def grano(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    import grano as module
    return module


def test_one_liner_prints_the_cli_temperature(grano):
    import h5py
    ini = "%s/experiments/scenes/box.ini" % ROOT
    r = subprocess.run([EXE, "run", ini, "--method", "edmd", "--until", "1", "-o", "box.h5", "-f", "-q"])
    assert r.returncode == 0
    with h5py.File("box.h5", "r") as f:
        want = f["observables/temperature/value"][-1]
    code = ("import grano; s = grano.Sim(grano.Scene('%s'), method='edmd'); s.advance(1.0); "
            "print(s.observables()['temperature'])" % ini)
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True).stdout
    assert float(out) == want


def test_bad_key_raises_scene_error_naming_it(grano):
    scene = grano.Scene("%s/experiments/scenes/box.ini" % ROOT)
    with pytest.raises(grano.SceneError, match="muu"):
        grano.Sim(scene.set("material.muu", 0.3), "dem")


@pytest.mark.parametrize("method", sorted(cli_parity.CASES))
def test_same_run_as_grano_run(grano, method):
    scene, until = cli_parity.CASES[method]
    cli_parity.compare_run(Checks(), grano, EXE, ROOT, method, scene, until)


@pytest.mark.parametrize("part", ["refusals", "registry", "snapshots", "failures", "interrupt", "gil", "reading",
                                  "restarts"])
def test_api(grano, part):
    fn = getattr(api_check, part)
    names = fn.__code__.co_varnames[:fn.__code__.co_argcount]
    args = {"tap": Checks(), "grano": grano, "exe": EXE, "root": ROOT}
    fn(*[args[n] for n in names])


def test_read_a_running_and_a_killed_result(grano):
    """grano.read opens a result while its run writes it, and after a kill
    (HDF5's SWMR read mode), with the frames flushed so far."""
    import signal
    import time
    ini = "%s/experiments/scenes/box.ini" % ROOT
    p = subprocess.Popen([EXE, "run", ini, "--method", "dem", "--until", "100", "-o", "live.h5", "-f", "-q"])
    seen = []
    try:
        for _ in range(200):
            time.sleep(0.1)
            if os.path.exists("live.h5"):
                r = grano.read("live.h5")
                seen.append(r.trajectory.position.shape[0])
                if len(set(seen)) >= 3:
                    break
    finally:
        p.send_signal(signal.SIGKILL)
        p.wait()
    assert len(set(seen)) >= 3 and seen == sorted(seen), seen
    assert grano.read("live.h5").trajectory.position.shape[0] >= seen[-1]
