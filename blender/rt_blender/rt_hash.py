"""Cycles' hashes (util/hash.h, Apache-2.0, Blender Foundation) as the exporter needs them:
the values Cycles gives objects, instances and mesh islands, reproduced exactly."""

import numpy as np


def lookup3_final(a, b, c):
    """Bob Jenkins' lookup3 `final` on 32-bit words (Cycles' util/hash.h); returns c."""
    def rot(x, k):
        return ((x << k) | (x >> (32 - k))) & 0xFFFFFFFF
    # Each step: word x ^= word y, then x -= y rotated by k.
    for x, y, k in ((2, 1, 14), (0, 2, 11), (1, 0, 25), (2, 1, 16), (0, 2, 4), (1, 0, 14), (2, 1, 24)):
        w = [a, b, c]
        w[x] = ((w[x] ^ w[y]) - rot(w[y], k)) & 0xFFFFFFFF
        a, b, c = w
    return c


def hash_uint(k):
    """Cycles' hash_uint: lookup3 of one 32-bit word."""
    seed = (0xDEADBEEF + (1 << 2) + 13) & 0xFFFFFFFF
    return lookup3_final((seed + k) & 0xFFFFFFFF, seed, seed)


def instance_random(random_id):
    """Object Info's Random of an instance: its depsgraph `random_id` over 2^32 - 1, as
    Cycles sets it."""
    return float(np.float32(random_id & 0xFFFFFFFF) * (np.float32(1.0) / np.float32(0xFFFFFFFF)))
