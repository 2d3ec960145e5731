#!/usr/bin/python3
# verify_spine_math.py - numerical verification of every formula of docs/MATH-spine.md
# (issue 18: curvature lines of a canal surface along a 3D spine).
# SPDX-License-Identifier: MIT
#
# Usage: /usr/bin/python3 tools/verify_spine_math.py [--quick]
# Needs numpy only. Prints one line per check: its name, the residual, the bound it must
# stay under, and PASS/FAIL; then the tables of the "Fixed-step numerics" section; the last
# line is "verify-spine: N passed, N failed" (exit status 0 iff nothing failed).
# --quick skips the float32 tables (the slowest part).
#
# Independence: every derivative of the surface that a formula claims is checked against
# finite differences of m(u, theta) = c + R n itself; the reference lines are integrated
# from the defining orthogonality (or from the document's dtheta/ds, never from the 2x2
# transport); frames come from integrating the RMF ODE (never from double reflection),
# except where a closed form exists (helix).
import math
import sys

import numpy as np

QUICK = "--quick" in sys.argv
TWO_PI = 2.0 * math.pi
results = []


def check(name, resid, bound):
    ok = bool(np.isfinite(resid) and resid <= bound)
    results.append(ok)
    print(f"  {'PASS' if ok else 'FAIL'}  {name:<64s} {resid:10.3e}  (<= {bound:.0e})")


def unit(v):
    return v / np.linalg.norm(v)


def wrap(a):
    """angle difference folded into (-pi, pi]"""
    return (a + math.pi) % TWO_PI - math.pi


# ----------------------------------------------------------------- spines (u in [0, 1])
# Each spine returns (c, c_u, c_uu) of the normalized parameter u; each law (R, R_u, R_uu).


class Line:
    def __init__(self, p0, p1):
        self.p0, self.d = np.array(p0, float), np.array(p1, float) - np.array(p0, float)

    def jet(self, u):
        return self.p0 + u * self.d, self.d.copy(), np.zeros(3)


class Arc:
    """circle in the plane through ctr normal to nrm; start direction d0 (projected onto
    the plane), angle span phi (radians, positive = counter-clockwise about nrm)"""

    def __init__(self, ctr, nrm, r, d0, span):
        self.ctr, self.r, self.span = np.array(ctr, float), r, span
        k = unit(np.array(nrm, float))
        d = np.array(d0, float)
        self.e1 = unit(d - (d @ k) * k)
        self.e2 = np.cross(k, self.e1)

    def jet(self, u):
        p = self.span * u
        cp, sp = math.cos(p), math.sin(p)
        w = self.span
        c = self.ctr + self.r * (cp * self.e1 + sp * self.e2)
        c1 = self.r * w * (-sp * self.e1 + cp * self.e2)
        c2 = -self.r * w * w * (cp * self.e1 + sp * self.e2)
        return c, c1, c2


class Helix:
    """axis point p, axis direction ax, radius r, pitch (mm per turn, > 0 right-handed),
    turns, start direction d0 (projected onto the plane normal to ax)"""

    def __init__(self, p, ax, r, pitch, turns, d0):
        self.p, self.r, self.h, self.turns = np.array(p, float), r, pitch / TWO_PI, turns
        self.k = unit(np.array(ax, float))
        d = np.array(d0, float)
        self.e1 = unit(d - (d @ self.k) * self.k)
        self.e2 = np.cross(self.k, self.e1)

    def jet(self, u):
        w = TWO_PI * self.turns
        p = w * u
        cp, sp = math.cos(p), math.sin(p)
        c = self.p + self.r * (cp * self.e1 + sp * self.e2) + self.h * p * self.k
        c1 = w * (self.r * (-sp * self.e1 + cp * self.e2) + self.h * self.k)
        c2 = -w * w * self.r * (cp * self.e1 + sp * self.e2)
        return c, c1, c2

    def closed_rmf(self, u, n0_is_principal=True):
        """the exact RMF of the helix (N1(0) = the principal normal): N1 = cos(phi) N +
        sin(phi) B with phi = -tau s (derived in MATH-spine section 2)"""
        c, c1, c2 = self.jet(u)
        T = unit(c1)
        N = unit(c2 - (c2 @ T) * T)
        B = np.cross(T, N)
        rr, hh = self.r, self.h
        tau = hh / (rr * rr + hh * hh)
        s = TWO_PI * self.turns * u * math.hypot(rr, hh)
        return T, math.cos(-tau * s) * N + math.sin(-tau * s) * B


class Bezier:
    def __init__(self, P):
        self.P = np.array(P, float)

    def jet(self, u):
        P, v = self.P, 1.0 - u
        c = v**3 * P[0] + 3 * v * v * u * P[1] + 3 * v * u * u * P[2] + u**3 * P[3]
        c1 = 3 * (v * v * (P[1] - P[0]) + 2 * v * u * (P[2] - P[1]) + u * u * (P[3] - P[2]))
        c2 = 6 * (v * (P[2] - 2 * P[1] + P[0]) + u * (P[3] - 2 * P[2] + P[1]))
        return c, c1, c2


class Floor:
    """the floor-fillet spine of MATH-canal section 7: c = C(t) + R(t) e_z, C = 3 (cos t,
    sin t, 0), R = 5.5 cos 2t + 10.5, t = 2 pi u"""

    def jet(self, u):
        t, w = TWO_PI * u, TWO_PI
        c = np.array([3 * math.cos(t), 3 * math.sin(t), 5.5 * math.cos(2 * t) + 10.5])
        c1 = w * np.array([-3 * math.sin(t), 3 * math.cos(t), -11 * math.sin(2 * t)])
        c2 = w * w * np.array([-3 * math.cos(t), -3 * math.sin(t), -22 * math.cos(2 * t)])
        return c, c1, c2


def law(kind, rp):
    """the canal's radius laws (canal.h) in the normalized spine parameter u"""
    if kind == "CONST":
        return lambda u: (rp[0], 0.0, 0.0)
    if kind == "LINEAR":
        return lambda u: (rp[0] + (rp[1] - rp[0]) * u, rp[1] - rp[0], 0.0)
    if kind == "COS":  # R = b cos(k 2 pi u) + c, rp = (b, c, k)
        w = TWO_PI * rp[2]
        return lambda u: (rp[0] * math.cos(w * u) + rp[1], -rp[0] * w * math.sin(w * u),
                          -rp[0] * w * w * math.cos(w * u))

    def cubic(u):  # Bernstein
        r, v = rp, 1.0 - u
        return (r[0] * v**3 + 3 * r[1] * v * v * u + 3 * r[2] * v * u * u + r[3] * u**3,
                3 * ((r[1] - r[0]) * v * v + 2 * (r[2] - r[1]) * v * u + (r[3] - r[2]) * u * u),
                6 * ((r[2] - 2 * r[1] + r[0]) * v + (r[3] - 2 * r[2] + r[1]) * u))

    return cubic


class Canal:
    """a spine, a radius law and the start vector of N1 (None: the principal normal)"""

    def __init__(self, name, spine, rlaw, ref=None):
        self.name, self.sp, self.R = name, spine, rlaw
        c, c1, c2 = spine.jet(0.0)
        T = unit(c1)
        v = (c2 - (c2 @ T) * T) if ref is None else np.array(ref, float)
        self.N10 = unit(v - (v @ T) * T)
        # arc length by composite Simpson (2048 panels; |c_u| is smooth)
        us = np.linspace(0.0, 1.0, 2049)
        sp = np.array([np.linalg.norm(spine.jet(x)[1]) for x in us])
        self.L = (sp[0] + sp[-1] + 4 * sp[1:-1:2].sum() + 2 * sp[2:-1:2].sum()) / (3 * 2048)

    def geom(self, u):
        """everything at u that is independent of the frame"""
        c, c1, c2 = self.sp.jet(u)
        R, Ru, Ruu = self.R(u)
        v = np.linalg.norm(c1)
        T = c1 / v
        Tu = (c2 - (c2 @ T) * T) / v  # dT/du
        a = Ru / v  # dR/ds
        # da/ds = (R_uu - a (c_u . c_uu)/|c_u|) / |c_u|^2
        a_s = (Ruu - a * (c1 @ c2) / v) / (v * v)
        return dict(c=c, v=v, T=T, Tu=Tu, R=R, a=a, b=math.sqrt(1.0 - a * a), a_s=a_s)

    def frame_of(self, g, N1):
        N1 = unit(N1 - (N1 @ g["T"]) * g["T"])
        return N1, np.cross(g["T"], N1)

    def point(self, u, th, N1, off=0.0):
        """m(u, theta) = c + (R + off) n, n = -a T + b (cos th N1 + sin th N2)"""
        g = self.geom(u)
        N1, N2 = self.frame_of(g, N1)
        n = -g["a"] * g["T"] + g["b"] * (math.cos(th) * N1 + math.sin(th) * N2)
        return g["c"] + (g["R"] + off) * n, n


# ------------------------------------------------ adaptive Dormand-Prince 5(4) (reference)
DP_C = [0, 1 / 5, 3 / 10, 4 / 5, 8 / 9, 1, 1]
DP_A = [[], [1 / 5], [3 / 40, 9 / 40], [44 / 45, -56 / 15, 32 / 9],
        [19372 / 6561, -25360 / 2187, 64448 / 6561, -212 / 729],
        [9017 / 3168, -355 / 33, 46732 / 5247, 49 / 176, -5103 / 18656],
        [35 / 384, 0, 500 / 1113, 125 / 192, -2187 / 6784, 11 / 84]]
DP_E = [71 / 57600, 0, -71 / 16695, 71 / 1920, -17253 / 339200, 22 / 525, -1 / 40]


def dp45(f, y0, nodes, tol=1e-12, h0=1e-3):
    """integrate y' = f(u, y) from nodes[0] through every node (exactly); returns the
    states at the nodes. Error per step <= tol (1 + |y|) in the max norm."""
    u, y, out, h = nodes[0], np.array(y0, float), [np.array(y0, float)], h0
    for un in nodes[1:]:
        while u < un:
            hh = min(h, un - u)
            k = [f(u, y)]
            for i in range(1, 7):
                k.append(f(u + DP_C[i] * hh, y + hh * sum(a * kk for a, kk in zip(DP_A[i], k))))
            yn = y + hh * sum(a * kk for a, kk in zip(DP_A[6], k))
            err = np.max(np.abs(hh * sum(e * kk for e, kk in zip(DP_E, k))))
            sc = tol * (1.0 + np.max(np.abs(yn)))
            fac = min(5.0, max(0.2, 0.9 * (sc / err) ** 0.2)) if err > 0 else 5.0
            if err <= sc:
                u, y = (un if hh == un - u else u + hh), yn
                h = max(h, hh * fac) if hh == un - u else hh * fac
            else:
                h = hh * fac
        out.append(y.copy())
    return out


def rhs_lines(cn):
    """the state (N1, theta_1..theta_k) in u: N1' = -(N1 . T_u) T (the RMF ODE) and the
    document's theta' = (a/b)(k2 cos theta - k1 sin theta) ds/du"""

    def f(u, y):
        g = cn.geom(u)
        N1 = y[:3]
        d = np.empty_like(y)
        d[:3] = -(N1 @ g["Tu"]) * g["T"]
        N1u, N2u = cn.frame_of(g, N1)
        k1, k2 = g["Tu"] @ N1u, g["Tu"] @ N2u  # per unit u (k_i |c_u|)
        th = y[3:]
        d[3:] = g["a"] / g["b"] * (k2 * np.cos(th) - k1 * np.sin(th))
        return d

    return f


def ref_lines(cn, th0, nodes, tol=1e-12):
    """frames and line angles at the nodes: list of (N1, thetas)"""
    y0 = np.concatenate([cn.N10, np.array(th0, float)])
    ys = dp45(rhs_lines(cn), y0, nodes, tol)
    return [(y[:3], y[3:]) for y in ys]


def rmf_step(cn, u, N1, h):
    """N1 at u + h from N1 at u: one classical RK4 step of the RMF ODE (local error
    O(h^5); used only over |h| <= 2e-3 around a reference frame for finite differences)"""

    def fr(uu, N):
        g = cn.geom(uu)
        return -(N @ g["Tu"]) * g["T"]

    k1 = fr(u, N1)
    k2 = fr(u + h / 2, N1 + h / 2 * k1)
    k3 = fr(u + h / 2, N1 + h / 2 * k2)
    k4 = fr(u + h, N1 + h * k3)
    return N1 + h / 6 * (k1 + 2 * k2 + 2 * k3 + k4)


# -------------------------------------------------------------------------- the shapes
SHAPES = {
    # the acceptance shapes (parts <= 100 mm)
    "helix-cos": Canal("helix-cos", Helix([0, 0, 0], [0, 0, 1], 15.0, 10.0, 2.0, [1, 0, 0]),
                       law("COS", [1.5, 4.0, 3.0])),
    "bezier-cubic": Canal("bezier-cubic",
                          Bezier([[0, 0, 0], [25, 35, 15], [60, -25, 35], [90, 10, 5]]),
                          law("CUBIC", [3.0, 6.0, 2.0, 5.0])),
    "arc-tilted-linear": Canal("arc-tilted-linear",
                               Arc([10, -5, 20], [1, -2, 3], 40.0, [1, 1, 0], 1.5 * math.pi),
                               law("LINEAR", [3.0, 10.0])),
    "pipe-bezier": Canal("pipe-bezier",
                         Bezier([[0, 0, 0], [25, 35, 15], [60, -25, 35], [90, 10, 5]]),
                         law("CONST", [4.0])),
}
FLOOR = Canal("floor", Floor(), law("COS", [5.5, 10.5, 2.0]), ref=[0, 0, -1])


def fd4(f, x, h):
    """4th-order central difference of a vector function"""
    return (-f(x + 2 * h) + 8 * f(x + h) - 8 * f(x - h) + f(x - 2 * h)) / (12 * h)


def sample_frames(cn, us):
    """reference RMF vectors N1 at the sample parameters us (sorted, us[0] > 0)"""
    return [fr for fr, _ in ref_lines(cn, [], [0.0] + list(us))[1:]]


def near_points(cn, u, N1, th, hs, off=0.0):
    """m and n at (u + h, th) for h in hs, the frame carried from (u, N1) by rmf_step"""
    return [cn.point(u + h, th, rmf_step(cn, u, N1, h) if h else N1, off) for h in hs]


def partials1(cn, u, N1, th, h, ht):
    """m, n, m_u, m_th, m_uu, m_uth, m_thth by 4th-order central differences of m itself"""
    hs = [-2 * h, -h, 0.0, h, 2 * h]
    P = near_points(cn, u, N1, th, hs)
    m, n = P[2]
    d1 = lambda q: (q[0] - 8 * q[1] + 8 * q[3] - q[4]) / 12.0
    d2 = lambda q: (-q[0] + 16 * q[1] - 30 * q[2] + 16 * q[3] - q[4]) / 12.0
    mu = d1([p[0] for p in P]) / h
    muu = d2([p[0] for p in P]) / (h * h)
    Q = [cn.point(u, th + k * ht, N1) for k in (-2, -1, 0, 1, 2)]
    mt = d1([q[0] for q in Q]) / ht
    mtt = d2([q[0] for q in Q]) / (ht * ht)
    # mixed: d/du of m_th (m_th by 4th-order differences at each u + k h)
    mts = []
    for hk in hs:
        Nk = rmf_step(cn, u, N1, hk) if hk else N1
        Qk = [cn.point(u + hk, th + j * ht, Nk)[0] for j in (-2, -1, 1, 2)]
        mts.append((Qk[0] - 8 * Qk[1] + 8 * Qk[2] - Qk[3]) / (12 * ht))
    mut = d1(mts) / h
    return m, n, mu, mt, muu, mut, mtt


def partials(cn, u, N1, th, h=5e-4, ht=1e-3):
    """partials1 at h and h/2, Richardson-extrapolated in u (truncation O(h^6): the
    residuals below are then the formulas' own, down to ~1e-10 relative)"""
    A = partials1(cn, u, N1, th, h, ht)
    B = partials1(cn, u, N1, th, h / 2, ht)
    return tuple(b if i in (0, 1, 3, 6) else (16 * b - a) / 15 for i, (a, b) in
                 enumerate(zip(A, B)))


def formula(cn, u, N1, th):
    """the document's closed forms at (u, th): theta'(per u), kappa_E, kappa_th (per s),
    g = a_s + b kappa_E, D = b^2 - R g, kappa2 = g / D, e_th"""
    g = cn.geom(u)
    N1, N2 = cn.frame_of(g, N1)
    k1, k2 = g["Tu"] @ N1 / g["v"], g["Tu"] @ N2 / g["v"]  # per unit s
    kE = k1 * math.cos(th) + k2 * math.sin(th)
    kT = k2 * math.cos(th) - k1 * math.sin(th)
    gg = g["a_s"] + g["b"] * kE
    D = g["b"] ** 2 - g["R"] * gg
    eth = -math.sin(th) * N1 + math.cos(th) * N2
    return dict(g, N1=N1, N2=N2, k1=k1, k2=k2, kE=kE, kT=kT, thp=g["a"] / g["b"] * kT * g["v"],
                gg=gg, D=D, k2c=gg / D if D else math.inf, eth=eth)


ALL = list(SHAPES.values()) + [FLOOR]
US = [0.07 + 0.86 * k / 6 for k in range(7)]
THS = [0.3 + 0.9 * j for j in range(7)]


def sec_surface():
    print("== 1. the surface, the frame, the orthogonal-trajectory equation (pointwise)")
    env = fr = thp = thp_bad = mth = muth = nrm = jac = kap = rod1 = 0.0
    for cn in ALL:
        for u, N1 in zip(US, sample_frames(cn, US)):
            for th in THS:
                f = formula(cn, u, N1, th)
                m, n, mu, mt, muu, mut, mtt = partials(cn, u, N1, th)
                # envelope: |m - c| = R and (m - c).T = -R a (the sphere family's d/ds)
                env = max(env, abs(np.linalg.norm(m - f["c"]) - f["R"]) / f["R"],
                          abs((m - f["c"]) @ f["T"] + f["R"] * f["a"]) / f["R"])
                # the orthogonality condition -(m_u.m_th)/(m_th.m_th) against the formula
                ref = -(mu @ mt) / (mt @ mt)
                thp = max(thp, abs(ref - f["thp"]) / (1.0 + abs(ref)))
                thp_bad = max(thp_bad, abs(ref + f["thp"]) / (1.0 + abs(ref)))
                # m_th = R b e_th, and m_u . e_th = -R a kappa_th |c_u|
                mth = max(mth, np.linalg.norm(mt - f["R"] * f["b"] * f["eth"]) / f["R"])
                muth = max(muth, abs(mu @ f["eth"] + f["R"] * f["a"] * f["kT"] * f["v"]) /
                           (f["R"] * f["v"]))
                # normal: m_u x m_th = -|c_u| R D n
                cr = np.cross(mu, mt)
                sc = f["R"] * (1.0 + abs(f["D"]))
                nrm = max(nrm, np.linalg.norm(cr / f["v"] + f["R"] * f["D"] * n) / sc)
                jac = max(jac, abs(np.linalg.norm(cr) / f["v"] - f["R"] * abs(f["D"])) / sc)
                # principal curvatures from the two fundamental forms (n outward; II = m_ij.n)
                I = np.array([[mu @ mu, mu @ mt], [mu @ mt, mt @ mt]])
                II = np.array([[muu @ n, mut @ n], [mut @ n, mtt @ n]])
                ks = np.sort(np.linalg.eigvals(np.linalg.solve(I, II)).real)
                want = np.sort([-1.0 / f["R"], f["k2c"]])
                kap = max(kap, np.max(np.abs(ks - want) / (1.0 / f["R"] + np.abs(want))))
                # the circles: Rodrigues n_th = m_th / R (kappa1 = -1/R)
                ht = 1e-4
                nt = (cn.point(u, th + ht, N1)[1] - cn.point(u, th - ht, N1)[1]) / (2 * ht)
                rod1 = max(rod1, np.linalg.norm(nt - mt / f["R"]))
    check("envelope |m-c|=R, (m-c).T=-Ra (rel)", env, 1e-13)
    check("m_th = R b e_th (rel R)", mth, 1e-10)
    check("m_u . e_th = -R a kappa_th |c_u| (rel R|c_u|)", muth, 1e-8)
    check("theta' = (a/b)(k2 cos - k1 sin) vs -(m_u.m_th)/|m_th|^2", thp, 1e-8)
    print(f"        (the opposite sign would leave a residual of {thp_bad:.3e})")
    check("m_u x m_th = -|c_u| R D n, D = b^2 - R a_s - R b kE (rel R(1+|D|))", nrm, 1e-8)
    check("Jacobian |m_s x m_th| = R |D| (rel R(1+|D|))", jac, 1e-8)
    check("principal curvatures {-1/R, g/(b^2-Rg)} vs eig(I^-1 II) (rel)", kap, 1e-6)
    check("circles are curvature lines: |n_th - m_th/R|", rod1, 1e-7)


def sec_frame():
    print("== 2. the rotation-minimizing frame")
    H = SHAPES["helix-cos"]
    nodes = list(np.linspace(0.0, 1.0, 65))
    out = ref_lines(H, [], nodes)
    hel = 0.0
    for u, (N1, _) in zip(nodes, out):
        T, N1c = H.sp.closed_rmf(u)
        hel = max(hel, np.linalg.norm(N1 - N1c))
    check("helix: integrated RMF vs closed form N1 = cos(-tau s)N + sin(-tau s)B", hel, 1e-10)
    worst = 0.0
    for cn in ALL:
        for u, N1 in zip(US, sample_frames(cn, US)):
            # rotation rate about T: N1_u . N2 = 0 (4th-order differences of the frame)
            g = cn.geom(u)
            Ns = [cn.frame_of(cn.geom(u + h), rmf_step(cn, u, N1, h))[0]
                  for h in (-5e-4, -2.5e-4, 2.5e-4, 5e-4)]
            d = (Ns[0] - 8 * Ns[1] + 8 * Ns[2] - Ns[3]) / (12 * 2.5e-4)
            worst = max(worst, abs(d @ np.cross(g["T"], N1)) / g["v"])
    check("RMF: N1' . N2 = 0 along every spine (per mm)", worst, 1e-9)




def along(vals, k, h):
    """d/du at node k of a sampled vector function (spacing h): 4th-order central
    differences at h and 2h, Richardson-extrapolated (O(h^6))"""
    a = (vals[k - 2] - 8 * vals[k - 1] + 8 * vals[k + 1] - vals[k + 2]) / (12 * h)
    b = (vals[k - 4] - 8 * vals[k - 2] + 8 * vals[k + 2] - vals[k + 4]) / (24 * h)
    return (16 * a - b) / 15


def line_samples(cn, th0, n=2048, off=0.0):
    """the reference lines (theta' of the document, RMF ODE) at n + 1 nodes: per line the
    lists of m, n, and per node the frame N1 and the angles"""
    nodes = list(np.linspace(0.0, 1.0, n + 1))
    st = ref_lines(cn, th0, nodes)
    ms = [[cn.point(u, th[j], N1, off) for u, (N1, th) in zip(nodes, st)] for j in range(len(th0))]
    return nodes, st, ms


TH0 = [0.3 + 0.9 * j for j in range(7)]


def sec_lines():
    print("== 3. the lines: orthogonal to the circles, curvature lines, and the pipe")
    orth = rod = kap = dev_const = pipe_rod = pipe_orth = tan = 0.0
    for cn in ALL:
        nodes, st, ms = line_samples(cn, TH0)
        h = nodes[1] - nodes[0]
        for j in range(len(TH0)):
            M = [p[0] for p in ms[j]]
            Nn = [p[1] for p in ms[j]]
            for k in range(8, len(nodes) - 8, 40):
                u, (N1, th) = nodes[k], st[k]
                dm, dn = along(M, k, h), along(Nn, k, h)
                f = formula(cn, u, N1, th[j])
                mt = f["R"] * f["b"] * f["eth"]
                orth = max(orth, abs(math.degrees(math.asin(
                    (dm @ mt) / (np.linalg.norm(dm) * np.linalg.norm(mt))))))
                rod = max(rod, np.linalg.norm(np.cross(dn, dm)) /
                          (np.linalg.norm(dn) * np.linalg.norm(dm) + 1e-300))
                kap = max(kap, np.linalg.norm(dn + f["k2c"] * dm) / np.linalg.norm(dn))
                # the line's velocity per unit spine length: (D/b)(b T + a E)
                E = math.cos(th[j]) * f["N1"] + math.sin(th[j]) * f["N2"]
                vel = f["D"] / f["b"] * (f["b"] * f["T"] + f["a"] * E)
                tan = max(tan, np.linalg.norm(dm / f["v"] - vel) / (1 + np.linalg.norm(vel)))
        # theta = const with the RMF: orthogonal (a curvature line) only where a = 0
        for k in range(8, len(nodes) - 8, 40):
            for j, t0 in enumerate(TH0):
                u = nodes[k]
                dm = along([cn.point(nodes[i], t0, st[i][0])[0] for i in range(k - 4, k + 5)],
                           4, h)
                mt = cn.point(u, t0 + 1e-6, st[k][0])[0] - cn.point(u, t0 - 1e-6, st[k][0])[0]
                ang = abs(math.degrees(math.asin((dm @ mt) /
                                                 (np.linalg.norm(dm) * np.linalg.norm(mt)))))
                if cn.name.startswith("pipe"):
                    pipe_orth = max(pipe_orth, ang)
                    nn = [cn.point(nodes[i], t0, st[i][0])[1] for i in range(k - 4, k + 5)]
                    dn = along(nn, 4, h)
                    pipe_rod = max(pipe_rod, np.linalg.norm(np.cross(dn, dm)) /
                                   (np.linalg.norm(dn) * np.linalg.norm(dm)))
                else:
                    dev_const = max(dev_const, ang)
    check("family 2 orthogonal to the circles: max |90 deg - angle| (deg)", orth, 1e-6)
    check("family 2 curvature lines: |dn x dm| / (|dn||dm|)", rod, 1e-8)
    check("Rodrigues dn = -kappa2 dm, kappa2 = g/(b^2 - R g) (rel)", kap, 1e-7)
    check("line velocity dm/ds = (D/b)(b T + a E) (rel)", tan, 1e-7)
    check("pipe (R const): theta = const lines orthogonal to circles (deg)", pipe_orth, 1e-6)
    check("pipe (R const): theta = const lines are curvature lines", pipe_rod, 1e-8)
    print(f"        (theta = const with R not const is NOT: it meets the circles up to "
          f"{dev_const:.3f} deg off 90)")


def sec_riccati():
    print("== 4. Riccati form, the 2x2 linear system, the Mobius transport")
    rng = np.random.default_rng(18)
    ric = lin = 0.0
    for _ in range(2000):
        a, k1, k2, th = rng.uniform(-0.95, 0.95), *rng.normal(size=2), rng.uniform(-3.1, 3.1)
        b = math.sqrt(1 - a * a)
        thp = a / b * (k2 * math.cos(th) - k1 * math.sin(th))
        w = math.tan(th / 2)
        al, be = a * k2 / (2 * b), a * k1 / (2 * b)
        ric = max(ric, abs((1 + w * w) / 2 * thp - (al * (1 - w * w) - 2 * be * w)) / (1 + w * w))
        rho = rng.uniform(0.1, 10)
        y = rho * np.array([math.sin(th / 2), math.cos(th / 2)])
        yp = np.array([[-be, al], [al, be]]) @ y
        lin = max(lin, abs(2 * (y[1] * yp[0] - y[0] * yp[1]) / (y @ y) - thp))
    check("w' = alpha(1 - w^2) - 2 beta w, alpha = a k2/2b, beta = a k1/2b", ric, 1e-14)
    check("(y1,y2)' = [[-beta, alpha],[alpha, beta]] y gives theta' (theta = 2 atan2 y)", lin,
          1e-13)
    det = mob = mobw = 0.0
    ths = [k * TWO_PI / 12 for k in range(12)]  # includes theta0 = pi (w0 = infinity)
    for cn in ALL:
        def f(u, y):
            g = cn.geom(u)
            N1, N2 = cn.frame_of(g, y[:3])
            k1, k2 = g["Tu"] @ N1, g["Tu"] @ N2  # per u
            al, be = g["a"] * k2 / (2 * g["b"]), g["a"] * k1 / (2 * g["b"])
            A = np.array([[-be, al], [al, be]])
            d = np.empty(7)
            d[:3] = -(y[:3] @ g["Tu"]) * g["T"]
            d[3:] = (A @ y[3:].reshape(2, 2)).ravel()
            return d

        nodes = list(np.linspace(0.0, 1.0, 17))
        Ms = dp45(f, np.concatenate([cn.N10, [1.0, 0, 0, 1.0]]), nodes)
        direct = ref_lines(cn, ths, nodes)
        for y, (_, th) in zip(Ms, direct):
            M = y[3:].reshape(2, 2)
            det = max(det, abs(np.linalg.det(M) - 1))
            for j, t0 in enumerate(ths):
                z = M @ np.array([math.sin(t0 / 2), math.cos(t0 / 2)])
                mob = max(mob, abs(wrap(2 * math.atan2(z[0], z[1]) - th[j])))
                if abs(wrap(t0 - math.pi)) > 0.1:
                    w0 = math.tan(t0 / 2)
                    w = (M[0, 0] * w0 + M[0, 1]) / (M[1, 0] * w0 + M[1, 1])
                    mobw = max(mobw, abs(wrap(2 * math.atan(w) - th[j])))
    check("det M(s) = 1 (M integrated with the RMF, adaptive)", det, 1e-10)
    check("Mobius (homogeneous y = M y0) vs direct theta ODE (rad)", mob, 1e-10)
    check("Mobius w = (M11 w0 + M12)/(M21 w0 + M22) vs direct (rad)", mobw, 1e-10)

    # planar spine (here the tilted arc; the RMF is N1 = the principal normal, k2 = 0):
    # alpha = 0, so w = w0 exp(-2 int beta ds) = w0 exp(-int a kappa / b ds)
    cn = SHAPES["arc-tilted-linear"]
    nodes = list(np.linspace(0.0, 1.0, 9))
    ths = [0.4, 1.3, 2.2, -0.7]
    pl = 0.0
    for u, (_, th) in zip(nodes, ref_lines(cn, ths, nodes)):
        g = cn.geom(u)
        for j, t0 in enumerate(ths):
            w = math.tan(t0 / 2) * math.exp(-g["a"] / 40.0 / g["b"] * cn.L * u)
            pl = max(pl, abs(wrap(2 * math.atan(w) - th[j])))
    check("planar spine: tan(theta/2) = tan(theta0/2) exp(-int a kappa/b ds) (rad)", pl, 1e-10)


def canal_closed(w, t, r_off=0.0):
    """MATH-canal section 7 closed form of the paper example's line w at t (contact frame):
    the point, the contact-frame angle u, and with r_off the ball-end centre m - r_off n"""
    R = 5.5 * math.cos(2 * t) + 10.5
    p = -(11.0 / 3.0) * math.sin(2 * t)
    lam = w + (11.0 / 6.0) * (math.cos(2 * t) - 1.0)
    s = 2 * R / (1 + p * p + lam * lam)
    tC = np.array([-math.sin(t), math.cos(t), 0.0])
    nC = np.array([-math.cos(t), -math.sin(t), 0.0])
    C = 3 * np.array([math.cos(t), math.sin(t), 0.0])
    k = np.array([0.0, 0.0, 1.0])
    N = -p * tC + lam * nC + k
    n = 2 * N / (N @ N) - k
    m = C + s * (-p * tC + lam * nC + k)
    q = math.sqrt(1 + p * p)
    return m - r_off * n, 2 * math.atan2(q, lam)


def sec_floor():
    print("== 5. the floor fillet: SPINE on c = C + R e_z is the canal model")
    ws = [-6.0, -2.0, 2.0, 12.0, 0.1, 40.0]
    u0s = [2 * math.atan2(1.0, w) for w in ws]  # q(t0) = 1 here: u0 = 2 atan2(q0, w)
    nodes = list(np.linspace(0.0, 1.0, 129))
    st = ref_lines(FLOOR, u0s, nodes)  # reference direction -e_z: theta0 = u0
    dm = dphi = 0.0
    # phi(t) = int_0^t R' c kappa_C / sigma dt (= int a b kappa_C ds): composite Simpson,
    # 32 panels per node interval (error < 1e-13 rad)
    ts = [TWO_PI * u for u in nodes]
    gfun = lambda t: -11 * math.sin(2 * t) / math.sqrt(9 + 121 * math.sin(2 * t) ** 2)
    phi = [0.0]
    for k in range(1, len(ts)):
        x = np.linspace(ts[k - 1], ts[k], 65)
        y = np.array([gfun(v) for v in x])
        phi.append(phi[-1] + (x[1] - x[0]) / 3 * (y[0] + y[-1] + 4 * y[1:-1:2].sum() +
                                                  2 * y[2:-1:2].sum()))
    for k, (u, (N1, th)) in enumerate(zip(nodes, st)):
        for j, w in enumerate(ws):
            mc, uc = canal_closed(w, ts[k])
            ms = FLOOR.point(u, th[j], N1)[0]
            dm = max(dm, np.linalg.norm(ms - mc))
            dphi = max(dphi, abs(wrap(th[j] - uc - phi[k])))
    check("floor: spine lines (theta0 = u0, N1(0) = -e_z) vs canal closed form (mm)", dm, 1e-8)
    check("floor: theta(t) - u(t) = phi(t) = int R' c kappa_C/sigma dt (rad)", dphi, 1e-9)
    print(f"        (RMF holonomy over the closed spine: phi(2 pi) = {phi[-1]:.2e} rad)")
    # the default reference direction (the principal normal): theta0 = u0 + atan2(-3, 22)
    pn = Canal("floor-pn", Floor(), law("COS", [5.5, 10.5, 2.0]))
    phi0 = math.atan2(-3.0, 22.0)
    e1 = np.array([0.0, 0.0, -1.0])
    T0 = unit(Floor().jet(0.0)[1])
    got0 = math.atan2(e1 @ np.cross(T0, pn.N10), e1 @ pn.N10)
    check("floor: phi0 = atan2(e1.N2, e1.N1) = atan2(-3, 22) (principal normal)",
          abs(got0 - phi0), 1e-15)
    st2 = ref_lines(pn, [u + phi0 for u in u0s], nodes[::8])
    dm2 = 0.0
    for u, (N1, th) in zip(nodes[::8], st2):
        for j, w in enumerate(ws):
            dm2 = max(dm2, np.linalg.norm(pn.point(u, th[j], N1)[0] - canal_closed(w, TWO_PI * u)[0]))
    check("floor: principal-normal start, theta0 = u0 - 0.1355277 vs canal (mm)", dm2, 1e-8)
    # the cuspidal edge: D = 0 exactly where MATH-canal's lambda+- are (D_canal = 0)
    dz = 0.0
    for t in np.linspace(0.85, 2.30, 9):
        R = 5.5 * math.cos(2 * t) + 10.5
        p = -(11.0 / 3.0) * math.sin(2 * t)
        disc = (R / 3) ** 2 - 1 - p * p + 2 * R * (-(22.0 / 9.0) * math.cos(2 * t))
        u = t / TWO_PI
        k = int(round(u * 128))  # the frame at the nearest node, carried by one RK4 step
        N1 = rmf_step(FLOOR, nodes[k], st[k][0], u - nodes[k])
        for sgn in (1, -1):
            lam = R / 3 + sgn * math.sqrt(disc)
            uc = 2 * math.atan2(math.sqrt(1 + p * p), lam)
            # theta of the point at contact angle uc: the angle of its E in the RMF, with
            # the contact frame e1 = (a T - e_z)/b, e2 = n_C (MATH-canal section 2.2)
            g = FLOOR.geom(u)
            N1u, N2u = FLOOR.frame_of(g, N1)
            e1 = (g["a"] * g["T"] - np.array([0, 0, 1.0])) / g["b"]
            e2 = np.array([-math.cos(t), -math.sin(t), 0.0])
            E = math.cos(uc) * e1 + math.sin(uc) * e2
            th = math.atan2(E @ N2u, E @ N1u)
            dz = max(dz, abs(formula(FLOOR, u, N1, th)["D"]))
    check("floor: D(t, theta) = 0 on the canal's cuspidal edge lambda+-", dz, 1e-12)



def sec_offset():
    print("== 6. ball-end tool: the offset surface m + d n is the canal surface of R + d")
    env = rod = orth = jac = 0.0
    for cn in ALL:
        for d in (1.5, -1.5):  # outside tool (+r) and inside tool (-r); every R here > 1.5
            nodes, st, ms = line_samples(cn, TH0[1:3], n=2048, off=d)
            h = nodes[1] - nodes[0]
            for j in range(2):
                M = [p[0] for p in ms[j]]
                Nn = [p[1] for p in ms[j]]
                for k in range(8, len(nodes) - 8, 96):
                    u, (N1, th) = nodes[k], st[k]
                    f = formula(cn, u, N1, th[j])
                    m = M[k]
                    env = max(env, abs(np.linalg.norm(m - f["c"]) - (f["R"] + d)) / f["R"],
                              abs((m - f["c"]) @ f["T"] + (f["R"] + d) * f["a"]) / f["R"])
                    dm, dn = along(M, k, h), along(Nn, k, h)
                    rod = max(rod, np.linalg.norm(np.cross(dn, dm)) /
                              (np.linalg.norm(dn) * np.linalg.norm(dm)))
                    mt = (f["R"] + d) * f["b"] * f["eth"]
                    orth = max(orth, abs(dm @ mt) / (np.linalg.norm(dm) * np.linalg.norm(mt)))
                    # offset Jacobian |m_s x m_th| = (R + d)|b^2 - (R + d) g| (FD in u, th)
                    P = [cn.point(nodes[i], th[j], st[i][0], d)[0] for i in range(k - 4, k + 5)]
                    ht = 1e-4
                    mth = (cn.point(u, th[j] + ht, N1, d)[0] - cn.point(u, th[j] - ht, N1, d)[0])
                    mth /= 2 * ht
                    mus = along(P, 4, h) / f["v"]
                    want = (f["R"] + d) * abs(f["b"] ** 2 - (f["R"] + d) * f["gg"])
                    jac = max(jac, abs(np.linalg.norm(np.cross(mus, mth)) - want) /
                              ((f["R"] + d) * (1 + want)))
    check("offset: |m - c| = R + d, (m - c).T = -(R + d) a (rel)", env, 1e-12)
    check("offset: the same theta lines are its curvature lines", rod, 1e-8)
    check("offset: and orthogonal to its circles (|cos|)", orth, 1e-8)
    check("offset Jacobian (R + d)|b^2 - (R + d) g| (rel)", jac, 1e-7)
    # the canal model's tool centre m - r n (canal.h) is this document's inside tool
    nodes = list(np.linspace(0.0, 1.0, 33))
    st = ref_lines(FLOOR, [2 * math.atan2(1.0, 12.0)], nodes)
    tool = 0.0
    for u, (N1, th) in zip(nodes, st):
        mc = canal_closed(12.0, TWO_PI * u, r_off=2.0)[0]
        tool = max(tool, np.linalg.norm(FLOOR.point(u, th[0], N1, off=-2.0)[0] - mc))
    check("canal tool centre m - r n = spine point of radius R - r (mm)", tool, 1e-9)



# ------------------------------------------------------------ 7. fixed-step numerics


def fixed_transport(cn, N, th0s, scheme="magnus4", dt=np.float64):
    """the firmware's candidate schemes, every operation in dt (np.float64 or np.float32;
    the jets are computed in double and rounded to dt): the RMF by double reflection (Wang,
    Juttler, Zheng, Liu 2008) on the 2N + 1 nodes u_k = k/2N, and M(u) by N fixed steps of
    Magnus-4 (Simpson nodes) or classical RK4 over the same nodes. Returns per output node
    i = 0..N the points of the lines th0s, from (u_i, M_i y0) only, and the DR frames."""
    F = lambda x: dt(x)
    K = 2 * N
    X, T, P = [], [], []
    for k in range(K + 1):
        u = k / K
        c, c1, c2 = cn.sp.jet(u)
        R, Ru, _ = cn.R(u)
        X.append(c.astype(dt))
        t = c1.astype(dt)
        T.append(t / np.sqrt(t @ t))
        v = np.linalg.norm(c1)
        # per-node constants: R, a, b and the factor of alpha, beta: R_u / (2 b |c_u|^2)
        P.append((F(R), F(Ru / v), F(math.sqrt(1 - (Ru / v) ** 2)),
                  F(Ru / (2 * v * math.sqrt(v * v - Ru * Ru))), c2.astype(dt)))
    # double reflection: r_{k+1} = H2 H1 r_k (two Householder reflections)
    r = [cn.N10.astype(dt)]
    two = F(2)
    for k in range(K):
        v1 = X[k + 1] - X[k]
        c1 = v1 @ v1
        rL = r[k] - (two / c1) * (v1 @ r[k]) * v1
        tL = T[k] - (two / c1) * (v1 @ T[k]) * v1
        v2 = T[k + 1] - tL
        c2 = v2 @ v2
        r.append(rL - (two / c2) * (v2 @ rL) * v2 if c2 > 0 else rL)

    def A(k):  # generator per unit u at node k: [[-beta, alpha], [alpha, beta]]
        f, c2 = P[k][3], P[k][4]
        n1 = r[k]
        n2 = np.cross(T[k], n1)
        al, be = f * (c2 @ n2), f * (c2 @ n1)
        return np.array([[-be, al], [al, be]], dtype=dt)

    h = F(1.0 / N)
    M = np.eye(2, dtype=dt)
    comp = np.zeros((2, 2), dtype=dt)  # Kahan compensation of M's entries
    Ms = [M]
    d2max = 0.0
    for i in range(N):
        A0, Am, A1 = A(2 * i), A(2 * i + 1), A(2 * i + 2)
        if scheme.startswith("magnus4"):
            Om = (h / F(6)) * (A0 + F(4) * Am + A1) - (h * h / F(12)) * (Am @ (A1 - A0) -
                                                                          (A1 - A0) @ Am)
            d2 = Om[0, 0] * Om[0, 0] + Om[0, 1] * Om[1, 0]  # Om^2 = d2 I (traceless)
            d2max = max(d2max, abs(float(d2)))
            # exp(Om) - I = (C - 1) I + S Om, C = cosh(d), S = sinh(d)/d as series in d2 = d^2
            # (|d2| <= 1e-2 here: the terms kept leave < 1e-20 in double, < ulp in float);
            # the increment form keeps the small part's bits (no 1 + small rounding)
            Cm1 = d2 * (F(1 / 2) + d2 * (F(1 / 24) + d2 * (F(1 / 720) + d2 * F(1 / 40320))))
            S = F(1) + d2 * (F(1 / 6) + d2 * (F(1 / 120) + d2 * (F(1 / 5040) + d2 * F(1 / 362880))))
            inc = Cm1 * M + S * (Om @ M)
            if scheme == "magnus4-naive":  # exp(Om) formed first: 1 + small rounds
                M = ((F(1) + Cm1) * np.eye(2, dtype=dt) + S * Om) @ M
                Ms.append(M)
                continue
        else:
            K1 = A0 @ M
            K2 = Am @ (M + (h / two) * K1)
            K3 = Am @ (M + (h / two) * K2)
            K4 = A1 @ (M + h * K3)
            inc = (h / F(6)) * (K1 + two * K2 + two * K3 + K4)
        if scheme.endswith("kahan"):
            y = inc - comp
            t = M + y
            comp = (t - M) - y
            M = t
        else:
            M = M + inc
        Ms.append(M)
    pts = []
    for i in range(N + 1):
        k = 2 * i
        R, a, b = P[k][0], P[k][1], P[k][2]
        n1 = r[k] - (r[k] @ T[k]) * T[k]
        n1 = n1 / np.sqrt(n1 @ n1)
        n2 = np.cross(T[k], n1)
        row = []
        for t0 in th0s:
            y = Ms[i] @ np.array([math.sin(t0 / 2), math.cos(t0 / 2)], dtype=dt)
            q = y @ y
            ct, st = (y[1] * y[1] - y[0] * y[0]) / q, (two * y[0] * y[1]) / q
            row.append(X[k] + R * (-a * T[k] + b * (ct * n1 + st * n2)))
        pts.append(row)
    assert pts[-1][0].dtype == dt
    fixed_transport.d2max = d2max
    return pts, r[::2], Ms


def ref_points(cn, th0s, N):
    nodes = list(np.linspace(0.0, 1.0, N + 1))
    st = ref_lines(cn, th0s, nodes, tol=1e-13)
    return [[cn.point(u, th[j], N1)[0] for j in range(len(th0s))]
            for u, (N1, th) in zip(nodes, st)], [N1 for N1, _ in st]


LINES8 = [k * TWO_PI / 8 + 0.1 for k in range(8)]


def dr_inverse_check(cn, N, dt):
    """DR forward over 2N steps, then the exact inverse r_k = H1 H2 r_{k+1} back: |r_0 - N10|
    (Magnus is exactly invertible too: exp(-Om))"""
    F = lambda x: dt(x)
    K = 2 * N
    X = [cn.sp.jet(k / K)[0].astype(dt) for k in range(K + 1)]
    T = [unit(cn.sp.jet(k / K)[1]).astype(dt) for k in range(K + 1)]
    r = cn.N10.astype(dt)
    two = F(2)
    refl = lambda v, x: x - (two / (v @ v)) * (v @ x) * v
    for k in range(K):
        v1 = X[k + 1] - X[k]
        v2 = T[k + 1] - refl(v1, T[k])
        r = refl(v2, refl(v1, r))
    for k in range(K - 1, -1, -1):
        v1 = X[k + 1] - X[k]
        v2 = T[k + 1] - refl(v1, T[k])
        r = refl(v1, refl(v2, r))
    return float(np.linalg.norm(r.astype(float) - cn.N10))


def curve_kt(sp, u, e=1e-5):
    """curvature, torsion and speed of the spine at u (c_uuu by a central difference)"""
    c, c1, c2 = sp.jet(u)
    c3 = (sp.jet(u + e)[2] - sp.jet(u - e)[2]) / (2 * e)
    x = np.cross(c1, c2)
    v = np.linalg.norm(c1)
    xx = x @ x
    return math.sqrt(xx) / v**3, ((x @ c3) / xx if xx > 1e-300 else 0.0), v


def q_dr(sp, u, e=2e-3):
    """the double-reflection error density Q = k^2 t^3 + k k_s t_s + 2 k_s^2 t - k k_ss t
    (s-derivatives by 4th-order differences in u with the chain rule)"""
    vals = [curve_kt(sp, u + j * e) for j in (-2, -1, 0, 1, 2)]
    k, t, v = vals[2]
    d1 = lambda q: (q[0] - 8 * q[1] + 8 * q[3] - q[4]) / (12 * e)
    d2 = lambda q: (-q[0] + 16 * q[1] - 30 * q[2] + 16 * q[3] - q[4]) / (12 * e * e)
    K, Tt, V = [x[0] for x in vals], [x[1] for x in vals], [x[2] for x in vals]
    vu = d1(V)
    ks, ts = d1(K) / v, d1(Tt) / v
    kss = d2(K) / v**2 - vu / v**3 * d1(K)
    return k * k * t**3 + k * ks * ts + 2 * ks * ks * t - k * kss * t, v


def a4_bound(cn, n=2048):
    """the a-priori terms: I4 = int_0^1 ||A~^(4)(u)|| du (A~ = the generator per unit u; 4th
    differences on n nodes with the reference RMF), Gamma = int ||A~|| du, R_max, and
    J = int_0^1 |Q| |c_u|^5 du (the double reflection's error density)"""
    nodes = list(np.linspace(0.0, 1.0, n + 1))
    fr = [N1 for N1, _ in ref_lines(cn, [], nodes)]
    al, be, rmax = [], [], 0.0
    for u, N1 in zip(nodes, fr):
        g = cn.geom(u)
        n1, n2 = cn.frame_of(g, N1)
        f = g["a"] / (2 * g["b"])
        al.append(f * (g["Tu"] @ n2))
        be.append(f * (g["Tu"] @ n1))
        rmax = max(rmax, g["R"])
    al, be, h = np.array(al), np.array(be), 1.0 / n
    d4 = lambda x: (x[:-4] - 4 * x[1:-3] + 6 * x[2:-2] - 4 * x[3:-1] + x[4:]) / h**4
    # ||[[-b, a], [a, b]]||_2 = sqrt(a^2 + b^2)
    i4 = np.mean(np.hypot(d4(al), d4(be)))
    gam = np.mean(np.hypot(al, be))
    qs = [q_dr(cn.sp, u) for u in np.linspace(0.004, 0.996, 249)]
    jq = np.mean([abs(q) * v**5 for q, v in qs])
    return i4, gam, rmax, jq


def dr_local_check():
    """one double-reflection step against the RMF ODE, on random Bezier spines: the
    deviation from -(h^5/720) Q, relative"""
    rng = np.random.default_rng(5)
    worst = 0.0
    for _ in range(4):
        cn = Canal("b", Bezier(rng.uniform(-40, 40, (4, 3))), law("CONST", [1.0]))
        us = list(np.linspace(0.15, 0.85, 5))
        for u, N1 in zip(us, sample_frames(cn, us)):
            hu = 0.004
            u0 = u - hu / 2
            N = rmf_step(cn, u, N1, -hu / 2)
            c0, c10, _ = cn.sp.jet(u0)
            c1_, c11, _ = cn.sp.jet(u0 + hu)
            T0, T1 = unit(c10), unit(c11)
            N = unit(N - (N @ T0) * T0)
            v1 = c1_ - c0
            rL = N - 2 / (v1 @ v1) * (v1 @ N) * v1
            tL = T0 - 2 / (v1 @ v1) * (v1 @ T0) * v1
            v2 = T1 - tL
            r1 = rL - 2 / (v2 @ v2) * (v2 @ rL) * v2
            Nx, uu = N.copy(), u0
            for _k in range(32):
                Nx = rmf_step(cn, uu, Nx, hu / 32)
                uu += hu / 32
            Nx = unit(Nx - (Nx @ T1) * T1)
            err = math.atan2(np.cross(Nx, r1) @ T1, Nx @ r1)
            q, v = q_dr(cn.sp, u)
            hs = np.linalg.norm(v1)
            worst = max(worst, abs(err + hs**5 * q / 720) / (hs**5 * abs(q) / 720))
    return worst


def sec_numerics():
    print("== 7. fixed-step numerics (double reflection + Magnus-4 / RK4 on M)")
    H = SHAPES["helix-cos"]
    # DR order on the helix against its closed-form RMF
    errs = []
    for K in (32, 64, 128):
        r = H.N10.copy()
        for k in range(K):
            x0, t0 = H.sp.jet(k / K)[0], unit(H.sp.jet(k / K)[1])
            x1, t1 = H.sp.jet((k + 1) / K)[0], unit(H.sp.jet((k + 1) / K)[1])
            v1 = x1 - x0
            rL = r - 2 / (v1 @ v1) * (v1 @ r) * v1
            tL = t0 - 2 / (v1 @ v1) * (v1 @ t0) * v1
            v2 = t1 - tL
            r = rL - 2 / (v2 @ v2) * (v2 @ rL) * v2
        errs.append(np.linalg.norm(r - H.sp.closed_rmf(1.0)[1]))
    hh = H.sp
    kap = hh.r / (hh.r**2 + hh.h**2)
    tau = hh.h / (hh.r**2 + hh.h**2)
    pred = kap**2 * tau**3 / 720 * H.L * (H.L / 32) ** 4
    print(f"  DR on the helix, K = 32, 64, 128 steps: frame error {errs[0]:.3e} {errs[1]:.3e} "
          f"{errs[2]:.3e} (ratios {errs[0] / errs[1]:.2f}, {errs[1] / errs[2]:.2f})")
    check("DR global order 4 on the helix (|log2 ratio - 4|)",
          abs(math.log2(errs[1] / errs[2]) - 4), 0.05)
    check("DR helix error = kappa^2 tau^3 L h^4 / 720 (rel, K = 32)", abs(errs[0] / pred - 1), 0.02)
    for dt, bound in ((np.float64, 1e-13), (np.float32, 1e-5)):
        check(f"DR exactly invertible (H1 H2 back), {dt.__name__}, K = 512",
              dr_inverse_check(H, 256, dt), bound)
    shapes = list(SHAPES.values()) + [FLOOR]
    Ns = [8, 16, 32, 64, 128, 256]
    print("\n  double: max |m - m_ref| (mm) over the nodes and 8 lines; N transport steps "
          "(2N DR steps)")
    print("  | shape | L mm | " + " | ".join(f"N={N}" for N in Ns) + " | C = err N^4 |")
    table = {}
    for cn in shapes:
        ref, _ = ref_points(cn, LINES8, 256)
        row = []
        for N in Ns:
            pts = fixed_transport(cn, N, LINES8)[0]
            st = 256 // N
            row.append(max(np.linalg.norm(pts[i][j] - ref[i * st][j])
                           for i in range(N + 1) for j in range(8)))
        C = max(e * N**4 for e, N in zip(row, Ns) if N >= 32)
        table[cn.name] = (row, C, ref)
        print(f"  | {cn.name} | {cn.L:.1f} | " + " | ".join(f"{e:.2e}" for e in row) +
              f" | {C:.3g} |")
    check("DR local error = -(h^5/720)(k^2 t^3 + k k' t' + 2 k'^2 t - k k'' t) (rel)",
          dr_local_check(), 2e-2)
    print("\n  step counts for eps = 1 um, 0.1 um, 1 nm: measured N = ceil((C/eps)^(1/4)); "
          "a-priori C_A = R_max [e^(2 Gamma) I4/1440 + (1 + e^(2 Gamma)) J/11520]")
    print("  | shape | Gamma | I4 | J | C | C_A | N 1 um | N 0.1 um | N 1 nm | N_A 1 um | "
          "N_A 0.1 um |")
    for cn in shapes:
        row, C, _ = table[cn.name]
        i4, gam, rmax, jq = a4_bound(cn)
        ca = rmax * (math.exp(2 * gam) * i4 / 1440 + (1 + math.exp(2 * gam)) * jq / 11520)
        nn = [math.ceil((C / e) ** 0.25) for e in (1e-3, 1e-4, 1e-6)]
        na = [math.ceil((ca / e) ** 0.25) for e in (1e-3, 1e-4)]
        print(f"  | {cn.name} | {gam:.3f} | {i4:.3g} | {jq:.3g} | {C:.3g} | {ca:.3g} | {nn[0]} | "
              f"{nn[1]} | {nn[2]} | {na[0]} | {na[1]} |")
    # RK4 on M against Magnus-4 (double), N = 32
    cn = SHAPES["helix-cos"]
    ref = table[cn.name][2]
    for sch in ("magnus4", "rk4"):
        pts = fixed_transport(cn, 32, LINES8, sch)[0]
        e = max(np.linalg.norm(pts[i][j] - ref[i * 8][j]) for i in range(33) for j in range(8))
        print(f"  helix-cos, N = 32, {sch}: {e:.3e} mm")
    if QUICK:
        return
    print("\n  float32 (every operation after the jets; Magnus-4 in increment form + Kahan on M)")
    Nf = [16, 32, 64, 128, 256]
    print("  | shape | " + " | ".join(f"N={N}" for N in Nf) + " |")
    for cn in shapes:
        ref = table[cn.name][2]
        row = []
        for N in Nf:
            pts = fixed_transport(cn, N, LINES8, "magnus4-kahan", np.float32)[0]
            st = 256 // N
            row.append(max(np.linalg.norm(pts[i][j].astype(float) - ref[i * st][j])
                           for i in range(N + 1) for j in range(8)))
        print(f"  | {cn.name} | " + " | ".join(f"{e:.2e}" for e in row) + " |")
        fixed_transport(cn, 16, LINES8)
        print(f"      (max |delta^2| of the exp series at N = 16: {fixed_transport.d2max:.2e})")
    cn = SHAPES["arc-tilted-linear"]
    ref = ref_points(cn, LINES8, 512)[0]
    for sch in ("magnus4-naive", "magnus4", "magnus4-kahan"):
        pts, _, Ms = fixed_transport(cn, 512, LINES8, sch, np.float32)
        e = max(np.linalg.norm(pts[i][j].astype(float) - ref[i][j])
                for i in range(513) for j in range(8))
        dd = max(abs(np.linalg.det(M.astype(float)) - 1) for M in Ms)
        print(f"  tilted arc, float32, N = 512, {sch}: {e:.2e} mm, max |det M - 1| {dd:.1e}")
    # the paper example's regular band (the canal tests' lines, u0 in [-0.5, 0.125])
    band = list(np.linspace(-0.5, 0.125, 6))
    ref, _ = ref_points(FLOOR, band, 1024)
    print("\n  floor, regular band u0 in [-0.5, 0.125] (6 lines): max |m - m_ref| (mm)")
    print("  | N | double | float32 |")
    for N in (128, 256, 512, 1024):
        e = []
        for dt in (np.float64, np.float32):
            pts = fixed_transport(FLOOR, N, band, "magnus4-kahan", dt)[0]
            st = 1024 // N
            e.append(max(np.linalg.norm(pts[i][j].astype(float) - ref[i * st][j])
                         for i in range(N + 1) for j in range(len(band))))
        print(f"  | {N} | {e[0]:.2e} | {e[1]:.2e} |")

def main():
    sec_surface()
    sec_frame()
    sec_lines()
    sec_riccati()
    sec_floor()
    sec_offset()
    sec_numerics()
    print(f"verify-spine: {sum(results)} passed, {len(results) - sum(results)} failed")
    return 0 if all(results) else 1


if __name__ == "__main__":
    sys.exit(main())
