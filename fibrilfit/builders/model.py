"""The fibril: `layers` copies of a core (slab or outline) with `protofilaments` chains (anchor +
linker + globule) each, every layer raised and twisted, every protofilament turned and raised.

This module: the built model's handles (Model, find_model), the build's steps and stages. The
bodies of each layer: layers.py; the parameters a model root stores: stored.py; colours:
colours.py."""
from __future__ import annotations

from dataclasses import dataclass, field

import bpy

from ..model import params as P
from .exit_path import build_exit_path
from .layers import LayerBuilder
from .physics import check_world_free, ensure_world
from .scene import (INDEX, LAYER, PART_COLLECTIONS, PROTOFILAMENT, ROOT, TAG, clear_model,
                    find_root, new_collection, tag)
from .stored import params_of, store_params

@dataclass
class Model:
    """Handles to a built model. `chain[c][i]`: chain c, member i (0 anchor .. linker globule).

    Chains are layer-major: chain c is protofilament c % K of layer c // K (helix.chain_layers);
    with one protofilament, chain c is layer c. `slabs[k]`: layer k's core. `constraints[c]`:
    chain c's bonds. A mixed fibril (model/occupancy.py): `chain` holds the decorated subunits'
    chains only, in the same order (occupancy.decorated_chains(params) names them); `tails[t]`
    is an undecorated subunit's bare tail (when bare_tail asks for one), `bare_anchors` the
    marker at each undecorated subunit's anchor when it has none (no body: drawn only)."""

    root: bpy.types.Collection
    params: P.Params
    slabs: list
    chain: list
    constraints: list
    tails: list = field(default_factory=list)
    bare_anchors: list = field(default_factory=list)

    @property
    def globules(self) -> list:
        """Every chain's globules, chain-major: globule g is domain g % D of chain g // D
        (D = len(params.domains); one domain: the chain's last member)."""
        members = [d.member for d in self.params.domains]
        return [c[i] for c in self.chain for i in members]

    @property
    def active(self) -> list:
        return [ob for c in self.chain for ob in c[1:]]


def find_model(scene: bpy.types.Scene) -> Model | None:
    """The model built in `scene`, reassembled from its tags, or None."""
    root = find_root(scene)
    if root is None:
        return None
    p = params_of(root)
    slabs, chain, cons, tails, bare = {}, {}, {}, {}, {}
    # Not root.all_objects: Blender rebuilds that cache in O(n²) after any change (4.5 s for
    # 14,000 objects, measured on 5.0.1); each collection's own objects are a plain list.
    for ob in (ob for coll in (root, *root.children_recursive) for ob in coll.objects):
        role, k = ob.get(TAG), ob.get(LAYER)
        key = (k, ob.get(PROTOFILAMENT, 0))  # layer-major, as the builder numbers chains
        if role == "slab":
            slabs[k] = ob
        elif role in ("anchor", "residue", "globule"):
            chain.setdefault(key, {})[ob[INDEX]] = ob
        elif role == "bond":
            cons.setdefault(key, {})[ob[INDEX]] = ob
        elif role == "tail":
            tails.setdefault(key, {})[ob[INDEX]] = ob
        elif role == "bare_anchor":
            bare[key] = ob
    ordered = lambda d: [d[i] for i in sorted(d)]
    return Model(root, p, ordered(slabs), [ordered(chain[k]) for k in sorted(chain)],
                 [ordered(cons[k]) for k in sorted(cons)],
                 [ordered(tails[k]) for k in sorted(tails)], [bare[k] for k in sorted(bare)])


PARTS = ("slab", "anchor", "linker", "globule")  # one layer's parts, in the tutorial's order
STEPS = (*PARTS, "layers")  # the build steps; "layers" replicates layer 0 to every layer
STAGE = "fibrilfit_stage"   # on the root collection: the last step done, then "baked", "checked"
LAST_FRAME = "fibrilfit_last_frame"  # on the root collection: the last frame the bake reached
STAGES = (*STEPS, "baked", "checked")
IMAGES = "fibrilfit_images"  # on the root collection of a periodic cell: its images, by kind
def build_model(p: P.Params, scene: bpy.types.Scene | None = None, *, force: bool = False) -> Model:
    """Build the model in `scene` (default: the context's), replacing any previous one.

    Validates first (raising ParamError), so bad input leaves the scene as it was.
    """
    return build_steps(p, scene, upto="layers", force=force)


def build_steps(p: P.Params, scene: bpy.types.Scene | None = None, *, upto: str = "layers",
                force: bool = False) -> Model:
    """Build the steps of STEPS up to `upto` from scratch, replacing any previous model.

    The parts go into layer 0 in the tutorial's order; the step "layers" then replicates them,
    each layer raised by `rise` and turned by `twist`. The sidebar's step buttons call this.
    """
    if upto not in STEPS:
        raise ValueError(f"upto must be one of {STEPS}")
    scene = scene or bpy.context.scene
    model = start_model(p, scene, force=force)
    steps = STEPS[:STEPS.index(upto) + 1]
    builder = LayerBuilder(model, scene)
    for part in steps:
        if part in PARTS:
            builder.add(part, 0)
    if "layers" in steps:
        for k in range(1, model.params.layers):
            for part in PARTS:
                builder.add(part, k)
    builder.place()
    if "layers" in steps and model.params.periodic:
        from .periodic import build_images
        model.root[IMAGES] = build_images(model, scene)
    if "layers" in steps:
        build_exit_path(model)  # a buried anchor's exit, drawn (none on the surface)
    # No view_layer.update() here: place() sets valid world matrices, and the depsgraph is
    # built once, on first use (the bake's first frame, or the viewport's next redraw).
    set_stage(model, upto)
    return model


def start_model(p: P.Params, scene: bpy.types.Scene, *, force: bool = False) -> Model:
    """Validate `p`, remove any previous model, and make the model's empty collections and world."""
    p = P.validate(p, force=force)
    check_world_free(scene)
    clear_model(scene)
    rbw = ensure_world(scene)
    root = new_collection("FibrilFit", ROOT, scene.collection)
    store_params(root, p)
    for role, title in PART_COLLECTIONS.items():
        new_collection(f"FibrilFit {title}", role + "s", root)
    rbw.collection = tag(bpy.data.collections.new("FibrilFit bodies"), "rigid_bodies")
    rbw.constraints = tag(bpy.data.collections.new("FibrilFit constraints"), "rigid_constraints")
    return Model(root, p, [], [], [])


def set_stage(model: Model, stage: str, *, last_frame: int | None = None) -> None:
    """Record how far the model got (see STAGES); a bake also records its last frame."""
    if stage not in STAGES:
        raise ValueError(f"stage must be one of {STAGES}")
    model.root[STAGE] = stage
    if last_frame is not None:
        model.root[LAST_FRAME] = int(last_frame)


def last_frame(model: Model) -> int:
    """The frame the bake ended on (the tutorial's "last frame")."""
    return int(model.root.get(LAST_FRAME, model.params.bake_frames()))


def update_params(model: Model, p: P.Params) -> None:
    """Give a built model new parameters that do not change what was built (bake, check)."""
    model.params = p
    store_params(model.root, p)


def model_stage(scene: bpy.types.Scene) -> str:
    """How far the scene's model got: "" (none), a step of STEPS, "baked" or "checked".

    A bake counts only while its cache is kept (freeing it in Blender's physics panel undoes it).
    Cheap enough for poll() and draw(): reads the root collection, not every object.
    """
    root = find_root(scene)
    if root is None:
        return ""
    stage = root.get(STAGE, "layers")  # models from before stages were recorded were whole
    if stage in ("baked", "checked"):
        rbw = scene.rigidbody_world
        if rbw is None or not rbw.point_cache.is_baked:
            return "layers"
    return stage


