#!/usr/bin/env python3
"""The coefficients of ltc_corrections.h's LTC_Atan (issue 19, sixth round): atan(x) = x P(x^2) on [0, 1],
P of degree 8 fitted by iteratively reweighted least squares on Chebyshev nodes toward the
smallest largest relative error (printed: 1.5e-8, below float's 6e-8). Run by hand (numpy):
    python3 tools/fits/fit_atan.py
GPU atan (lavapipe's) is off by up to ~1e-4 relative, which the streak estimate's lateral
closed form (LTC_StreakLateral) would carry; the fit is ours, the method textbook.
"""
import numpy as np

N, DEG = 4000, 8
x = np.cos(np.pi * (np.arange(N) + 0.5) / N) * 0.5 + 0.5
A = np.vstack([(x * x) ** k for k in range(DEG + 1)]).T
y = np.arctan(x) / x
w = np.ones(N)
for _ in range(30):
    c, *_ = np.linalg.lstsq(A * w[:, None], y * w, rcond=None)
    e = (A @ c - y) / y
    w = w * (1 + np.abs(e) / np.abs(e).max())
xs = np.linspace(1e-6, 1, 200001)
rel = np.abs(np.polyval(c[::-1], xs * xs) * xs - np.arctan(xs)) / np.arctan(xs)
print("largest relative error on (0, 1]: %.2g" % rel.max())
print("coefficients (x^0, x^2, ...):", ", ".join("%.9gf" % v for v in c))
