#!/usr/bin/env bash
# grano silo-start and silo-flow in quick mode: every output and figure is
# produced, every fit converges, the numbers are physical (superdiffusive
# MSD, flow rising with D), read from the HDF5 tables by column name, cd's flow beside dem's, a
# resumed sweep redoes only missing parts and gives the same bits with another --jobs, without
# gnuplot the data are written and the exit code is 0, and bad flags exit 2. TAP.
set -u
GRANO=$1
PY=/usr/bin/python3
# shellcheck source=tap.sh
. "$(dirname "$0")/tap.sh"
if ! $PY -c 'import h5py, numpy' 2>/dev/null; then
    echo "1..0 # SKIP /usr/bin/python3 lacks h5py"
    exit 0
fi

# --- help and bad flags
"$GRANO" silo-start --help >"$tmp/out" 2>&1 && grep -q "usage: grano silo-start" "$tmp/out"
check $? "silo-start --help"
"$GRANO" silo-flow --help >"$tmp/out" 2>&1 && grep -q "usage: grano silo-flow" "$tmp/out"
check $? "silo-flow --help"
for args in "silo-start --bogus:--bogus" "silo-start --jobs 0:--jobs" "silo-flow --orifices 3,abc:--orifices" \
            "silo-flow --blocks x:--blocks" "silo-start --subtract mean:--subtract" "silo-flow --peer gromacs:--peer" "silo-start --orifices 60:--orifices" "silo-flow extra:extra" \
            "silo-start --hopper-outlet 1.5:--hopper-outlet" "silo-flow --quick --hopper-outlet 0.8:--hopper-outlet" \
            "silo-start --material mu:--material" "silo-start --quick --material mu=x:'mu'"; do
    cmd=${args%%:*}
    flag=${args##*:}
    # shellcheck disable=SC2086
    "$GRANO" $cmd -o "$tmp/never" >"$tmp/err" 2>&1
    rc=$?
    if [ $rc = 2 ] && grep -q -- "$flag" "$tmp/err" && [ ! -e "$tmp/never" ]; then
        ok "grano $cmd exits 2 naming $flag"
    else
        notok "grano $cmd exits 2 naming $flag (got $rc)"
    fi
done

# --- --material replaces a key of the thesis's law, and only that key
M=$tmp/material
"$GRANO" silo-start --quick -n 1 -D 11 --material mu=0.3 -o "$M" -q >/dev/null 2>"$tmp/err"
check $? "silo-start --quick --material mu=0.3 runs"
$PY - "$M/silo-start.h5" <<'PYEOF'
import sys, h5py
t = h5py.File(sys.argv[1], "r")["config/material"][0]
t = t.decode() if isinstance(t, bytes) else t
assert "mu = 0.3" in t and "mu = 0.5" not in t and "gamma_t = 300" in t, t
PYEOF
check $? "--material mu=0.3 is the scene's mu, the other keys the thesis's"

# --- silo-start --quick
S=$tmp/start
"$GRANO" silo-start --quick --jobs 2 -o "$S" -q >/dev/null 2>"$tmp/err"
check $? "silo-start --quick --jobs 2 runs"
missing=""
for f in silo-start.h5 summary.dat msd_D3.8.dat msd_D11.dat pdf_short_D11.dat pdf_long_D3.8.dat \
         fig3_1_filling.png fig3_2_velocity_profiles.png fig3_2_velocity_profiles_D3.8.png \
         fig3_2_stationarity.png fig3_3_displacement_pdf.png fig3_4_msd.png \
         fig3_5_displacement_pdf_long.png fig3_6_kurtosis.png silo_snapshot.png; do
    [ -s "$S/$f" ] || missing="$missing $f"
done
[ -z "$missing" ]
check $? "silo-start writes every table and figure${missing:+ (missing:$missing)}"
# settle once per realisation, branch both orifices from it
[ "$(find "$S/parts" -name 'fill-*.part' | wc -l)" = 2 ] && [ "$(find "$S/parts" -name 'start-*.part' | wc -l)" = 4 ]
check $? "silo-start fills once per realisation (2 fillings) and branches its 4 discharges from them"

$PY - "$S/silo-start.h5" >"$tmp/err" 2>&1 <<'PY'
import sys, h5py, numpy as np
f = h5py.File(sys.argv[1], "r")
assert "h5md" not in f and "particles" not in f, "silo-start.h5 dressed as an H5MD trajectory"

def table(g):
    """A table's columns by name; every column has a unit."""
    for k, v in g.items():
        assert "unit" in v.attrs and "description" in v.attrs, (g.name, k)
    return {k: (v.asstr()[()] if v.dtype.kind == "O" else v[()]) for k, v in g.items()}

cfg = table(f["config"])
assert cfg["method"][0] == "dem" and cfg["realisations"].dtype.kind == "i" and cfg["realisations"][0] == 2, cfg
s = table(f["summary"])
assert len(s["D"]) == 2 and list(s["D"]) == [3.8, 11], s["D"]
assert s["realisations"].dtype.kind == "i" and (s["realisations"] == 2).all(), s["realisations"]
assert f["summary/exp_x"].attrs["unit"] == "1" and f["summary/lag_short"].attrs["unit"] == "tau"
for i, D in enumerate(s["D"]):
    ex, ey = s["exp_x"][i], s["exp_y"][i]
    # fits converged; the local mean flow (columns) subtracted, the motion
    # is superdiffusive and below ballistic over the fitted range (quick
    # mode measured 1.65-1.84 on 2 discharges, errors 0.02-0.05; the quick
    # runs reach a fall of 0.06-0.3 d only, so the band is wider than the
    # thesis's 1.33-1.51 at a 1 d fall: docs/experiments.md)
    assert np.isfinite([ex, ey, s["exp_x_err"][i], s["exp_y_err"][i]]).all(), (D, ex, ey)
    assert 1.4 < ex < 1.95 and 1.4 < ey < 1.95, (D, ex, ey)
    # the short lag is a fall of about 0.01 d
    assert 0.003 < s["fall_short"][i] < 0.03, s["fall_short"][i]
    assert np.isfinite([s[k][i] for k in ("ks_eq34_x", "ks_gauss_x", "ks_eq34_y", "ks_gauss_y")]).all(), D
for D in ("3.8", "11"):
    g = f["D" + D]
    v = g["velocity_y"][:]
    grid = table(g["field_grid"])
    assert v.shape == (len(g["field_steps/step"]), grid["ny"][0], grid["nx"][0]), (v.shape, grid)
    assert np.isfinite(v).any() and np.nanmin(v) < 0, D  # grains move down
    for k in ("msd", "msd_fit", "pdf_short", "pdf_long", "pdf_stats", "discharges", "r00/msd_sums", "r01/series"):
        assert k in g, (D, k)
    fit = table(g["msd_fit"])
    assert list(fit["axis"]) == ["x", "y"] and np.isfinite(fit["exponent"]).all(), fit
    m = table(g["msd"])
    assert m["n"].dtype.kind == "i" and m["lag_steps"].dtype.kind == "i", (m["n"].dtype, m["lag_steps"].dtype)
    d = table(g["discharges"])
    assert list(d["realisation"]) == [0, 1] and (d["steps"] > 0).all(), d
    p = table(g["pdf_short"])
    du = p["u"][1] - p["u"][0]
    for col in ("p_x", "p_y"):
        area = p[col].sum() * du
        assert 0.9 < area <= 1.0 + 1e-9, (D, col, area)
st = table(f["stationarity"])
assert st["step"].dtype.kind == "i" and len(st["D"]) == len(st["step"]), st
PY
check $? "silo-start: fits converge, MSD exponents in (1.4, 1.95), densities normalised"

cp "$S/silo-start.h5" "$tmp/start-first.h5"
"$GRANO" silo-start --quick --jobs 2 -o "$S" >/dev/null 2>"$tmp/err" && grep -q "(4 reused)" "$tmp/err"
check $? "silo-start rerun reuses all 4 parts"
rm "$S/parts/start-D11-r01.part"
"$GRANO" silo-start --quick --jobs 1 -o "$S" >/dev/null 2>"$tmp/err" && grep -q "(3 reused)" "$tmp/err"
check $? "silo-start resumes: redoes only the missing part"
$PY - "$tmp/start-first.h5" "$S/silo-start.h5" >"$tmp/err" 2>&1 <<'PY'
import sys, h5py, numpy as np
a = h5py.File(sys.argv[1], "r"); b = h5py.File(sys.argv[2], "r")
for k in ("summary/exp_x", "summary/exp_y", "summary/sd_x", "D11/msd/msd_x", "D11/msd/msd_y", "D11/velocity_y",
          "D3.8/pdf_short/p_x"):
    x, y = a[k][()], b[k][()]
    assert np.array_equal(x, y, equal_nan=True), k
PY
check $? "silo-start: the redone part (1 job) gives the same bits as the first run (2 jobs)"

# --- silo-flow --quick
F=$tmp/flow
"$GRANO" silo-flow --quick --jobs 2 -o "$F" -q >/dev/null 2>"$tmp/err"
check $? "silo-flow --quick --jobs 2 runs"
missing=""
for f in silo-flow.h5 flow.dat fits.dat pdf_fluctuations.dat reduced_flow.dat fig4_1_flow_rate.png \
         fig4_2_flow_fluctuations.png fig4_3_fluctuation_pdf.png fig4_5_packing.png \
         fig4_6_modified_flow_law.png silo_snapshot.png; do
    [ -s "$F/$f" ] || missing="$missing $f"
done
[ -z "$missing" ]
check $? "silo-flow writes every table and figure${missing:+ (missing:$missing)}"
# settle once, branch many: one filling for the 7 orifices of realisation 0
[ -s "$F/parts/fill-r00.part" ] && [ "$(find "$F/parts" -name 'fill-*.part' | wc -l)" = 1 ]
check $? "silo-flow fills once (parts/fill-r00.part) and branches every orifice from it"
$PY - "$F/silo-flow.h5" >"$tmp/err" 2>&1 <<'PY'
import sys, h5py, numpy as np
f = h5py.File(sys.argv[1], "r")
assert "h5md" not in f and "particles" not in f, "silo-flow.h5 dressed as an H5MD trajectory"

def table(name):
    g = f[name]
    for k, v in g.items():
        assert "unit" in v.attrs and "description" in v.attrs, (name, k)
    return {k: (v.asstr()[()] if v.dtype.kind == "O" else v[()]) for k, v in g.items()}

fits = table("fits")
assert list(fits["law"]) == ["beverloo", "sigma_w_all", "sigma_w_small", "sigma_w_large", "density_law",
                             "modified_law"], fits["law"]
fit = {law: i for i, law in enumerate(fits["law"])}
conv = fits["converged"]
assert conv.dtype.kind == "i", conv.dtype
# the density law may end at a bound of its decay rate (flag 2), a result, not a failure
assert conv[fit["density_law"]] in (1, 2), "density-law fit failed: %s" % conv
assert all(conv[i] == 1 for law, i in fit.items() if law != "density_law"), "a fit did not converge: %s" % conv
dl = fit["density_law"]
assert fits["p0"][dl] > 0.3 and np.isfinite(fits["p2"][dl]), (fits["p0"][dl], fits["p2"][dl])
C, k = fits["p0"][fit["beverloo"]], fits["p1"][fit["beverloo"]]
assert fits["parameters"][fit["beverloo"]] == "C,k" and C > 0 and -3 < k < 3.5, (C, k)
flow = table("flow")
assert f["flow/W"].attrs["unit"] == "tau-1" and f["flow/D"].attrs["unit"] == "d"
D, W = flow["D"], flow["W"]
assert (W > 0).all() and W[-1] > 3 * W[0], W
assert ((flow["packing"] > 0.3) & (flow["packing"] < 0.91)).all(), flow["packing"]
assert (flow["sigma_w"] > 0).all() and flow["blocks"].dtype.kind == "i" and (flow["blocks"] == 16).all()
b = table("blocks")
assert b["grains"].dtype.kind == "i", b["grains"].dtype
mine = (b["D"] == 3.56) & (b["realisation"] == 0)
assert mine.sum() == 16, mine.sum()
# the table's flow rate is the blocks' grains over the block time
cfg = table("config")
bt = cfg["block_time"][0]
for i, d in enumerate(D):
    assert abs(b["grains"][b["D"] == d].mean() / bt - W[i]) < 1e-9 * max(1, W[i]), (d, W[i])
r = table("realisations")
assert len(r["D"]) == len(D) * cfg["realisations"][0] and (r["steps_run"] > 0).all(), r
PY
check $? "silo-flow: every fit converges (density law: or stops at a bound), Beverloo C > 0, flow rises with D, packing physical"

# every figure's axes fit its data (the scripts replayed by gnuplot)
if command -v gnuplot >/dev/null && [ -x /usr/bin/python3 ]; then
    /usr/bin/python3 "$(dirname "$0")/figure_axes.py" "$S" "$F" >"$tmp/err" 2>&1
    check $? "silo-start's and silo-flow's figures: no axis five times wider than its data"
fi

# --- without gnuplot on PATH: the data are written, the figures are not,
# grano says so and exits 0 (the quick runs' parts are reused)
mkdir -p "$tmp/nognu"
for study in flow start; do
    src=$F
    [ $study = start ] && src=$S
    mkdir -p "$tmp/ng-$study" && cp -r "$src/parts" "$tmp/ng-$study/parts"
    PATH=$tmp/nognu "$GRANO" silo-$study --quick --jobs 2 -o "$tmp/ng-$study" -q >"$tmp/out" 2>"$tmp/err"
    rc=$?
    [ $rc = 0 ] && [ -s "$tmp/ng-$study/silo-$study.h5" ] && ! ls "$tmp/ng-$study"/*.png >/dev/null 2>&1 &&
        grep -q "gnuplot is not on PATH" "$tmp/err"
    check $? "silo-$study without gnuplot: exit 0 (got $rc), silo-$study.h5 written, no figure, says why"
done

# --- silo-flow --quick --method cd at D = 8 beside dem's quick run above
# (same grains, walls and seed). The filling itself asserts that nothing
# leaves while the orifice is closed (silo_fill fails otherwise). The band:
# cd's rate within [0.5, 1.2] of dem's at D = 8 (measured: 10.5 against
# 14.25 grains/tau, ratio 0.74, each with an error of 11-20% over 8 and 16
# blocks; 0.93 over 16 blocks; cd flows slower, docs/methods/cd.md).
C=$tmp/flowcd
"$GRANO" silo-flow --quick --method cd --orifices 8 --blocks 8 -o "$C" -q >"$tmp/out" 2>"$tmp/err"
check $? "silo-flow --quick --method cd runs"
$PY - "$F/flow.dat" "$C/flow.dat" >"$tmp/err" 2>&1 <<'PY'
import sys, numpy as np
dem = np.loadtxt(sys.argv[1]); cd = np.loadtxt(sys.argv[2], ndmin=2)
Wd = dem[dem[:, 0] == 8][0, 1]
Wc = cd[0, 1]
print("# flow rate at D = 8: dem %.3f, cd %.3f, ratio %.3f" % (Wd, Wc, Wc / Wd))
assert Wc > 0, Wc
assert 0.5 * Wd < Wc < 1.2 * Wd, (Wc, Wd)
assert 0.7 < cd[0, 5] < 0.91, cd[0, 5]
PY
check $? "silo-flow --method cd: grains leave once open, rate within [0.5, 1.2] of dem's at D = 8"
finish
