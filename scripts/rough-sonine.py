#!/usr/bin/env python3
"""Derivation of the collisional moments of rough spheres (3D) and disks (2D) in the first
Sonine approximation: the record of how the closed forms of
crates/gas/src/theory/rough_sonine.rs were obtained (sympy; not run by the build or tests,
whose oracles are Monte Carlo averages of the collision rule and an exact quadrature).

Trial distribution in the scaled velocities c = v / sqrt(2 T_tr / m),
w = omega / sqrt(2 T_rot / I) (each Gaussian factor pi^{-d/2} exp(-x^2)):

  f = phi(c) phi(w) [1 + a20 S2(c^2) + a02 S2(w^2) + a11 S1(c^2) S1(w^2)],
  S1(x) = d/2 - x,  S2(x) = x^2/2 - (d+2) x/2 + d (d+2)/8   (d = d_t or d_r).

Collision (n the unit normal from 1 to 2, approaching g . n > 0), in the variables c and
s = (sigma/2) omega / sqrt(2 T_tr/m) = lam w, lam^2 = theta / q:
  g = c1 - c2, g_ct = g - (g.n) n + (s1 + s2) x n,
  c1' = c1 - (1+alpha)/2 (g.n) n - eta g_ct,  c2' = c2 + ...,
  s1' = s1 - (eta/q) n x g_ct,  s2' = s2 - (eta/q) n x g_ct.

Every collisional moment is E[(g.n)^+ Delta psi W] over the Gaussian pair, W the Sonine
weight of both particles, linear in the cumulants; divided by E[(g.n)^+] = 1/sqrt(2 pi).
With c1 = C + g/2, c2 = C - g/2: C Gaussian with variance 1/4 a component, g with
variance 1 (g.n on the half line with the weight g.n), w's with variance 1/2.

Prints, per dimension, each moment as a polynomial in alpha, eta, q, theta.
"""
import sympy as sp
from sympy.polys.rings import ring
from sympy.polys.domains import QQ
from math import factorial

alpha, eta, q, theta = sp.symbols("alpha eta q theta")


def double_factorial(n):
    return 1 if n <= 0 else n * double_factorial(n - 2)


def gauss_moment(k, var):
    """E[x^k] for x ~ N(0, var)."""
    if k % 2:
        return 0
    return sp.Rational(double_factorial(k - 1)) * var ** (k // 2)


def half_line_moment(k):
    """E[x^+ x^k] / E[x^+] for x ~ N(0, 1): 2^{k/2} (k/2)! (k even)."""
    assert k % 2 == 0
    return sp.Integer(2 ** (k // 2) * factorial(k // 2))


def derive(dim):
    d_t, d_r = (3, 3) if dim == 3 else (2, 1)
    names = []
    names += [f"C{i}" for i in range(3)]
    names += [f"g{i}" for i in range(3)]
    names += [f"u{i}" for i in range(3)]  # w1
    names += [f"v{i}" for i in range(3)]  # w2
    names += ["al", "et", "qq", "qi", "la", "li"]
    R, *gens = ring(",".join(names), QQ)
    C, g, w1, w2 = gens[0:3], gens[3:6], gens[6:9], gens[9:12]
    al, et, qq, qi, la, li = gens[12:]
    # translational axes: x (= n), y, and z in 3D; rotation: x, y, z in 3D, z in 2D
    tr = [0, 1, 2] if dim == 3 else [0, 1]
    ro = [0, 1, 2] if dim == 3 else [2]
    zero = R(0)
    C = [C[i] if i in tr else zero for i in range(3)]
    g = [g[i] if i in tr else zero for i in range(3)]
    w1 = [w1[i] if i in ro else zero for i in range(3)]
    w2 = [w2[i] if i in ro else zero for i in range(3)]

    def cross(a, b):
        return [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]

    def dot(a, b):
        return sum((x * y for x, y in zip(a, b)), zero)

    n = [R(1), zero, zero]
    c1 = [C[i] + g[i] * QQ(1, 2) for i in range(3)]
    c2 = [C[i] - g[i] * QQ(1, 2) for i in range(3)]
    s1 = [la * x for x in w1]
    s2 = [la * x for x in w2]
    roll = cross([a + b for a, b in zip(s1, s2)], n)
    g_ct = [(g[i] if i != 0 else zero) + roll[i] for i in range(3)]
    dc = [-(1 + al) * QQ(1, 2) * g[0] * n[i] - et * g_ct[i] for i in range(3)]
    nxg = cross(n, g_ct)
    # w' = w + Delta s / lam = w - (eta / q) (1/lam) n x g_ct
    dw = [-et * qi * li * x for x in nxg]
    c1p = [c1[i] + dc[i] for i in range(3)]
    c2p = [c2[i] - dc[i] for i in range(3)]
    w1p = [w1[i] + dw[i] for i in range(3)]
    w2p = [w2[i] + dw[i] for i in range(3)]

    def sq(v):
        return dot(v, v)

    x1, x2, y1, y2 = sq(c1), sq(c2), sq(w1), sq(w2)
    x1p, x2p, y1p, y2p = sq(c1p), sq(c2p), sq(w1p), sq(w2p)
    moments = {
        "1": R(2),  # both particles: the collision frequency (halved below)
        "c2": x1p + x2p - x1 - x2,
        "w2": y1p + y2p - y1 - y2,
        "c4": x1p**2 + x2p**2 - x1**2 - x2**2,
        "w4": y1p**2 + y2p**2 - y1**2 - y2**2,
        "c2w2": x1p * y1p + x2p * y2p - x1 * y1 - x2 * y2,
    }

    def s1poly(x, d):
        return QQ(d, 2) - x

    def s2poly(x, d):
        return x**2 * QQ(1, 2) - x * QQ(d + 2, 2) + QQ(d * (d + 2), 8)

    weights = {
        "0": R(1),
        "a20": s2poly(x1, d_t) + s2poly(x2, d_t),
        "a02": s2poly(y1, d_r) + s2poly(y2, d_r),
        "a11": s1poly(x1, d_t) * s1poly(y1, d_r) + s1poly(x2, d_t) * s1poly(y2, d_r),
    }
    # moments of the velocity generators
    var = [sp.Rational(1, 4)] * 3 + [None, 1, 1] + [sp.Rational(1, 2)] * 6

    def expect(p):
        acc = {}
        for mon, coef in p.terms():
            value = sp.Rational(coef.numerator, coef.denominator)
            for k in range(12):
                e = mon[k]
                if k == 3:
                    value *= half_line_moment(e) if e % 2 == 0 else 0
                else:
                    value *= gauss_moment(e, var[k])
                if value == 0:
                    break
            if value == 0:
                continue
            a, b, c, qinv, l, linv = mon[12:]
            key = (a, b, c - qinv, l - linv)
            acc[key] = acc.get(key, 0) + value
        expr = 0
        for (a, b, qe, le), v in acc.items():
            assert le % 2 == 0
            expr += v * alpha**a * eta**b * q**qe * (theta / q) ** (le // 2)
        return sp.factor(sp.simplify(expr))

    out = {}
    for mk, mp in moments.items():
        for wk, wp in weights.items():
            out[(mk, wk)] = expect(mp * wp)
    return out


def rust_term(coef, mon, names):
    """One monomial with its rational coefficient as Rust: 3.0 / 16.0 * a2 * e."""
    factors = []
    for name, k in zip(names, mon):
        if k == 1:
            factors.append(name)
        elif k > 1:
            factors.append(f"{name}{k}")
    c = abs(coef)
    num = f"{c.p}.0" if c.q == 1 else f"{c.p}.0 / {c.q}.0"
    if not factors:
        body = num
    elif c == 1:
        body = " * ".join(factors)
    else:
        body = num + " * " + " * ".join(factors)
    return ("-" if coef < 0 else "+", body)


def rust(dim):
    """The moments as Rust expressions in a = alpha, e = eta, r = eta / q, t = theta,
    ti = 1 / theta (a2 = a^2 etc.): one row per moment, one entry per weight."""
    a, e, r, t = sp.symbols("a e r t")
    res = derive(dim)
    rows = []
    for mk in ["1", "c2", "w2", "c4", "w4", "c2w2"]:
        entries = []
        for wk in ["0", "a20", "a02", "a11"]:
            expr = res[(mk, wk)].subs({alpha: a, eta: e, theta: t}).subs(q, e / r)
            # theta^-2 is the lowest power: a polynomial after multiplying by theta^2
            poly = sp.Poly(sp.expand(sp.expand(expr) * t**2), a, e, r, t)
            groups = {}
            for (ia, ie, ir, it), c in poly.terms():
                if c == 0:
                    continue
                groups.setdefault(it - 2, []).append((c, (ia, ie, ir)))
            parts = []
            for power in sorted(groups):
                terms = [rust_term(c, m, ["a", "e", "r"]) for c, m in sorted(groups[power], key=lambda x: x[1])]
                text = " ".join(f"{sg} {b}" for sg, b in terms)
                text = text[2:] if text.startswith("+ ") else "-" + text[2:]
                scale = {0: "", 1: "t * ", 2: "t * t * ", -1: "ti * ", -2: "ti * ti * "}[power]
                parts.append(f"{scale}({text})" if scale else f"({text})")
            entries.append(" + ".join(parts) if parts else "0.0")
        rows.append((mk, entries))
    return rows


if __name__ == "__main__":
    import sys

    if sys.argv[1:2] == ["--rust"]:
        # the tables of crates/gas/src/theory/rough_sonine/moments.rs
        for dim in [3, 2]:
            print(f"// dimension {dim}")
            for mk, entries in rust(dim):
                print(f"// {mk}")
                print("[" + ", ".join(entries) + "],")
        sys.exit()
    dims = [int(a) for a in sys.argv[1:]] or [3, 2]
    for dim in dims:
        print(f"# dimension {dim} (collisional moments / E[(g.n)^+], both particles)")
        res = derive(dim)
        for (mk, wk), e in res.items():
            print(f"{mk:5} {wk:4} {sp.expand(e)}")
