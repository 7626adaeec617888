#!/usr/bin/python3
"""Space-time density and power spectrum of the lgca pipe (test_lgca_pipe's
output files, in its build directory):

    meson test -C build lgca_pipe
    /usr/bin/python3 tests/method/lgca/lgca_pipe_plot.py build/tests/method/lgca lgca_pipe.png
"""
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402


def main():
    if len(sys.argv) != 3:
        sys.exit("usage: lgca_pipe_plot.py RESULT_DIR OUT.png")
    d, out = sys.argv[1], sys.argv[2]
    st = np.loadtxt(f"{d}/lgca_pipe_spacetime.txt")
    sp = np.loadtxt(f"{d}/lgca_pipe_spectrum.txt")
    fig, ax = plt.subplots(1, 2, figsize=(11, 5))
    im = ax[0].imshow(st, aspect="auto", cmap="gray_r", origin="upper",
                      extent=[0, 4 * st.shape[1], 4 * st.shape[0], 0])
    ax[0].set_xlabel("height along the pipe (rows, a)")
    ax[0].set_ylabel("step")
    ax[0].set_title("occupation per channel, bins of 4 rows")
    fig.colorbar(im, ax=ax[0])
    f = sp[:, 0]
    for col, lab in [(1, "p = stop = 0.3, windows of 4 rows"), (2, "p = stop = 0.3, 32 rows"),
                     (3, "p = stop = 0, 4 rows")]:
        ax[1].loglog(f, sp[:, col], "o-", ms=3, label=lab)
    k = np.argmin(abs(f - 2e-3))
    ax[1].loglog(f, sp[k, 1] * (f / f[k]) ** (-4 / 3), "k--", label="f^-4/3 (Peng and Herrmann)")
    ax[1].set_xlabel("frequency (1/step)")
    ax[1].set_ylabel("power of the particle count")
    ax[1].legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(out, dpi=90)


if __name__ == "__main__":
    main()
