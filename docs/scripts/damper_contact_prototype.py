#!/usr/bin/env python3
"""damper_contact_prototype.py -- would a soft-contact clearance pay on the
friction damper? (issue #10; docs/diagnosis_what_if.md, "Friction damper").

A stand-alone prototype, sharing no code with rt_bushing, run before building
the word into the element. The fitted damper model (alpha at its floor,
Kr ~ 1e-16, K0 = 0) is a Jenkins element: a spring Kpa in series with a
Coulomb slider of level Fy (dashpot level asymmetry fa: +Fy(1+fa), -Fy(1-fa)).
In series with it sits the clearance of total width g, here with a contact
law of penetration d = |s| - g/2 (s = x - xb):
    f_c(d) = kc d^2 / (2 w)   for d < w,   kc (d - w/2)   beyond   (C1),
w = 0 with a very large kc being the element's hard clearance. Each sample
solves F_J(xb) = f_c(x - xb) by bisection (both sides monotone in xb).
Forces are low-passed as `rtb diagnose --lowpass 20` does (2nd-order
Butterworth, forward-backward, odd-reflection padding) and decimated 5x.

  python3 docs/scripts/damper_contact_prototype.py DATA_DIR [--fit sines|quakes] [--iters N]

prints, for the hard and the soft clearance, the Nelder-Mead fit on the
chosen records and the NRMSE (rms error / force range) of each earthquake.
Standard library only (no numpy on the build machine); ~3 min per model for
--fit sines, ~10 for --fit quakes.
"""
import argparse
import math

SINES = ['d2_sine_0.25Hz_1.5in_36lb.csv', 'd2_sine_0.5Hz_1in_36lb.csv',
         'd2_sine_1Hz_0.5in_36lb.csv']
QUAKES = ['d3_quake_%s.csv' % r for r in
          ('ImperialValleyDBE', 'ImperialValleyMCE', 'KocaeliDBE', 'KocaeliMCE')]


def lowpass(y, dt, fc):
    """Zero-phase 2nd-order Butterworth, as offline/preprocess/preprocess.cpp."""
    w = math.tan(math.pi * fc * dt)
    q = 1.0 / math.sqrt(2.0)
    n = 1.0 / (1.0 + w / q + w * w)
    b0, a1, a2 = w * w * n, 2.0 * (w * w - 1.0) * n, (1.0 - w / q + w * w) * n
    pad = min(len(y) - 1, int(math.ceil(3.0 / (fc * dt))))
    e = [2 * y[0] - y[k] for k in range(pad, 0, -1)] + list(y) + \
        [2 * y[-1] - y[-1 - k] for k in range(1, pad + 1)]
    for _ in range(2):
        x1 = x2 = y1 = y2 = e[0]
        out = []
        for x in e:
            v = b0 * (x + 2 * x1 + x2) - a1 * y1 - a2 * y2
            x2, x1, y2, y1 = x1, x, y1, v
            out.append(v)
        e = out[::-1]
    return e[pad:pad + len(y)]


def load(path, decimate=5, fc=20.0):
    t, x, F = [], [], []
    for row in open(path):
        if row.startswith('#') or row[0].isalpha():
            continue
        a = row.split(',')
        t.append(float(a[0])); x.append(float(a[1])); F.append(float(a[2]))
    F = lowpass(F, (t[-1] - t[0]) / (len(t) - 1), fc)
    return x[::decimate], F[::decimate]


def contact(s, g, w, kc):
    d = abs(s) - 0.5 * g
    if d <= 0.0:
        return 0.0
    f = kc * d if w <= 0.0 else (kc * d * d / (2 * w) if d < w else kc * (d - 0.5 * w))
    return f if s > 0 else -f


def simulate(x, P):
    Kpa, Fy, g, w, kc, fa = P
    up, lo = Fy * (1 + fa), -Fy * (1 - fa)
    u, out = 0.0, []
    for xi in x:
        a, b = xi - 0.5 * g - 10.0, xi + 0.5 * g + 10.0
        for _ in range(60):
            m = 0.5 * (a + b)
            if min(max(Kpa * (m - u), lo), up) - contact(xi - m, g, w, kc) > 0:
                b = m
            else:
                a = m
        xb = 0.5 * (a + b)
        F = Kpa * (xb - u)
        if F > up:
            u, F = xb - up / Kpa, up
        elif F < lo:
            u, F = xb - lo / Kpa, lo
        out.append(F)
    return out


def nrmse(m, F):
    return 100 * math.sqrt(sum((p - q) ** 2 for p, q in zip(m, F)) / len(F)) / (max(F) - min(F))


def nelder_mead(f, x0, steps, iters):
    n = len(x0)
    pts = [list(x0)] + [[x0[j] + (steps[i] if i == j else 0) for j in range(n)] for i in range(n)]
    val = [f(p) for p in pts]
    for _ in range(iters):
        order = sorted(range(n + 1), key=lambda i: val[i])
        pts, val = [pts[i] for i in order], [val[i] for i in order]
        c = [sum(p[j] for p in pts[:-1]) / n for j in range(n)]
        xr = [2 * c[j] - pts[-1][j] for j in range(n)]
        fr = f(xr)
        if fr < val[0]:
            xe = [3 * c[j] - 2 * pts[-1][j] for j in range(n)]
            fe = f(xe)
            pts[-1], val[-1] = (xe, fe) if fe < fr else (xr, fr)
        elif fr < val[-2]:
            pts[-1], val[-1] = xr, fr
        else:
            xc = [0.5 * (c[j] + pts[-1][j]) for j in range(n)]
            fc = f(xc)
            if fc < val[-1]:
                pts[-1], val[-1] = xc, fc
            else:
                for i in range(1, n + 1):
                    pts[i] = [0.5 * (pts[0][j] + pts[i][j]) for j in range(n)]
                    val[i] = f(pts[i])
    i = min(range(n + 1), key=lambda k: val[k])
    return pts[i], val[i]


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument('data_dir')
    ap.add_argument('--fit', choices=('sines', 'quakes'), default='sines')
    ap.add_argument('--iters', type=int, default=300)
    a = ap.parse_args()
    rec = {n: load(a.data_dir + '/' + n) for n in SINES + QUAKES}
    fit = SINES if a.fit == 'sines' else QUAKES

    for soft in (False, True):
        def unpack(q):  # log-stiffnesses, signed widths folded positive
            P = [math.exp(q[0]), q[1], abs(q[2]), abs(q[3]), math.exp(q[4]), 0.0]
            if not soft:
                P[3], P[4] = 0.0, 1e6
            return P

        def misfit(q):
            P = unpack(q)
            s = s0 = 0.0
            for n in fit:
                x, F = rec[n]
                s += sum((m - f) ** 2 for m, f in zip(simulate(x, P), F))
                s0 += sum(f * f for f in F)
            return s / s0

        # Start: the diagnosis's backlash fit on the sines (Kpa 40, C0 3.56, g 0.198).
        q, J = nelder_mead(misfit, [math.log(40), 3.56, 0.198, 0.05, math.log(40), 0.0],
                           [0.3, 0.3, 0.03, 0.03, 0.5, 0.1], a.iters)
        P = unpack(q)
        e = [nrmse(simulate(rec[n][0], P), rec[n][1]) for n in QUAKES]
        print('%s clearance: Kpa %.4g Fy %.4g g %.4g w %.4g kc %.4g; fit sqrt(J/J0) %.2f%%'
              % ('soft' if soft else 'hard', P[0], P[1], P[2], P[3], P[4], 100 * math.sqrt(J)))
        print('  earthquake NRMSE %%: %s  mean %.2f' % (' '.join('%.2f' % v for v in e), sum(e) / 4))


if __name__ == '__main__':
    main()
