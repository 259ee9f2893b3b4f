#!/usr/bin/env python3
"""Bakes rt's microfacet albedo tables (crates/rt/src/gpu/microfacet_tables.bin).

The tables are Cycles' (Blender 4.x/5.x `intern/cycles/app/cycles_precompute.cpp`), with
the same definitions, sizes, grids and layout, so that rt's energy compensation reads the
numbers Cycles reads:

  ggx_E[32][32]            albedo of GGX reflection (no Fresnel), [mu][rough]
  ggx_Eavg[32]             its cosine-weighted average over mu, [rough]
  ggx_glass_E[16][16][16]  albedo of a GGX dielectric (reflection + refraction, exact
                           Fresnel, no 1/eta^2), IOR > 1, [z][mu][rough]
  ggx_glass_Eavg[16][16]   its average over mu, [z][rough]
  ggx_glass_inv_E, ggx_glass_inv_Eavg   the same for 1/IOR
  ggx_gen_schlick_ior_s[16][16][16]     mean interpolation factor s between F0 and 1 of
                           the real Fresnel curve over the reflected directions, [z][mu][rough]

with rough = sqrt(alpha) = x / (n - 1), mu = cos(view) = y / (n - 1) (both clamped to
[1e-4, 1]), z = clamp(k / 15, 1e-4, 0.99) and IOR = ior_from_F0(z^4). The GGX model is
Cycles': visible-normal sampling and the height-correlated Smith masking-shadowing
1 / (1 + Lambda_i + Lambda_o). Cycles integrates by Monte Carlo; this script uses a
midpoint rule over the visible-normal sampler's unit square (N x N points), which
converges to the same integrals (to ~1e-4 here). Needs numpy; a few minutes.

Output: little-endian f32, the tables in the order above, nothing else.
"""

import sys

import numpy as np

N = 192  # quadrature points per side of the sampler's unit square
N_MU_AVG = 64  # midpoints in mu for the averages


def ior_from_f0(f0):
    s = np.sqrt(f0)
    return (1.0 + s) / (1.0 - s)


def lam(alpha2, cos):
    c2 = np.maximum(cos * cos, 1e-30)
    return 0.5 * (np.sqrt(1.0 + alpha2 * np.maximum(1.0 / c2 - 1.0, 0.0)) - 1.0)


def grid():
    u = (np.arange(N) + 0.5) / N
    u1, u2 = np.meshgrid(u, u, indexing="ij")
    return u1.ravel(), u2.ravel()


U1, U2 = grid()


def sample_vndf(mu, alpha):
    """Visible normals seen from wi = (sqrt(1 - mu^2), 0, mu); broadcasts over alpha
    (shape [A, 1]) and the square's points (shape [P])."""
    sin = np.sqrt(max(0.0, 1.0 - mu * mu))
    wx, wz = alpha * sin, np.full_like(alpha, mu)
    norm = np.sqrt(wx * wx + wz * wz)
    vx, vz = wx / norm, wz / norm
    # T1 = (0, 1, 0) (wi lies in the xz plane), T2 = cross(v, T1) = (-vz, 0, vx).
    r = np.sqrt(U1)
    phi = 2.0 * np.pi * U2
    t1 = r * np.cos(phi)
    t2 = r * np.sin(phi)
    s = 0.5 * (1.0 + vz)
    t2 = (1.0 - s) * np.sqrt(np.maximum(0.0, 1.0 - t1 * t1)) + s * t2
    tz = np.sqrt(np.maximum(0.0, 1.0 - t1 * t1 - t2 * t2))
    hx = -t2 * vz + tz * vx
    hy = t1 + 0.0 * vx
    hz = t2 * vx + tz * vz
    hx, hy, hz = alpha * hx, alpha * hy, np.maximum(0.0, hz)
    n = np.sqrt(hx * hx + hy * hy + hz * hz)
    return hx / n, hy / n, hz / n, sin


def fresnel_dielectric(cos_i, eta):
    c = np.abs(cos_i)
    g2 = eta * eta - 1.0 + c * c
    tir = g2 < 0.0
    g = np.sqrt(np.maximum(g2, 0.0))
    a = (g - c) / (g + c)
    b = (c * (g + c) - 1.0) / (c * (g - c) + 1.0)
    f = 0.5 * a * a * (1.0 + b * b)
    return np.where(tir, 1.0, f)


def reflection_terms(mu, alpha):
    """Per sample: validity of the reflected direction, the sample weight eval/pdf, cos(H, wi)."""
    hx, hy, hz, sin = sample_vndf(mu, alpha)
    cos_hi = hx * sin + hz * mu
    oz = 2.0 * cos_hi * hz - mu
    a2 = alpha * alpha
    li = lam(a2, mu)
    weight = (1.0 + li) / (1.0 + li + lam(a2, oz))
    return oz > 0.0, weight, cos_hi, (hx, hy, hz, sin)


def ggx_e(mu, alpha):
    valid, weight, _, _ = reflection_terms(mu, alpha)
    return np.where(valid, weight, 0.0).mean(axis=1)


def glass_e(mu, alpha, eta):
    valid, w_reflect, cos_hi, (hx, hy, hz, sin) = reflection_terms(mu, alpha)
    f = fresnel_dielectric(cos_hi, eta)
    # Refracted direction through H (Cycles' fresnel_dielectric): wo = -wi/eta + (cos/eta - cos_t) H.
    sin2_t = (1.0 - cos_hi * cos_hi) / (eta * eta)
    cos_t = np.sqrt(np.maximum(0.0, 1.0 - sin2_t))
    oz = -mu / eta + (cos_hi / eta - cos_t) * hz
    a2 = alpha * alpha
    li = lam(a2, mu)
    w_refract = (1.0 + li) / (1.0 + li + lam(a2, oz))
    value = f * np.where(valid, w_reflect, 0.0) + (1.0 - f) * w_refract
    return value.mean(axis=1)


def gen_schlick_s(mu, alpha, eta):
    valid, _, cos_hi, _ = reflection_terms(mu, alpha)
    f_real = fresnel_dielectric(cos_hi, eta)
    f0 = ((eta - 1.0) / (eta + 1.0)) ** 2
    s = np.clip((f_real - f0) / (1.0 - f0), 0.0, 1.0)
    return np.where(valid, s, 0.0).mean(axis=1)


def axis(n):
    return np.clip(np.arange(n) / (n - 1), 1e-4, 1.0)


def table_2d(n, f):
    alpha = (axis(n) ** 2)[:, None]
    return np.stack([f(mu, alpha) for mu in axis(n)])


def average(n, f):
    alpha = (axis(n) ** 2)[:, None]
    mus = (np.arange(N_MU_AVG) + 0.5) / N_MU_AVG
    return sum(2.0 * mu * f(mu, alpha) for mu in mus) / N_MU_AVG


def iors(n):
    z = np.clip(np.arange(n) / (n - 1), 1e-4, 0.99)
    return ior_from_f0(z**4)


def main(path):
    tables = [table_2d(32, ggx_e), average(32, ggx_e)]
    for invert in (False, True):
        etas = [1.0 / i if invert else i for i in iors(16)]
        tables.append(np.stack([table_2d(16, lambda mu, a, e=e: glass_e(mu, a, e)) for e in etas]))
        tables.append(np.stack([average(16, lambda mu, a, e=e: glass_e(mu, a, e)) for e in etas]))
    tables.append(np.stack([table_2d(16, lambda mu, a, e=e: gen_schlick_s(mu, a, e)) for e in iors(16)]))
    data = np.concatenate([np.clip(t, 0.0, 1.0).ravel() for t in tables]).astype("<f4")
    data.tofile(path)
    print(f"{path}: {data.size} floats; ggx_E[mu=1] at rough 0, 0.5, 1: {tables[0][31][[0, 15, 31]]}")


if __name__ == "__main__":
    main(sys.argv[1] if len(sys.argv) > 1 else "crates/rt/src/gpu/microfacet_tables.bin")
