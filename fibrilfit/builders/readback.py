"""World transforms of many objects in one foreach_get, for every frame of a bake and for the check.

Reading `ob.matrix_world` object by object costs a Python object per read; at 100 layers that was
5 % of a bake. Here one foreach_get per collection reads every object of the collections that
hold ours (the rigid-body world's, or the model's part collections), and numpy picks ours out.
"""
from __future__ import annotations

import numpy as np


def collection_matrices(objects) -> np.ndarray:
    """World matrices (n, 4, 4) row-major, as float64, of every object of a collection's
    `objects`, in its order: one foreach_get (MatrixReader picks a list of objects out)."""
    mats = np.empty(16 * len(objects), dtype=np.float32)
    objects.foreach_get("matrix_world", mats)
    return mats.reshape(-1, 4, 4).transpose(0, 2, 1).astype(float)


class MatrixReader:
    """World matrices of a fixed list of objects, (n, 4, 4) row-major, as float64.

    The values equal `ob.matrix_world` read one by one (the same float32 numbers). Objects are
    matched to the collection's members by `session_uid`, checked again on every read, so a
    collection that changes (objects added, removed or reordered) is indexed again.
    """

    def __init__(self, objects, collections=()):
        """`collections`: read together, they should hold every object (e.g. the model's part
        collections, or the rigid-body world's); else the first object's smallest collection
        that holds them all is used, else objects are read one by one."""
        self.objects = list(objects)
        self._uids = np.fromiter((ob.session_uid for ob in self.objects), dtype=np.int64,
                                 count=len(self.objects))
        self._sources = ()
        candidates = [tuple(c for c in collections if c is not None)] if collections else []
        candidates += [(c,) for c in self._collections_of_first()]
        for sources in candidates:
            if sources and self._index_in(sources):
                break

    def _collections_of_first(self):
        if not self.objects:
            return []
        return sorted(self.objects[0].users_collection, key=lambda c: len(c.objects))

    @staticmethod
    def _member_uids(sources) -> np.ndarray:
        parts = []
        for coll in sources:
            uids = np.empty(len(coll.objects), dtype=np.int64)
            coll.objects.foreach_get("session_uid", uids)
            parts.append(uids)
        return np.concatenate(parts)

    def _index_in(self, sources) -> bool:
        members = self._member_uids(sources)
        if len(self._uids) and not len(members):
            return False
        order = np.argsort(members, kind="stable")
        where = np.minimum(np.searchsorted(members, self._uids, sorter=order), len(members) - 1)
        index = order[where] if len(members) else where
        if not np.array_equal(members[index], self._uids):
            return False
        self._sources, self._members, self._index = sources, members, index
        self._buffer = np.empty(len(members) * 16, dtype=np.float32)
        return True

    @property
    def bulk(self) -> bool:
        """True when reads go through foreach_get (else object by object)."""
        return bool(self._sources)

    def _raw(self) -> np.ndarray:
        """(n, 4, 4) as stored: Blender's column-major float[4][4], translation in row 3."""
        if self._sources:
            if not np.array_equal(self._member_uids(self._sources), self._members):
                sources, self._sources = self._sources, ()
                self._index_in(sources)
        if not self._sources:
            return np.array([np.array(ob.matrix_world).T for ob in self.objects],
                            dtype=np.float32).reshape(-1, 4, 4)
        start = 0
        for coll in self._sources:
            end = start + 16 * len(coll.objects)
            coll.objects.foreach_get("matrix_world", self._buffer[start:end])
            start = end
        return self._buffer.reshape(-1, 4, 4)[self._index]

    def matrices(self) -> np.ndarray:
        return self._raw().transpose(0, 2, 1).astype(float)

    def positions(self) -> np.ndarray:
        """World-space origins, (n, 3)."""
        return self._raw()[:, 3, :3].astype(float)
