"""3D bodies as triangle meshes, and 3D rigid-body kinematics.

:class:`TriangleMesh` holds a body surface in its own frame (facet centroids, outward unit normals,
areas); :func:`load_mesh` reads files with the optional trimesh package, :func:`resample` refines a
mesh to a facet size, :func:`wheel_from_mesh` places a CAD wheel (units, axle, centre) in the
body frame, :func:`visible_facets` finds the facets reachable from outside, and
:mod:`~terradyn.geometry3d.primitives` builds plates, boxes, wheels, spheres
and cones with NumPy alone. :class:`Pose3D`, :class:`Twist3D` and :class:`Wrench3D` place and move them.
"""

from .kinematics import Pose3D, Twist3D, Wrench3D, rotation_from_rpy, rpy_from_rotation
from .mesh import TriangleMesh, load_mesh, resample, save_mesh
from .primitives import box, cone, plate, sphere, wheel_cylinder, wheel_grousered
from .visibility import visible_facets
from .wheel import WheelMeshFit, fit_wheel_mesh, load_wheel_mesh, wheel_from_mesh

__all__ = [
    "Pose3D",
    "TriangleMesh",
    "Twist3D",
    "WheelMeshFit",
    "Wrench3D",
    "box",
    "cone",
    "fit_wheel_mesh",
    "load_mesh",
    "load_wheel_mesh",
    "plate",
    "resample",
    "rotation_from_rpy",
    "rpy_from_rotation",
    "save_mesh",
    "sphere",
    "visible_facets",
    "wheel_cylinder",
    "wheel_from_mesh",
    "wheel_grousered",
]
