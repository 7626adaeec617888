#!/usr/bin/python3
"""The Sonine coefficients of the homogeneous cooling state (HCS) of inelastic
smooth hard disks (d = 2) from the Boltzmann equation, beyond first Sonine.

Independent of the DSMC code: the collisional moments
    mu_p = -int dc c^p I[f, f],   f = phi(c) (1 + sum_{k=2..K} a_k S_k(c^2)),
phi = exp(-c^2)/pi, S_k = L_k^(0) (Laguerre; d/2 - 1 = 0), c = v / sqrt(2T/m),
are quadratic polynomials in the a's; their coefficients are computed by a
quadrature that is exact for polynomials: Gauss-Hermite over the centre-of-mass
velocity C (weight exp(-2 C^2)), generalised Gauss-Laguerre over x = G^2/2 of
the relative speed (weight x^(1/2) e^-x: the flux factor G times the Jacobian
G dG, G = |g|; the direction of g is fixed by rotational invariance) and
Gauss-Legendre over the impact parameter s = b/sigma in [-1, 1] (the normal n
makes the angle asin(s) with g, so the post-collision relative velocity is a
polynomial in s and sqrt(1 - s^2), whose odd part cancels on symmetric nodes).

The scaled HCS, (zeta*/2) d/dc.(c f) = I[f, f], gives for every even p
    mu_p = (p/2) zeta* <c^p>,  zeta* = (2/d) mu_2,  so in d = 2:
    mu_p = (p/2) mu_2 <c^p>,   p = 4, 6, ..., 2K,
K - 1 equations for a_2..a_K (<c^2> = d/2 = 1 fixes a_1 = 0; p = 4 is
mu_4 = (d + 2)(1 + a_2) mu_2). Two closures at each order K:
  linear: mu_p and mu_2 <c^p> linearised in the a's (K = 2 is van Noije and
          Ernst's formula);
  full:   mu_p with all its quadratic terms and mu_2 <c^p> as it is (cubic),
          solved by Newton from the linear solution.
As K grows the two closures and successive orders converge where the Sonine
expansion does (alpha >~ 0.5); their spread measures what is left.

    /usr/bin/python3 tests/method/dsmc/sonine_hcs.py            # the table (1-2 min)
    /usr/bin/python3 tests/method/dsmc/sonine_hcs.py --alpha 0.9999 --kmax 6
    /usr/bin/python3 tests/method/dsmc/sonine_hcs.py --check    # self-tests
"""
import math
import sys

import numpy as np
from numpy.polynomial import hermite, laguerre, legendre
from scipy.special import roots_genlaguerre

D = 2


def sonine(k, x):
    """S_k(x) = L_k^(0)(x) for d = 2, at x (array)."""
    return laguerre.lagval(x, [0] * k + [1])


def quadrature(kmax, nh=None, ng=None, ns=None):
    """Nodes and weights of (C, G, s) for moments up to c^(2 kmax) with f of
    Sonine order kmax: the integrand is a polynomial of degree 6 kmax in the
    velocities (f1 f2: 4 kmax, c^p: 2 kmax) times the flux factor G."""
    deg = 6 * kmax + 2
    nh = nh or deg // 2 + 2
    ng = ng or deg // 4 + 3
    ns = ns or deg + 4
    t, wt = hermite.hermgauss(nh)  # weight exp(-t^2), C_x = t / sqrt(2)
    cx, cw = t / math.sqrt(2), wt / math.sqrt(2)
    x, wx = roots_genlaguerre(ng, 0.5)  # weight x^(1/2) e^-x, G = sqrt(2x)
    G, gw = np.sqrt(2 * x), wx * math.sqrt(2)  # int G^2 e^{-G^2/2} dG P = sqrt(2) int x^.5 e^-x P
    s, sw = legendre.leggauss(ns)
    CX, CY, GG, SS = np.meshgrid(cx, cx, G, s, indexing="ij")
    W = np.einsum("a,b,c,d->abcd", cw, cw, gw, sw)
    return CX.ravel(), CY.ravel(), GG.ravel(), SS.ravel(), W.ravel()


def moment_tables(alpha, kmax, q=None):
    """M[p][i][j] with mu_{2p} = sum_ij a_i a_j M[p][i][j] (a_0 = 1, a_1 = 0),
    for p = 0..kmax, i, j = 0..kmax; and m[p][k] = <c^{2p} S_k> over phi.
    Normalisation: mu_p = -(1/2) int dc1 dc2 f1 f2 int_{-1}^{1} ds |g| Delta(c^p),
    i.e. sigma = 1, unit density."""
    CX, CY, G, S, W = q or quadrature(kmax)
    # phi(c1) phi(c2) = pi^-2 exp(-2C^2 - g^2/2), the Gaussians and the flux
    # factor G are in the weights; 2 pi from the direction of g
    W = W * 2 * math.pi / math.pi**2
    cn = np.sqrt(1 - S * S)  # cos(theta), n = (cos, sin) with g = (G, 0)
    gn = G * cn
    k = (1 + alpha) * gn
    gpx, gpy = G - k * cn, -k * S  # g' = g - (1 + alpha)(g.n) n
    c1 = (CX + G / 2) ** 2 + CY**2
    c2 = (CX - G / 2) ** 2 + CY**2
    c1p = (CX + gpx / 2) ** 2 + (CY + gpy / 2) ** 2
    c2p = (CX - gpx / 2) ** 2 + (CY - gpy / 2) ** 2
    P = kmax + 1
    dpsi = np.array([c1p**p + c2p**p - c1**p - c2**p for p in range(P)])
    S1 = np.array([sonine(i, c1) for i in range(P)])
    S2 = np.array([sonine(i, c2) for i in range(P)])
    M = -0.5 * np.einsum("pn,in,jn,n->pij", dpsi, S1, S2, W)
    M[:, 1, :] = 0
    M[:, :, 1] = 0
    # <c^{2p} S_k>_phi = int_0^inf x^p L_k(x) e^-x dx, exact by Gauss-Laguerre
    x, w = laguerre.laggauss(2 * P + 2)
    m = np.array([[np.sum(w * x**p * sonine(kk, x)) for kk in range(P)] for p in range(P)])
    m[:, 1] = 0
    return M, m


def residual(a, M, m, K, linear):
    """r_p = mu_{2p} - p mu_2 <c^{2p}>, p = 2..K (d = 2), a = (a_2..a_K)."""
    A = np.zeros(K + 1)
    A[0] = 1
    A[2:] = a
    r = []
    for p in range(2, K + 1):
        if linear:
            mu = M[p][0][0] + 2 * sum(A[i] * M[p][0][i] for i in range(2, K + 1))  # M symmetric in i, j
            mu2 = M[1][0][0] + 2 * sum(A[i] * M[1][0][i] for i in range(2, K + 1))
            cp = m[p][0] + sum(A[i] * m[p][i] for i in range(2, K + 1))
            # p mu_2 <c^2p> linearised: p (mu2_0 cp_0 + mu2_0 (cp - cp_0) + (mu2 - mu2_0) cp_0)
            prod = mu2 * m[p][0] + M[1][0][0] * (cp - m[p][0])
            r.append(mu - p * prod)
        else:
            Mk = M[p][: K + 1, : K + 1]
            M1 = M[1][: K + 1, : K + 1]
            mu, mu2 = A @ Mk @ A, A @ M1 @ A
            cp = m[p][: K + 1] @ A
            r.append(mu - p * mu2 * cp)
    return np.array(r)


def solve(alpha, K, linear, tables=None):
    """a_2..a_K of the HCS at Sonine order K; tables from moment_tables with
    kmax >= K."""
    M, m = tables or moment_tables(alpha, K)
    M = 0.5 * (M + M.transpose(0, 2, 1))  # a_i a_j symmetric part
    n = K - 1
    a = np.zeros(n)
    if linear:
        r0 = residual(a, M, m, K, True)
        J = np.array([(residual(np.eye(n)[i], M, m, K, True) - r0) for i in range(n)]).T
        return np.linalg.solve(J, -r0)
    a = solve(alpha, K, True, (M, m))
    for _ in range(50):
        r = residual(a, M, m, K, False)
        h = 1e-7
        J = np.array([(residual(a + h * np.eye(n)[i], M, m, K, False) - r) / h for i in range(n)]).T
        da = np.linalg.solve(J, -r)
        a = a + da
        if np.max(np.abs(da)) < 1e-14:
            break
    return a


def van_noije_ernst(alpha, d=D):
    return 16 * (1 - alpha) * (1 - 2 * alpha**2) / (9 + 24 * d - alpha * (41 - 8 * d) + 30 * (1 - alpha) * alpha**2)


def check():
    """Self-tests; exit 1 on failure."""
    ok = True
    # 1. elastic limit: mu_2 = 0 for any a's (energy is conserved)
    M, m = moment_tables(1.0, 4)
    e = np.max(np.abs(M[1]))
    print(f"# elastic mu_2 coefficients, largest |M_1ij| = {e:.2e}")
    ok &= e < 1e-12
    # 1b. elastic: the Maxwellian is stationary (mu_p = 0 for every p), and the
    #     linearised operator is self-adjoint: in the Sonine basis
    #     L_kl = -int phi S_k L[S_l] is symmetric (tests the a3, a4 terms)
    M = 0.5 * (M + M.transpose(0, 2, 1))
    e0 = np.max(np.abs(M[:, 0, 0]))
    coef = [laguerre.lag2poly([0] * k + [1]) for k in range(5)]
    L = np.array([[sum(coef[k][p] * 2 * M[p][0][l] for p in range(len(coef[k]))) for l in range(2, 5)]
                  for k in range(2, 5)])
    e1 = np.max(np.abs(L - L.T)) / np.max(np.abs(L))
    print(f"# elastic: largest |mu_p(Maxwellian)| = {e0:.2e}; asymmetry of L_kl (k, l = 2..4) {e1:.2e}")
    ok &= e0 < 1e-12 and e1 < 1e-12
    # 2. Maxwellian mu_2 against the exact value: with this normalisation
    #    mu_2 = sqrt(2 pi) (1 - alpha^2) / 4 ... derived from zeta of Haff: checked
    #    by the ratio to (1 - alpha^2) at two alphas (first Sonine: (1 + 3 a2/16))
    for al in (0.3, 0.8):
        M, m = moment_tables(al, 3)
        r0 = M[1][0][0] / (1 - al * al)
        r2 = 2 * M[1][0][2] / M[1][0][0]
        print(f"# alpha {al}: mu_2^(0)/(1-alpha^2) = {r0:.12f} (sqrt(2 pi)/2 = {math.sqrt(2*math.pi)/2:.12f}),"
              f" d mu_2/d a2 / mu_2^(0) = {r2:.12f} (3/16 = 0.1875)")
        ok &= abs(r0 - math.sqrt(2 * math.pi) / 2) < 1e-12 and abs(r2 - 0.1875) < 1e-12
    # 3. first Sonine linearised = van Noije-Ernst
    worst = 0
    for al in np.linspace(0.05, 0.999, 40):
        a = solve(al, 2, True)[0]
        worst = max(worst, abs(a - van_noije_ernst(al)))
    print(f"# K = 2 linear against van Noije-Ernst, alpha 0.05..0.999: largest |difference| = {worst:.2e}")
    ok &= worst < 1e-6
    # 4. the quadrature is exact: more nodes change nothing
    M1, _ = moment_tables(0.7, 4)
    M2, _ = moment_tables(0.7, 4, quadrature(4, 24, 16, 48))
    e = np.max(np.abs(M1 - M2)) / np.max(np.abs(M1))
    print(f"# quadrature K = 4: relative change with (24, 16, 48) nodes {e:.2e}")
    ok &= e < 1e-12
    print("# check", "passed" if ok else "FAILED")
    return ok


ALPHAS = [0.5, 0.6, 0.7, 0.8, 0.9, 0.95, 0.99]


def table(kmax=8, alphas=ALPHAS):
    """a2 at each order; 'best' is the middle of the range the orders K = 5..kmax
    span (both closures), '+-' half that range: where the expansion converges
    (alpha >= 0.7) the range is below 1e-4, where it does not (alpha <= 0.6)
    successive orders alternate about the value and the range is the honest
    uncertainty."""
    print(f"# a2 (and a3, a4 of K = {kmax} full) of the HCS of hard disks, Boltzmann equation; "
          "K = Sonine order (K = 2 linear is van Noije-Ernst)")
    print("alpha K2lin=vNE K2full K3lin K3full K4lin K4full best +- a3 a4 vNE/(1-alpha) best/(1-alpha) a3/(1-alpha)")
    for al in alphas:
        tab = moment_tables(al, kmax)
        row = [f"{al:.4g}"]
        for K in (2, 3, 4):
            row += [f"{solve(al, K, lin, tab)[0]:.5f}" for lin in (True, False)]
        hi = [solve(al, K, lin, tab)[0] for K in range(5, kmax + 1) for lin in (True, False)]
        full = solve(al, kmax, False, tab)
        best, e = (max(hi) + min(hi)) / 2, 1 - al
        row += [f"{best:.5f}", f"{(max(hi) - min(hi)) / 2:.5f}", f"{full[1]:.5f}", f"{full[2]:.5f}"]
        row += [f"{van_noije_ernst(al) / e:.4f}", f"{best / e:.4f}", f"{full[1] / e:.4f}"]
        print(" ".join(row), flush=True)


if __name__ == "__main__":
    if "--check" in sys.argv:
        sys.exit(0 if check() else 1)
    k = int(sys.argv[sys.argv.index("--kmax") + 1]) if "--kmax" in sys.argv else 8
    al = [float(a) for a in sys.argv[sys.argv.index("--alpha") + 1].split(",")] if "--alpha" in sys.argv else ALPHAS
    table(k, al)
