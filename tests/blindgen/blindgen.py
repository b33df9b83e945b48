#!/usr/bin/python3
"""Blind test-data generator for `rtb diagnose`.

Written from the paper (Puel, Bourgeteau & Aubry 2013, eq. (2) and (11)) and
the CLI help only, without reading the project's own generators or the
diagnosis code, so that it probes the diagnosis like an outside acceptance
test would.

  blindgen.py make --effects E1[,E2] --seed S --out DIR [--duration 4]
  blindgen.py selftest
  blindgen.py sizes --seed S [--duration 4]     (every case of one seed, sizes only)

Internal units: mm, N, s (stiffness N/mm, C0 in N (s/mm)^alpha, mass in
N s^2/mm = t).  The CSV units vary per case; truth.json says which
--scale-* factors bring them back to mm, N, s.
"""
import argparse
import json
import math
import os
import sys
import time
import zlib

import numpy as np
from scipy.integrate import solve_ivp
from scipy.special import erf

# --------------------------------------------------------------------------
# Vocabulary
# --------------------------------------------------------------------------
# generator effect name -> word the diagnosis is expected to name
VOCAB = {
    "none": "none",
    "cubic_stiffness": "cubic_stiffness",
    "asymmetry": "asymmetry",
    "maxwell": "maxwell",
    "viscous": "viscous",
    "backlash": "backlash",            # floating end in the gap (force 0)
    "backlash_held": "backlash",       # end held where contact was lost
    "mullins": "mullins",
    "delay": "delay",
    "inertia": "inertia",
    "offset": "offset",
    "softening": "softening",
    "slack": "slack",
    "relaxation_spectrum": "relaxation_spectrum",
    "friction_asymmetry": "friction_asymmetry",
}
# out of vocabulary: the honest verdict is `unexplained`
OOV = ("hum", "thermal_drift", "adc_quantization")

SINGLES = [e for e in VOCAB]  # includes none and backlash_held
HARD = ["delay,asymmetry", "maxwell,offset", "backlash,cubic_stiffness",
        "viscous,cubic_stiffness", "inertia,softening", "mullins,delay",
        "hum", "thermal_drift", "adc_quantization"]

# Effects whose force is linear in one strength theta: they are sized so that
# the part a plain RT refit cannot absorb is a drawn multiple of the noise.
LINEAR = {"cubic_stiffness", "asymmetry", "maxwell", "viscous", "mullins",
          "inertia", "offset", "softening", "relaxation_spectrum", "hum",
          "thermal_drift"}

# Centre of the RT parameters.  The paper gives no numbers for its sec. 3.4
# set, so this is a plausible automotive bushing: static stiffness
# K0 + 1/(1/Kpa + N/Kr) = 780 N/mm, initial tangent K0 + Kpa = 1500 N/mm,
# cell friction level C0 |v|^alpha ~ 100 N at 10 mm/s.
CENTRE = dict(K0=300.0, Kpa=1200.0, Kr=12000.0, C0=80.0, alpha=0.2)

RTOL, ATOL = 1e-6, 1e-8      # production tolerances (mm): ~1e-7 of the force range, far below noise


def loguniform(rng, lo, hi):
    return float(math.exp(rng.uniform(math.log(lo), math.log(hi))))


# --------------------------------------------------------------------------
# Commands (the displacement the rig is told to impose): analytic u(t), u'(t)
# --------------------------------------------------------------------------
def smooth_step(p):
    """C1 step 0 -> 1 over p in [0, 1] and its derivative d/dp."""
    p = np.clip(p, 0.0, 1.0)
    return 0.5 - 0.5 * np.cos(np.pi * p), 0.5 * np.pi * np.sin(np.pi * p)


def envelope(t, times, levels, tr):
    """Smooth piecewise-constant envelope: starts at 0, reaches levels[i]
    after a cosine transition of length tr starting at times[i]."""
    t = np.asarray(t, float)
    e = np.zeros_like(t)
    de = np.zeros_like(t)
    prev = 0.0
    for t0, lv in zip(times, levels):
        s, ds = smooth_step((t - t0) / tr)
        e = e + (lv - prev) * s
        de = de + (lv - prev) * ds / tr
        prev = lv
    return e, de


def cmd_sine_steps(rng, X, T):
    """Sine whose amplitude steps up 0.4X -> 0.7X -> X then back to 0.6X:
    amplitude-dependent and history-dependent (Mullins) effects show."""
    f = loguniform(rng, 0.7, 4.0)
    lv = [0.4, 0.7, 1.0, 0.6]
    tt = [0.0, 0.25 * T, 0.5 * T, 0.75 * T]
    tr = min(0.3, 0.1 * T)

    def u(t):
        e, de = envelope(t, tt, lv, tr)
        w = 2 * np.pi * f
        return X * e * np.sin(w * t), X * (de * np.sin(w * t) + e * w * np.cos(w * t))
    return u, dict(kind="sine_steps", f_hz=f, levels=lv, amp_mm=X)


def cmd_chirp(rng, X, T):
    """Linear swept sine 0.5 Hz -> f1: rate-dependent effects show."""
    f0, f1 = 0.5, rng.uniform(10.0, 20.0)
    a = X * rng.uniform(0.4, 0.6)
    tr = min(0.25, 0.1 * T)

    def u(t):
        e, de = envelope(t, [0.0], [1.0], tr)
        ph = 2 * np.pi * (f0 * t + (f1 - f0) * t * t / (2 * T))
        dph = 2 * np.pi * (f0 + (f1 - f0) * t / T)
        return a * e * np.sin(ph), a * (de * np.sin(ph) + e * dph * np.cos(ph))
    return u, dict(kind="chirp", f0_hz=f0, f1_hz=f1, amp_mm=a)


def cmd_multisine(rng, X, T, fmin=0.5, fmax=15.0):
    """Sum of 2-3 sines at log-spread frequencies."""
    n = int(rng.integers(2, 4))
    fs = np.sort(np.exp(rng.uniform(np.log(fmin), np.log(fmax), n)))
    amps = X * rng.uniform(0.3, 1.0, n) / np.sqrt(1 + fs / 5.0)   # less at high f
    amps *= 0.9 * X / amps.sum()
    ph = rng.uniform(0, 2 * np.pi, n)
    tr = min(0.25, 0.1 * T)

    def u(t):
        t = np.asarray(t, float)
        e, de = envelope(t, [0.0], [1.0], tr)
        s = np.zeros_like(t)
        ds = np.zeros_like(t)
        for a, f, p in zip(amps, fs, ph):
            s = s + a * np.sin(2 * np.pi * f * t + p)
            ds = ds + a * 2 * np.pi * f * np.cos(2 * np.pi * f * t + p)
        return e * s, de * s + e * ds
    return u, dict(kind="multisine", f_hz=fs.tolist(), amp_mm=amps.tolist())


def cmd_triangle(rng, X, T):
    """Triangle (constant-speed strokes, sharp reversals)."""
    f = loguniform(rng, 0.5, 3.0)
    a = X * rng.uniform(0.6, 1.0)
    tr = min(0.25, 0.1 * T)

    def u(t):
        e, de = envelope(t, [0.0], [1.0], tr)
        w = 2 * np.pi * f
        tri = (2 / np.pi) * np.arcsin(np.clip(np.sin(w * t), -1, 1))
        dtri = 4 * f * np.sign(np.cos(w * t))
        return a * e * tri, a * (de * tri + e * dtri)
    return u, dict(kind="triangle", f_hz=f, amp_mm=a)


def cmd_relax(rng, X, T):
    """Ramp - hold - ramp to the other side - hold - back to 0 (relaxation)."""
    tr = rng.uniform(0.05, 0.2)
    h = X * rng.uniform(0.6, 1.0)
    q = rng.uniform(0.5, 1.0)
    # knots in seconds
    ts = np.array([0.0, 0.05 * T, 0.05 * T + tr, 0.4 * T, 0.4 * T + 2 * tr,
                   0.75 * T, 0.75 * T + tr, T + 1.0])
    us = np.array([0.0, 0.0, h, h, -q * h, -q * h, 0.0, 0.0])
    slopes = np.diff(us) / np.diff(ts)

    def u(t):
        t = np.asarray(t, float)
        k = np.clip(np.searchsorted(ts, t, side="right") - 1, 0, len(slopes) - 1)
        return np.interp(t, ts, us), slopes[k]
    return u, dict(kind="relax", ramp_s=tr, hold_mm=[h, -q * h])


def cmd_random(rng, X, T):
    """Band-limited random: 40 sines of random phase, flat in [0.2, fmax]."""
    fmax = rng.uniform(5.0, 15.0)
    fs = rng.uniform(0.2, fmax, 40)
    ph = rng.uniform(0, 2 * np.pi, 40)
    tg = np.linspace(0, T, 20001)
    raw = np.sin(2 * np.pi * np.outer(tg, fs) + ph).sum(1)
    a = X * rng.uniform(0.7, 1.0) / np.abs(raw).max()
    tr = min(0.25, 0.1 * T)

    def u(t):
        t = np.asarray(t, float)
        e, de = envelope(t, [0.0], [1.0], tr)
        arg = 2 * np.pi * np.multiply.outer(t, fs) + ph
        s = a * np.sin(arg).sum(-1)
        ds = a * (2 * np.pi * fs * np.cos(arg)).sum(-1)
        return e * s, de * s + e * ds
    return u, dict(kind="random", fmax_hz=fmax, peak_mm=X)


def with_preload(cmd, pre, T):
    """Add a tension preload reached by a smooth ramp (slack specimens)."""
    tr = min(0.4, 0.15 * T)

    def u(t):
        a, da = cmd(t)
        e, de = envelope(t, [0.0], [1.0], tr)
        return a + pre * e, da + pre * de
    return u


def plan_records(rng, X, T):
    """Fit records always contain: an amplitude-stepped sine (amplitude and
    history), a relaxation test and a chirp (rate up to 10-20 Hz), so every
    effect is visible in the fit; sometimes a 4th (multisine or triangle).
    Hold-out: band-limited random, sometimes a second one."""
    fit = [cmd_sine_steps(rng, X, T), cmd_relax(rng, X, T), cmd_chirp(rng, X, T)]
    if rng.random() < 0.5:
        fit.append(cmd_multisine(rng, X, T) if rng.random() < 0.5 else cmd_triangle(rng, X, T))
    order = rng.permutation(len(fit))
    fit = [fit[i] for i in order]
    hold = [cmd_random(rng, X, T)]
    if rng.random() < 0.5:
        hold.append(cmd_multisine(rng, X, T, 1.0, 12.0) if rng.random() < 0.5
                    else cmd_triangle(rng, X, T))
    return fit, hold


# --------------------------------------------------------------------------
# Specimen + rig: the ODE
# --------------------------------------------------------------------------
class Rig:
    """State Y = [servo (1|2), s_held (0|1), y_1..y_N, z_1..z_B].

    servo: the actuator follows the command through a 1st- or 2nd-order
      low-pass (x is the true actuator motion, what the LVDT sees).
    s: the specimen's end.  mode 'direct': s = x.  'float': clearance of
      half-width g, inside it the end floats where the specimen force is 0.
      'held': clearance, the end stays where contact was lost (play operator,
      needs the state s_held).  'slack': tension-only strip, s = max(x, s_free).
    y: RT cells, eq. (2) in velocity form y' = sign(g)(|g|/C)^(1/alpha), g the
      spring-force imbalance on the cell.  C = C0 for y' > 0 and C0*ratio for
      y' < 0 when friction asymmetry is on (ratio < 1 flips the side).
    z: linear branches (Maxwell / Prony) k_i (s - z_i), z_i' = (s - z_i)/tau_i.
    """

    def __init__(self, p, N, cmd, servo, mode="direct", gap=0.0, branches=(), fric_ratio=1.0):
        self.K0, self.Kpa, self.Kr, self.C0, self.alpha = (p[k] for k in ("K0", "Kpa", "Kr", "C0", "alpha"))
        self.N, self.cmd, self.mode, self.gap = N, cmd, mode, gap
        self.order, self.fc = servo["order"], servo["fc_hz"]
        self.wn = 2 * np.pi * self.fc
        self.bk = np.array([b[0] for b in branches], float)
        self.btau = np.array([b[1] for b in branches], float)
        self.fric_ratio = fric_ratio
        self.ns = self.order
        self.nh = 1 if mode == "held" else 0
        self.iy = self.ns + self.nh
        self.iz = self.iy + N
        self.n = self.iz + len(self.bk)

    # actuator motion from the servo states (vectorized over columns)
    def actuator(self, Y, t):
        u, du = self.cmd(t)
        x = Y[0]
        if self.order == 1:
            xd = self.wn * (u - x)
            xdd = self.wn * (du - xd)
        else:
            xd = Y[1]
            xdd = self.wn ** 2 * (u - x) - 2 * 0.7 * self.wn * xd
        return x, xd, xdd

    def s_free(self, y1, z):
        """End position where the (linear part of the) specimen force is 0."""
        num = self.Kpa * y1 + (self.bk[:, None] * z).sum(0)
        return num / (self.K0 + self.Kpa + self.bk.sum())

    def end(self, Y, x):
        y1 = Y[self.iy]
        z = Y[self.iz:]
        if self.mode == "direct":
            return x
        if self.mode == "held":
            return Y[self.ns]
        sf = self.s_free(y1, z)
        if self.mode == "float":
            return np.clip(sf, x - self.gap, x + self.gap)
        return np.maximum(x, sf)   # slack

    def rhs(self, t, Y):
        """dY/dt; Y may be (n,) or (n, k) (vectorized: the solver's finite-
        difference Jacobian then costs one call)."""
        one = Y.ndim == 1
        Y = Y.reshape(self.n, -1)
        x, xd, xdd = self.actuator(Y, t)
        dY = np.empty_like(Y)
        dY[0] = xd
        if self.order == 2:
            dY[1] = xdd
        s = self.end(Y, x)
        if self.mode == "held":
            # play operator: follow the actuator only while pushed by a side
            # of the clearance; the small correction keeps it on the side.
            d = x - s
            push = (d >= self.gap * (1 - 1e-9)) & (xd > 0)
            pull = (d <= -self.gap * (1 - 1e-9)) & (xd < 0)
            dY[self.ns] = np.where(push, xd + 1e3 * (d - self.gap),
                                   np.where(pull, xd + 1e3 * (d + self.gap), 0.0))
        y = Y[self.iy:self.iz]
        Kr = self.Kr
        g = np.empty_like(y)
        g[0] = self.Kpa * (s - y[0]) - Kr * (y[0] - y[1])
        g[1:-1] = Kr * (y[:-2] - 2 * y[1:-1] + y[2:])
        g[-1] = Kr * (y[-2] - 2 * y[-1])
        C = np.where(g >= 0, self.C0, self.C0 * self.fric_ratio) if self.fric_ratio != 1.0 else self.C0
        dY[self.iy:self.iz] = np.sign(g) * (np.abs(g) / C) ** (1.0 / self.alpha)
        if len(self.bk):
            dY[self.iz:] = (s - Y[self.iz:]) / self.btau[:, None]
        return dY[:, 0] if one else dY

    def solve(self, T, rtol=RTOL, atol=ATOL):
        # max_step: the solver must not step over the onset of a ramp after a
        # long hold; 2 ms resolves the 20 Hz chirps and the servo.
        sol = solve_ivp(self.rhs, (0.0, T), np.zeros(self.n), method="Radau",
                        rtol=rtol, atol=atol, dense_output=True, max_step=2e-3, vectorized=True)
        if not sol.success:
            raise RuntimeError("integration failed: " + sol.message)
        return sol

    def states(self, sol, t):
        """Everything the force needs, on times t (t < 0: at rest)."""
        t = np.asarray(t, float)
        return self.states_of(sol.sol(np.clip(t, 0.0, None)), t)

    def states_of(self, Y, t):
        tc = np.clip(t, 0.0, None)
        Y = np.array(Y, float)
        Y[:, t < 0] = 0.0
        x, xd, xdd = self.actuator(Y, tc)
        xd = np.where(t < 0, 0.0, xd)
        xdd = np.where(t < 0, 0.0, xdd)
        s = self.end(Y, x)
        if self.mode == "direct":
            sd = xd
        else:
            sd = np.gradient(s, t)
        return dict(t=t, x=x, xd=xd, xdd=xdd, s=s, sd=sd, y1=Y[self.iy],
                    z=Y[self.iz:], yN=Y[self.iz - 1])


# --------------------------------------------------------------------------
# Effects: force terms added to the RT force (unit strength "shapes")
# --------------------------------------------------------------------------
def rt_force(p, st, bk):
    """Eq. (11) force K0 s + Kpa (s - y1), plus the linear branches."""
    F = p["K0"] * st["s"] + p["Kpa"] * (st["s"] - st["y1"])
    if len(bk):
        F = F + (bk[:, None] * (st["s"] - st["z"])).sum(0)
    return F


def shape(eff, ep, p, st, t_abs):
    """Force of effect `eff` at unit strength theta = 1 (linear effects)."""
    s, K0 = st["s"], p["K0"]
    if eff == "cubic_stiffness":          # F += k3 s^3   (theta = k3, N/mm^3)
        return s ** 3
    if eff == "asymmetry":                # bilinear: extra stiffness on one side
        return np.minimum(s, 0.0) if ep["side"] < 0 else np.maximum(s, 0.0)
    if eff == "softening":                # F -= ks (s - xs tanh(s/xs)), theta = ks (N/mm)
        return ep["xs"] * np.tanh(s / ep["xs"]) - s
    if eff == "mullins":                  # Ogden-Roxburgh on the static stiffness, theta = 1/r
        W = 0.5 * ep["k_ref"] * s ** 2
        Wm = np.maximum.accumulate(W)
        return -ep["k_ref"] * s * erf((Wm - W) / ep["m_energy"])
    if eff == "maxwell":                  # km (s - z), z' = (s - z)/tau, theta = km
        return s - st["z"][ep["branch"]]
    if eff == "relaxation_spectrum":      # sum w_i (s - z_i), sum w_i = 1, theta = total k
        zs = st["z"][ep["branch0"]:ep["branch0"] + len(ep["w"])]
        return (np.asarray(ep["w"])[:, None] * (s - zs)).sum(0)
    if eff == "viscous":                  # c s'
        return st["sd"]
    if eff == "inertia":                  # moving fixture mass m x''
        return st["xdd"]
    if eff == "offset":                   # load-cell zero error
        return np.ones_like(s)
    if eff == "hum":                      # mains pickup, fundamental + 3rd harmonic
        w = 2 * np.pi * ep["f_hz"]
        return np.sin(w * t_abs + ep["phase"]) + 0.3 * np.sin(3 * w * t_abs + 2 * ep["phase"])
    if eff == "thermal_drift":            # the whole specimen scales slowly with test time
        return None                       # multiplicative, handled in assemble()
    raise KeyError(eff)


def draw_effect(eff, rng, base):
    """Physical parameters of one effect (strength of the linear ones comes
    later from the noise target)."""
    X = base["amp_mm"]
    T = base["duration"]
    ep = {}
    if eff in LINEAR:
        ep["target_visible_x_noise"] = loguniform(rng, 3.0, 8.0)
    if eff == "asymmetry":
        ep["side"] = int(rng.choice([-1, 1]))
    elif eff == "softening":
        ep["xs"] = X * rng.uniform(0.4, 0.8)
    elif eff == "mullins":
        # the damage acts on the static stiffness K0 + 1/(1/Kpa + N/Kr): the
        # whole rubber's elastic energy, not only the K0 spring
        ep["k_ref"] = static_stiffness(base["params"], base["cells"])
        ep["m_energy_frac"] = rng.uniform(0.05, 0.25)
        ep["m_energy"] = ep["m_energy_frac"] * 0.5 * ep["k_ref"] * X ** 2
    elif eff == "maxwell":
        ep["tau_s"] = loguniform(rng, 0.005, 0.2)
    elif eff == "relaxation_spectrum":
        nb = int(rng.integers(8, 16))
        tau = np.logspace(-3, 2, nb)
        n = rng.uniform(0.15, 0.4)             # G(t) ~ t^-n
        w = tau ** (-n)
        ep.update(n_branches=nb, tau_s=tau.tolist(), power=n, w=(w / w.sum()).tolist())
    elif eff == "offset":
        ep["sign"] = int(rng.choice([-1, 1]))
    elif eff == "hum":
        ep["f_hz"] = float(rng.choice([50.0, 60.0]))
        ep["phase"] = rng.uniform(0, 2 * np.pi)
    elif eff == "thermal_drift":
        ep["period_s"] = rng.uniform(20.0, 60.0)
        ep["phase"] = rng.uniform(0, 2 * np.pi)
    elif eff in ("backlash", "backlash_held"):
        ep["gap_mm"] = X * rng.uniform(0.02, 0.10)
    elif eff == "slack":
        ep["preload_mm"] = X * rng.uniform(0.8, 1.0)   # slack only in the deep troughs
    elif eff == "friction_asymmetry":
        r = rng.uniform(1.3, 1.6)     # 1.6-2 gave 15-20x the noise: too easy
        ep["ratio_neg_over_pos"] = r if rng.random() < 0.5 else 1.0 / r
    elif eff == "delay":
        ep["delay_s"] = rng.uniform(0.001, 0.006)
    elif eff == "adc_quantization":
        ep["bits"] = int(rng.choice([6, 7]))
    return ep


# --------------------------------------------------------------------------
# Case generation
# --------------------------------------------------------------------------
UNIT_STYLES = [
    # header names, (time, displacement, force) value = internal * factor_out
    dict(names=("time", "displacement", "force"), out=(1.0, 1.0, 1.0), units="s, mm, N"),
    dict(names=("t", "disp_mm", "load_N"), out=(1.0, 1.0, 1.0), units="s, mm, N"),
    dict(names=("time_s", "x_m", "force_kN"), out=(1.0, 1e-3, 1e-3), units="s, m, kN"),
    dict(names=("time [ms]", "stroke [mm]", "load [kN]"), out=(1e3, 1.0, 1e-3), units="ms, mm, kN"),
    dict(names=("t (s)", "position_um", "f_N"), out=(1.0, 1e3, 1.0), units="s, um, N"),
]


def draw_base(seed, duration, cells):
    """Specimen, rig and protocols: the same for every effect of one seed
    (the effect streams are separate), so cases of a seed compare."""
    rng = np.random.default_rng(seed)
    p = {k: CENTRE[k] * loguniform(rng, 0.5, 2.0) for k in ("K0", "Kpa", "Kr", "C0")}
    p["alpha"] = rng.uniform(0.1, 0.4)
    X = loguniform(rng, 0.5, 3.0)
    base = dict(params=p, cells=cells, amp_mm=X, duration=duration,
                fs_hz=int(rng.choice([500, 1000, 2000])),
                servo=dict(order=int(rng.choice([1, 2])), fc_hz=rng.uniform(20.0, 60.0)),
                noise_x_frac=rng.uniform(0.001, 0.005),
                noise_f_frac=rng.uniform(0.003, 0.01),
                units=int(rng.integers(len(UNIT_STYLES))))
    fit, hold = plan_records(rng, X, duration)
    base["fit"], base["hold"] = fit, hold
    base["noise_seed"] = int(rng.integers(2 ** 31))
    return base


def static_stiffness(p, N):
    """K0 + 1/(1/Kpa + N/Kr): the force per displacement after full relaxation."""
    return p["K0"] + 1.0 / (1.0 / p["Kpa"] + N / p["Kr"])


def project_out(d, basis):
    """Part of d (concatenated records) no least-squares mix of basis removes:
    a cheap stand-in for what a plain RT refit cannot absorb."""
    B = np.column_stack(basis)
    c, *_ = np.linalg.lstsq(B, d, rcond=None)
    return d - B @ c


def simulate(base, effects, eff_params, theta, T):
    """Noise-free records: list of dict(t, x, F, Fplain, states...)."""
    p, N = base["params"], base["cells"]
    mode, gap, fric = "direct", 0.0, 1.0
    branches = []
    for e in effects:
        ep = eff_params.get(e, {})
        if e == "backlash":
            mode, gap = "float", ep["gap_mm"]
        elif e == "backlash_held":
            mode, gap = "held", ep["gap_mm"]
        elif e == "slack":
            mode = "slack"
        elif e == "friction_asymmetry":
            fric = ep["ratio_neg_over_pos"]
        elif e == "maxwell":
            ep["branch"] = len(branches)
            branches.append((theta.get(e, 1.0), ep["tau_s"]))
        elif e == "relaxation_spectrum":
            ep["branch0"] = len(branches)
            branches += [(theta.get(e, 1.0) * w, tau) for w, tau in zip(ep["w"], ep["tau_s"])]
    # branches only act on the dynamics through a floating/slack end; the
    # force of a branch is added through its shape, so keep k out of rt_force
    bk_dyn = [b if mode in ("float", "slack") else (0.0, b[1]) for b in branches]
    delay = eff_params.get("delay", {}).get("delay_s", 0.0)
    fs = base["fs_hz"]
    t = np.arange(int(round(T * fs)) + 1) / fs
    out = []
    records = [(c, True) for c in base["fit"]] + [(c, False) for c in base["hold"]]
    for i, ((cmd, meta), is_fit) in enumerate(records):
        if mode == "slack":
            cmd = with_preload(cmd, eff_params["slack"]["preload_mm"], T)
        plain = Rig(p, N, cmd, base["servo"])
        sol_p = plain.solve(T)
        rig = Rig(p, N, cmd, base["servo"], mode, gap, bk_dyn, fric)
        sol = sol_p if (mode == "direct" and fric == 1.0 and not branches) else rig.solve(T)
        te = t - delay                              # the force channel lags
        st = rig.states(sol, te)
        stp = plain.states(sol_p, t)     # the plain model sees the recorded time
        rec = dict(meta=meta, is_fit=is_fit, t=t, x=rig.states(sol, t)["x"],
                   st=st, F_rt=rt_force(p, st, np.zeros(0)),
                   F_plain=rt_force(p, stp, np.zeros(0)), Fchain_plain=p["Kpa"] * (stp["s"] - stp["y1"]),
                   x_plain=stp["x"])
        out.append(rec)
    return out


def assemble(recs, effects, eff_params, p, theta, base):
    """Specimen force of every record with the effects at strength theta."""
    T = base["duration"]
    for i, r in enumerate(recs):
        t_abs = r["t"] + base["acq_start"][i]
        F = r["F_rt"].copy()
        for e in effects:
            if e in LINEAR and e != "thermal_drift":
                F = F + theta[e] * shape(e, eff_params[e], p, r["st"], t_abs)
        if "thermal_drift" in effects:
            ep = eff_params["thermal_drift"]
            F = F * (1 + theta["thermal_drift"] * np.sin(2 * np.pi * t_abs / ep["period_s"] + ep["phase"]))
        r["F"] = F


def make_case(effects, seed, duration=4.0, cells=15, verbose=False):
    """Everything of a case, in memory: records (noisy) and the truth."""
    for e in effects:
        if e not in VOCAB and e not in OOV:
            raise SystemExit("unknown effect %r (known: %s)" % (e, ", ".join(list(VOCAB) + list(OOV))))
    effects = [e for e in effects if e != "none"] or ["none"]
    ends = [e for e in effects if e in ("backlash", "backlash_held", "slack")]
    if len(ends) > 1:
        raise SystemExit("backlash, backlash_held and slack exclude each other")
    base = draw_base(seed, duration, cells)
    p = base["params"]
    eff_params = {}
    for e in effects:
        if e == "none":
            continue
        erng = np.random.default_rng([seed, zlib.crc32(e.encode())])
        eff_params[e] = draw_effect(e, erng, base)
    nrng = np.random.default_rng([base["noise_seed"], zlib.crc32(",".join(effects).encode())])
    nrec = len(base["fit"]) + len(base["hold"])
    # acquisition order and start times (only the thermal drift sees them)
    order = nrng.permutation(nrec)
    base["acq_start"] = [float(k * (duration + 6.0)) for k in np.argsort(order)]

    theta = {e: 1.0 for e in effects if e in LINEAR}
    recs = simulate(base, effects, eff_params, theta, duration)
    # noise levels: fixed sensor noise (N, mm) set from the plain force and
    # displacement ranges over all records
    f_range = np.median([np.ptp(r["F_plain"]) for r in recs])
    x_range = np.median([np.ptp(r["x"]) for r in recs])
    sig_f = base["noise_f_frac"] * f_range
    sig_x = base["noise_x_frac"] * x_range
    quant = eff_params.get("adc_quantization")
    fit = [r for r in recs if r["is_fit"]]

    def visible(d_list):
        d = np.concatenate(d_list)
        basis = [np.concatenate([r["x_plain"] for r in fit]), np.concatenate([r["Fchain_plain"] for r in fit])]
        return float(np.sqrt(np.mean(project_out(d, basis) ** 2)) / sig_f)

    # size the linear effects: visible part = target x noise
    sizes = {}
    for e in effects:
        if e not in LINEAR:
            continue
        ep = eff_params[e]
        if e == "thermal_drift":
            shapes = [r["F_rt"] * np.sin(2 * np.pi * (r["t"] + base["acq_start"][i]) / ep["period_s"] + ep["phase"])
                      for i, r in enumerate(recs) if r["is_fit"]]
        else:
            shapes = [shape(e, ep, p, r["st"], r["t"] + base["acq_start"][i])
                      for i, r in enumerate(recs) if r["is_fit"]]
        v1 = visible(shapes)
        th = ep["target_visible_x_noise"] / max(v1, 1e-12)
        # physical limits: the static tangent stiffness must stay positive
        kst = static_stiffness(p, base["cells"])
        caps = {"mullins": 0.5, "softening": 0.8 * kst, "asymmetry": 0.8 * kst, "thermal_drift": 0.3}
        if e in caps and th > caps[e]:
            th = caps[e]
        if e == "offset":
            th *= ep["sign"]
        if e == "asymmetry":
            th *= rng_sign(seed, e)
        theta[e] = float(th)
    # branches change the end's dynamics only in float/slack modes: re-run
    if any(e in ("maxwell", "relaxation_spectrum") for e in effects) and ends and ends[0] != "backlash_held":
        recs = simulate(base, effects, eff_params, theta, duration)
    assemble(recs, effects, eff_params, p, theta, base)
    if quant:
        # noise below the ADC step: a staircase, not a dither
        fs_adc = 1.25 * max(np.abs(r["F"]).max() for r in recs)
        step = 2 * fs_adc / 2 ** quant["bits"]
        sig_f = 0.15 * step
        quant.update(full_scale_N=fs_adc, step_N=step)

    # effect sizes: with vs without every effect (noise-free), raw and visible
    for e in effects:
        if e == "none":
            continue
        ep = eff_params[e]
        if e in LINEAR:
            ep["theta"] = theta[e]
    d_all = [r["F"] - r["F_plain"] for r in fit]
    sizes["raw_rms_x_noise"] = float(np.sqrt(np.mean(np.concatenate(d_all) ** 2)) / sig_f)
    sizes["visible_rms_x_noise"] = visible(d_all) if effects != ["none"] else 0.0
    sizes["force_range_N"] = float(f_range)

    # measurement chain
    style = UNIT_STYLES[base["units"]]
    files = []
    for i, r in enumerate(recs):
        F = r["F"] + nrng.normal(0, sig_f, r["F"].shape)
        x = r["x"] + nrng.normal(0, sig_x, r["x"].shape)
        if quant:
            F = np.round(F / quant["step_N"]) * quant["step_N"]
            sizes.setdefault("quant_err_rms_x_noise", float(
                np.sqrt(np.mean((F - r["F"]) ** 2)) / sig_f))
        name = ("fit%d_%s.csv" % (i + 1, r["meta"]["kind"]) if r["is_fit"]
                else "holdout%d_%s.csv" % (i + 1 - len(fit), r["meta"]["kind"]))
        files.append((name, r["is_fit"], r["t"], x, F, r["meta"]))

    truth = dict(
        effects=effects, expected=expected_words(effects), seed=seed, duration_s=duration,
        fit=[f[0] for f in files if f[1]], holdout=[f[0] for f in files if not f[1]],
        scale=dict(time=1.0 / style["out"][0], displacement=1.0 / style["out"][1],
                   force=1.0 / style["out"][2]),
        units=style["units"], columns=list(style["names"]),
        params=dict(rt=p, cells=cells, amplitude_mm=base["amp_mm"], sample_rate_hz=base["fs_hz"],
                    servo=base["servo"], noise_force_N=sig_f, noise_displacement_mm=sig_x,
                    effects=eff_params, acquisition_start_s=base["acq_start"]),
        records={f[0]: f[5] for f in files},
        sizes=sizes)
    return files, truth, style


def rng_sign(seed, e):
    """Sign of a bilinear asymmetry (own stream, reproducible)."""
    return 1 if np.random.default_rng([seed, zlib.crc32((e + "sign").encode())]).random() < 0.5 else -1


def expected_words(effects):
    if effects == ["none"]:
        return ["none"]
    if any(e in OOV for e in effects):
        return ["unexplained"]
    words = []
    for e in effects:
        if VOCAB[e] not in words:
            words.append(VOCAB[e])
    return words


def write_case(files, truth, style, out):
    os.makedirs(out, exist_ok=True)
    ot, ox, of = style["out"]
    for name, _, t, x, F, meta in files:
        with open(os.path.join(out, name), "w") as fh:
            fh.write("# blindgen record %s (%s), units: %s\n" % (name, meta["kind"], style["units"]))
            fh.write(",".join(style["names"]) + "\n")
            for a, b, c in zip(t * ot, x * ox, F * of):
                fh.write("%.10g,%.8g,%.8g\n" % (a, b, c))
    with open(os.path.join(out, "truth.json"), "w") as fh:
        json.dump(truth, fh, indent=1, default=float)


# --------------------------------------------------------------------------
# Self-test
# --------------------------------------------------------------------------
def selftest():
    ok = True
    p = dict(CENTRE)
    N = 15
    servo = dict(order=2, fc_hz=40.0)
    rng = np.random.default_rng(7)
    T = 4.0
    # 1. convergence: production tolerance vs halved tolerance
    cmd, _ = cmd_chirp(rng, 2.0, T)
    t = np.arange(0, T, 1e-3)
    r1 = Rig(p, N, cmd, servo)
    t0 = time.time()
    F1 = rt_force(p, r1.states(r1.solve(T), t), np.zeros(0))
    dt1 = time.time() - t0
    F2 = rt_force(p, r1.states(r1.solve(T, RTOL / 2, ATOL / 2), t), np.zeros(0))
    F3 = rt_force(p, r1.states(r1.solve(T, RTOL / 1000, ATOL / 1000), t), np.zeros(0))
    e12 = np.abs(F1 - F2).max() / np.ptp(F1)
    e13 = np.abs(F1 - F3).max() / np.ptp(F1)
    good = e12 < 1e-5 and e13 < 1e-5      # noise is >= 1e-3 of the range
    ok &= good
    print("convergence: max|F(rtol)-F(rtol/2)|/range = %.2e, vs rtol/1000: %.2e  (%.1f s/solve) %s"
          % (e12, e13, dt1, "ok" if good else "FAIL"))
    # also the held-backlash play state and a 1st-order servo
    for mode in ("held", "float", "slack"):
        r = Rig(p, N, cmd, dict(order=1, fc_hz=30.0), mode, 0.1)
        Fa = rt_force(p, r.states(r.solve(T), t), np.zeros(0))
        Fb = rt_force(p, r.states(r.solve(T, RTOL / 2, ATOL / 2), t), np.zeros(0))
        e = np.abs(Fa - Fb).max() / np.ptp(Fa)
        good = e < 1e-4
        ok &= good
        print("convergence %-5s end: %.2e %s" % (mode, e, "ok" if good else "FAIL"))
    # 2. static limit: ramp to x and hold very long
    for alpha in (1.0, 0.3):
        q = dict(p, alpha=alpha)
        xh = 1.5
        hold = lambda tt: (xh * np.clip(np.asarray(tt) / 0.1, 0, 1),
                           np.where(np.asarray(tt) < 0.1, xh / 0.1, 0.0))
        r = Rig(q, N, hold, servo)
        Th = 1e2 if alpha == 1.0 else 1e7
        sol = solve_ivp(r.rhs, (0, Th), np.zeros(r.n), method="Radau", rtol=1e-10, atol=1e-12, vectorized=True,
                        dense_output=False, max_step=np.inf, first_step=1e-4)
        st = r.states_of(sol.y[:, -1:], np.array([Th]))
        F = rt_force(q, st, np.zeros(0))[0]
        Fs = q["K0"] * xh + xh / (1 / q["Kpa"] + N / q["Kr"])
        rel = abs(F - Fs) / Fs
        tol = 1e-6 if alpha == 1.0 else 5e-3
        good = rel < tol
        ok &= good
        print("static limit alpha=%.1f after %.0e s: F=%.4f  K0 x + x/(1/Kpa+N/Kr)=%.4f  rel %.1e %s"
              % (alpha, Th, F, Fs, rel, "ok" if good else "FAIL"))
    # 3. effect-free sanity: a slow small sine gives a loop between the
    # initial tangent K0+Kpa and the static stiffness, dissipating energy
    sine = lambda tt: (1.0 * np.sin(2 * np.pi * 1.0 * np.asarray(tt)), 2 * np.pi * np.cos(2 * np.pi * np.asarray(tt)))
    r = Rig(p, N, sine, servo)
    tt = np.linspace(1.0, 3.0, 4001)
    st = r.states(r.solve(3.0), tt)
    F = rt_force(p, st, np.zeros(0))
    ksec = np.ptp(F) / np.ptp(st["x"])
    kstat = p["K0"] + 1 / (1 / p["Kpa"] + N / p["Kr"])
    work = np.trapz(F, st["x"]) / 2        # energy dissipated per cycle
    good = kstat * 0.9 < ksec < p["K0"] + p["Kpa"] and work > 0
    ok &= good
    Fmax = np.abs(F).max()
    print("sanity: secant %.0f N/mm in (%.0f, %.0f), dissipated %.1f N mm/cycle, loss factor %.3f %s"
          % (ksec, kstat, p["K0"] + p["Kpa"], work, work / (np.pi * Fmax * 1.0), "ok" if good else "FAIL"))
    # 4. generation is reproducible
    f1, tr1, _ = make_case(["viscous"], 11, duration=1.0)
    f2, tr2, _ = make_case(["viscous"], 11, duration=1.0)
    good = all(np.array_equal(a[4], b[4]) for a, b in zip(f1, f2))
    ok &= good
    print("reproducible: %s" % ("ok" if good else "FAIL"))
    print("selftest", "PASSED" if ok else "FAILED")
    return 0 if ok else 1


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    sub = ap.add_subparsers(dest="cmd", required=True)
    m = sub.add_parser("make", help="write one case")
    m.add_argument("--effects", required=True, help="E1[,E2]; 'none' for plain RT")
    m.add_argument("--seed", type=int, required=True)
    m.add_argument("--out", required=True)
    m.add_argument("--duration", type=float, default=4.0)
    m.add_argument("--cells", type=int, default=15)
    sub.add_parser("selftest", help="integrator convergence, static limit, sanity")
    s = sub.add_parser("sizes", help="generate every case of one seed in memory, print effect sizes")
    s.add_argument("--seed", type=int, default=1)
    s.add_argument("--duration", type=float, default=4.0)
    s.add_argument("--set", default="all", choices=("singles", "hard", "all"))
    s.add_argument("--cases", default="", help="space-separated effect lists instead of --set")
    a = ap.parse_args(argv)
    if a.cmd == "selftest":
        return selftest()
    if a.cmd == "make":
        t0 = time.time()
        files, truth, style = make_case(a.effects.split(","), a.seed, a.duration, a.cells)
        write_case(files, truth, style, a.out)
        print("%s seed %d: %d fit + %d holdout, %s, raw %.1fx / visible %.1fx noise (%.1f s)"
              % (a.effects, a.seed, len(truth["fit"]), len(truth["holdout"]), truth["units"],
                 truth["sizes"]["raw_rms_x_noise"], truth["sizes"]["visible_rms_x_noise"], time.time() - t0))
        return 0
    cases = (SINGLES if a.set in ("singles", "all") else []) + (HARD if a.set in ("hard", "all") else [])
    if a.cases:
        cases = a.cases.split()
    b = draw_base(a.seed, a.duration, 15)
    print("seed %d: %s, X=%.3g mm, fs=%d Hz, servo order %d %.0f Hz, noise x %.2f%% F %.2f%% of range"
          % (a.seed, ", ".join("%s=%.4g" % kv for kv in b["params"].items()), b["amp_mm"], b["fs_hz"],
             b["servo"]["order"], b["servo"]["fc_hz"], 100 * b["noise_x_frac"], 100 * b["noise_f_frac"]))
    print("fit: %s; holdout: %s" % (", ".join(m["kind"] for _, m in b["fit"]), ", ".join(m["kind"] for _, m in b["hold"])))
    print("%-28s %8s %8s  %s" % ("effects", "raw/sig", "vis/sig", "parameters"))
    for c in cases:
        t0 = time.time()
        files, truth, _ = make_case(c.split(","), a.seed, a.duration)
        eff = truth["params"]["effects"]
        desc = "; ".join("%s: %s" % (k, ", ".join("%s=%.4g" % (kk, vv) for kk, vv in v.items()
                                                   if isinstance(vv, (int, float)) and kk not in ("branch", "branch0")))
                         for k, v in eff.items())
        if "quant_err_rms_x_noise" in truth["sizes"]:
            desc += "; quantization error %.1fx analog noise" % truth["sizes"]["quant_err_rms_x_noise"]
        print("%-28s %8.1f %8.1f  %s  [%.0fs]" % (c, truth["sizes"]["raw_rms_x_noise"],
                                                truth["sizes"]["visible_rms_x_noise"], desc, time.time() - t0))
        sys.stdout.flush()
    return 0


if __name__ == "__main__":
    sys.exit(main())
