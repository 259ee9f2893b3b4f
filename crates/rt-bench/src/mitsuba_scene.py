"""Loads a scene that rt translated for Mitsuba 3 (`rt bench mitsuba-scene`, or `rt bench
compare` itself): a Mitsuba scene dictionary as JSON, beside its PLY meshes. The one
translation is rt's (crates/rt-bench/src/mitsuba_scene.rs); this only turns the parts JSON cannot
hold into Mitsuba's objects (a sensor's look-at into a transform) and sets the sampler.
"""

import copy
import json

import mitsuba as mi


def _objects(node):
    if isinstance(node, dict):
        look_at = node.get("to_world", {}).get("look_at") if isinstance(node.get("to_world"), dict) else None
        if look_at is not None:
            node["to_world"] = mi.ScalarTransform4f().look_at(**look_at)
        for value in node.values():
            _objects(value)


def scene_dict(translated, sampler=None, spp=None):
    """The dictionary `mi.load_dict` takes, with `sampler` (a Mitsuba sampler's name) and
    `spp` in place of the translation's own where given."""
    d = copy.deepcopy(translated)
    _objects(d)
    s = d["sensor"]["sampler"]
    if sampler:
        s["type"] = sampler
    if spp:
        s["sample_count"] = spp
    return d


def load(path, sampler=None, spp=None):
    """The Mitsuba scene of the JSON file at `path`."""
    with open(path) as f:
        return mi.load_dict(scene_dict(json.load(f), sampler, spp))
