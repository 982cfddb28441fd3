"""Triangle meshes: the 3D surface a 3D force law sums over.

A :class:`TriangleMesh` is an immutable set of vertices and counter-clockwise (seen from outside)
triangles in the body frame; it carries each facet's centroid, outward unit normal and area. Files are
read with the optional ``trimesh`` package (``pip install terradyn[mesh]``); everything else is NumPy.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from functools import cached_property
from pathlib import Path
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from ..errors import InputError, check_positive
from .kinematics import Pose3D

__all__ = ["TriangleMesh", "load_mesh", "resample", "save_mesh"]

# Largest facet count resample() will build.
_MAX_FACETS = 20_000_000


@dataclass(frozen=True, eq=False)
class TriangleMesh:
    """An immutable triangle mesh in the body frame.

    Attributes
    ----------
    vertices : ndarray, shape (V, 3)
        Vertex coordinates [m].
    faces : ndarray of int, shape (F, 3)
        Vertex indices of each triangle, counter-clockwise seen from outside (outward normal by the
        right-hand rule).
    centroids : ndarray, shape (F, 3)
        Facet centroids [m] (derived).
    normals : ndarray, shape (F, 3)
        Outward unit normals [-] (derived); exactly zero for zero-area facets.
    areas : ndarray, shape (F,)
        Facet areas [m^2] (derived); zero-area facets are kept and carry no load.
    """

    vertices: NDArray[np.float64]
    faces: NDArray[np.int64]
    centroids: NDArray[np.float64] = field(init=False, repr=False)
    normals: NDArray[np.float64] = field(init=False, repr=False)
    areas: NDArray[np.float64] = field(init=False, repr=False)

    def __post_init__(self) -> None:
        try:
            vtx = np.array(self.vertices, dtype=np.float64)
            fcs = np.array(self.faces)
        except (TypeError, ValueError):
            raise InputError(
                "mesh", "unreadable arrays", "vertices (V, 3) floats and faces (F, 3) ints"
            ) from None
        if vtx.ndim != 2 or vtx.shape[1] != 3 or vtx.shape[0] < 3:
            raise InputError("mesh.vertices", vtx.shape, "an array of shape (V, 3) with V >= 3")
        if not np.all(np.isfinite(vtx)):
            raise InputError("mesh.vertices", "non-finite values", "finite coordinates [m]")
        if fcs.ndim != 2 or fcs.shape[1] != 3 or fcs.shape[0] < 1:
            raise InputError("mesh.faces", fcs.shape, "an array of shape (F, 3) with F >= 1")
        if not np.issubdtype(fcs.dtype, np.integer):
            raise InputError("mesh.faces", fcs.dtype, "integer vertex indices")
        fcs = fcs.astype(np.int64)
        if fcs.min() < 0 or fcs.max() >= vtx.shape[0]:
            raise InputError(
                "mesh.faces", f"indices in [{fcs.min()}, {fcs.max()}]", f"indices in [0, {vtx.shape[0] - 1}]"
            )
        tri = vtx[fcs]
        cross = np.cross(tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 0])
        norm = np.sqrt(np.einsum("ij,ij->i", cross, cross))
        safe = np.where(norm > 0.0, norm, 1.0)
        normals = np.where((norm > 0.0)[:, None], cross / safe[:, None], 0.0)
        derived = {
            "vertices": vtx,
            "faces": fcs,
            "centroids": tri.mean(axis=1),
            "normals": normals,
            "areas": 0.5 * norm,
        }
        for name, arr in derived.items():
            arr = np.ascontiguousarray(arr)
            arr.setflags(write=False)
            object.__setattr__(self, name, arr)

    @cached_property
    def kernel_arrays(self) -> tuple[NDArray[np.float64], NDArray[np.float64], NDArray[np.float64]]:
        """(centroids (3, F) [m], normals (3, F) [-], areas (F,) [m^2]), component-major and contiguous.

        The layout the 3D-RFT kernels read (it lets their facet loop vectorise). Computed once.
        """
        out = (np.ascontiguousarray(self.centroids.T), np.ascontiguousarray(self.normals.T), self.areas)
        for arr in out[:2]:
            arr.setflags(write=False)
        return out

    @property
    def facet_count(self) -> int:
        return int(self.faces.shape[0])

    @property
    def vertex_count(self) -> int:
        return int(self.vertices.shape[0])

    @property
    def area(self) -> float:
        """Total surface area [m^2]."""
        return float(self.areas.sum())

    @property
    def volume(self) -> float:
        """Enclosed volume [m^3] by the divergence theorem (meaningful for closed meshes).

        Positive when the normals point outward.
        """
        tri = self.vertices[self.faces]
        return float(np.einsum("ij,ij->i", tri[:, 0], np.cross(tri[:, 1], tri[:, 2])).sum() / 6.0)

    @property
    def bounds(self) -> NDArray[np.float64]:
        """Axis-aligned bounding box [[x_min, y_min, z_min], [x_max, y_max, z_max]] [m]."""
        return np.array([self.vertices.min(axis=0), self.vertices.max(axis=0)])

    def edge_lengths(self) -> NDArray[np.float64]:
        """Lengths (F, 3) [m] of the edges (v0 v1, v1 v2, v2 v0) of each facet."""
        tri = self.vertices[self.faces]
        return np.linalg.norm(tri[:, [1, 2, 0]] - tri, axis=2)

    def is_closed(self) -> bool:
        """True if every edge is shared by exactly two facets that traverse it in opposite senses."""
        e = self.faces[:, [0, 1, 1, 2, 2, 0]].reshape(-1, 2)
        n = self.vertex_count
        directed = np.unique(e[:, 0] * n + e[:, 1], return_counts=True)
        if np.any(directed[1] != 1):
            return False
        reverse = e[:, 1] * n + e[:, 0]
        return bool(np.all(np.isin(reverse, directed[0], assume_unique=False)))

    def transformed(self, pose: Pose3D) -> TriangleMesh:
        """The mesh placed in the world at ``pose`` (vertices ``position + rotation @ v``)."""
        return TriangleMesh(pose.to_world(self.vertices), self.faces)

    def translated(self, offset: ArrayLike) -> TriangleMesh:
        """The mesh moved by ``offset`` (3,) [m]."""
        d = np.asarray(offset, dtype=np.float64)
        if d.shape != (3,) or not np.all(np.isfinite(d)):
            raise InputError("offset", offset, "three finite numbers [m]")
        return TriangleMesh(self.vertices + d, self.faces)

    def scaled(self, factor: float) -> TriangleMesh:
        """The mesh scaled by ``factor`` > 0 about the body origin (e.g. 1e-3 for mm to m)."""
        return TriangleMesh(self.vertices * check_positive("factor", factor), self.faces)

    def merged(self, other: TriangleMesh) -> TriangleMesh:
        """Both meshes as one (vertices are not welded)."""
        faces = np.vstack((self.faces, other.faces + self.vertex_count))
        return TriangleMesh(np.vstack((self.vertices, other.vertices)), faces)


def _import_trimesh(purpose: str) -> Any:
    try:
        import trimesh
    except ImportError:
        raise InputError(
            "trimesh",
            "not installed",
            f"the optional package trimesh to {purpose}",
            "install the mesh extra: pip install 'terradyn[mesh]'",
        ) from None
    return trimesh


def load_mesh(path: str | Path, *, scale: float = 1.0, allow_open: bool = False) -> TriangleMesh:
    """Read a triangle mesh file (STL, OBJ, PLY, OFF, GLB, ... anything trimesh reads).

    Parameters
    ----------
    path : str or Path
        The file. Coordinates are taken as the body frame.
    scale : float
        Factor applied to the coordinates to get metres (1e-3 for a file in millimetres).
    allow_open : bool
        Accept a mesh that is not closed (watertight). Off by default: an open surface has no inside,
        so its outward normals (which decide the leading-edge rule) cannot be checked.

    Returns
    -------
    TriangleMesh
        Duplicate vertices merged; for a closed mesh the facet winding is made consistent and outward
        (trimesh's ``fix_normals``) if it was not. A closed, consistently wound STL file is read with
        NumPy alone (no trimesh import, which costs most of a second); every other file goes through
        trimesh.

    Raises
    ------
    InputError
        If trimesh is missing, the file does not exist, it holds no triangles, or it is open (unless
        ``allow_open``). The message names the file.
    """
    p = Path(path)
    field_name = f"mesh file {str(path)!r}"
    check_positive("scale", scale)
    if not p.is_file():
        raise InputError(field_name, str(path), "an existing mesh file", "check the path")
    if p.suffix.lower() == ".stl":
        fast = _read_closed_stl(p)
        if fast is not None:
            return fast.scaled(scale) if scale != 1.0 else fast
    trimesh = _import_trimesh("read mesh files")
    try:
        loaded = trimesh.load(str(p), force="mesh", process=True)
    except Exception as exc:  # trimesh raises many exception types for unreadable files
        raise InputError(
            field_name, type(exc).__name__, "a readable triangle mesh file (STL, OBJ, PLY, ...)", str(exc)
        ) from None
    faces = getattr(loaded, "faces", None)
    if faces is None or len(faces) == 0:
        raise InputError(field_name, "no triangles", "a file holding a triangle mesh")
    if not loaded.is_watertight:
        if not allow_open:
            raise InputError(
                field_name,
                "an open mesh (not watertight)",
                "a closed triangle mesh",
                "fill its holes in a mesh tool, or pass allow_open=True if it is a sheet whose "
                "normals already point the right way",
            )
    elif not loaded.is_winding_consistent or loaded.volume < 0:
        trimesh.repair.fix_normals(loaded)
    mesh = TriangleMesh(np.asarray(loaded.vertices, dtype=np.float64), np.asarray(loaded.faces))
    return mesh.scaled(scale) if scale != 1.0 else mesh


def _stl_triangles(path: Path) -> NDArray[np.float64] | None:
    """Corner coordinates (F, 3, 3) of a binary or ASCII STL file, or None if it is neither."""
    data = path.read_bytes()
    if len(data) >= 84:
        count = int(np.frombuffer(data, dtype="<u4", count=1, offset=80)[0])
        if len(data) == 84 + 50 * count and count > 0:
            record = np.dtype([("normal", "<f4", 3), ("corners", "<f4", (3, 3)), ("attribute", "<u2")])
            rows = np.frombuffer(data, dtype=record, count=count, offset=84)
            return np.asarray(rows["corners"], dtype=np.float64)
    try:
        text = data.decode("ascii")
    except UnicodeDecodeError:
        return None
    if not text.lstrip().lower().startswith("solid"):
        return None
    values = []
    for line in text.splitlines():
        parts = line.split()
        if len(parts) == 4 and parts[0].lower() == "vertex":
            try:
                values.append([float(v) for v in parts[1:]])
            except ValueError:
                return None
    if not values or len(values) % 3:
        return None
    return np.asarray(values, dtype=np.float64).reshape(-1, 3, 3)


def _read_closed_stl(path: Path) -> TriangleMesh | None:
    """A closed, consistently wound STL read with NumPy alone (no trimesh import), else None.

    Corners are welded where their coordinates are bit-identical (as trimesh's merge does for STL
    files, whose shared corners repeat the same floats); the winding is flipped if the volume is
    negative. Anything else (open, inconsistently wound, degenerate indices, unreadable) returns None
    and :func:`load_mesh` takes the trimesh path, which repairs or reports it.
    """
    tri = _stl_triangles(path)
    if tri is None or not np.all(np.isfinite(tri)):
        return None
    vertices, inverse = np.unique(tri.reshape(-1, 3), axis=0, return_inverse=True)
    faces = inverse.reshape(-1, 3).astype(np.int64)
    if vertices.shape[0] < 3 or np.any(
        (faces[:, 0] == faces[:, 1]) | (faces[:, 1] == faces[:, 2]) | (faces[:, 0] == faces[:, 2])
    ):
        return None
    mesh = TriangleMesh(vertices, faces)
    if not mesh.is_closed():
        return None
    if mesh.volume < 0.0:
        mesh = TriangleMesh(vertices, faces[:, ::-1].copy())
    return mesh


def save_mesh(mesh: TriangleMesh, path: str | Path) -> Path:
    """Write ``mesh`` to ``path`` (format from the suffix: .stl, .obj, .ply, ...) with trimesh."""
    trimesh = _import_trimesh("write mesh files")
    p = Path(path)
    out = trimesh.Trimesh(vertices=np.array(mesh.vertices), faces=np.array(mesh.faces), process=False)
    try:
        out.export(str(p))
    except (ValueError, KeyError, OSError) as exc:
        raise InputError(
            f"mesh file {str(path)!r}", p.suffix, "a writable path with a mesh suffix", str(exc)
        ) from None
    return p


def _split_long_edges(
    vertices: NDArray[np.float64], faces: NDArray[np.int64], size: float
) -> tuple[NDArray[np.float64], NDArray[np.int64], bool]:
    """One conforming refinement pass: bisect every edge longer than ``size``; True if none was."""
    nv = vertices.shape[0]
    e = faces[:, [0, 1, 1, 2, 2, 0]].reshape(-1, 3, 2)
    lo, hi = np.minimum(e[..., 0], e[..., 1]), np.maximum(e[..., 0], e[..., 1])
    keys, inverse = np.unique((lo * nv + hi).reshape(-1), return_inverse=True)
    a, b = keys // nv, keys % nv
    long_edge = np.linalg.norm(vertices[a] - vertices[b], axis=1) > size
    if not np.any(long_edge):
        return vertices, faces, True
    mid_index = np.full(keys.shape[0], -1, dtype=np.int64)
    mid_index[long_edge] = nv + np.arange(int(long_edge.sum()))
    new_vertices = np.vstack((vertices, 0.5 * (vertices[a[long_edge]] + vertices[b[long_edge]])))
    mids = mid_index[inverse.reshape(-1, 3)]  # mids[:, k]: midpoint of edge (v_k, v_k+1) or -1
    split = mids >= 0
    count = split.sum(axis=1)
    # Rotate each face so that: one split edge -> it is edge 0; two split -> edge 2 is the unsplit one.
    shift = np.zeros(faces.shape[0], dtype=np.int64)
    one = count == 1
    shift[one] = np.argmax(split[one], axis=1)
    two = count == 2
    shift[two] = (np.argmin(split[two], axis=1) + 1) % 3
    order = (np.arange(3)[None, :] + shift[:, None]) % 3
    f = np.take_along_axis(faces, order, axis=1)
    m = np.take_along_axis(mids, order, axis=1)
    v0, v1, v2, m0, m1, m2 = f[:, 0], f[:, 1], f[:, 2], m[:, 0], m[:, 1], m[:, 2]
    out = [f[count == 0]]
    out += [np.column_stack((v0, m0, v2))[one], np.column_stack((m0, v1, v2))[one]]
    # Two split edges: corner triangle (m0, v1, m1) and the quad (v0, m0, m1, v2) cut on its shorter diagonal.
    diag_a = np.linalg.norm(new_vertices[v0] - new_vertices[np.maximum(m1, 0)], axis=1)
    diag_b = np.linalg.norm(new_vertices[m0] - new_vertices[v2], axis=1)
    use_a = two & (diag_a <= diag_b)
    use_b = two & ~(diag_a <= diag_b)
    out += [np.column_stack((m0, v1, m1))[two]]
    out += [np.column_stack((v0, m0, m1))[use_a], np.column_stack((v0, m1, v2))[use_a]]
    out += [np.column_stack((v0, m0, v2))[use_b], np.column_stack((m0, m1, v2))[use_b]]
    three = count == 3
    out += [
        np.column_stack((v0, m0, m2))[three],
        np.column_stack((m0, v1, m1))[three],
        np.column_stack((m2, m1, v2))[three],
        np.column_stack((m0, m1, m2))[three],
    ]
    return new_vertices, np.vstack(out), False


def resample(mesh: TriangleMesh, target_facet_size: float) -> TriangleMesh:
    """Refine ``mesh`` until no edge is longer than ``target_facet_size`` [m].

    Edges longer than the target are bisected, and each facet is re-triangulated by the pattern of its
    split edges, repeatedly. Shared edges are split the same way on both sides, so a closed mesh stays
    closed; the surface itself (and hence volume and area) is unchanged. Facets already small enough
    are kept.

    Raises
    ------
    InputError
        If the target is not a positive length or would need more than 20 million facets.
    """
    size = check_positive("target_facet_size", target_facet_size)
    estimate = mesh.area / (0.25 * math.sqrt(3.0) * size * size)
    if estimate > _MAX_FACETS:
        raise InputError(
            "target_facet_size",
            size,
            f"a size giving at most {_MAX_FACETS} facets",
            f"about {estimate:.3g} facets would be needed for {mesh.area:.4g} m^2 of surface",
        )
    vertices, faces = np.array(mesh.vertices), np.array(mesh.faces)
    for _ in range(200):
        vertices, faces, done = _split_long_edges(vertices, faces, size)
        if done:
            return TriangleMesh(vertices, faces)
    raise InputError("target_facet_size", size, "a size the refinement can reach", "mesh too distorted")
