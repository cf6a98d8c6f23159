"""Mitsuba 3 scene for the textured-mesh side by side (dict API), the mesh counterpart of the
peers' sphere (../shared/peers/mi_scene.py): `scripts/side-by-side.sh` with SCENE=mesh copies this
file as `mi_scene.py` beside the peers' `mi_bench.py`, which imports `scene_dict` from it.

Scene (texplore's side: scripts/peers-mesh/peer-mesh.ron):
  * assets/torus-knot.ply, untransformed: a (2, 3) torus knot tube, 6144 triangles, with its own
    (u, v) (u along the knot, v around the tube, both in [0, 1]). Mitsuba's `ply` shape with
    `face_normals`: the area emitter below is one-sided in Mitsuba and tests the shading normal,
    so interpolated normals would blacken texels at the silhouette that texplore (whose Emissive
    glows on both sides) shows; with flat normals every triangle the camera sees faces it (the
    mesh is closed and wound outward).
  * the mesh is an 'area' emitter whose radiance is the peers' tex_checker_2048x1024.png read
    raw (texel = byte / 255), bilinear, repeat; its BSDF is black.
  * the v flip: a mesh's (u, v) have v = 0 at the BOTTOM row of the image (the lecture's and
    texplore's convention, and the PLY's); Mitsuba's bitmap puts v = 0 at the TOP row, so the
    bitmap's `to_uv` maps (u, v) to (u, 1 - v).
  * perspective camera at (0, 4.2, 3.4) looking at (0.18, 0, 0.05), up +y, vertical fov 40 degrees,
    640x480, box pixel filter; integrator 'path' with max_depth=1 (directly visible emission
    only); black background.
"""
import os
PEERS = os.environ.get("PEERS_DIR", os.path.dirname(os.path.abspath(__file__)))
import mitsuba as mi

TEX = f"{PEERS}/tex_checker_2048x1024.png"
PLY = f"{PEERS}/torus-knot.ply"
EYE, TARGET = [0.0, 4.2, 3.4], [0.18, 0.0, 0.05]


def scene_dict(filter_type="bilinear", sampler="independent", spp=1,
               width=640, height=480, fov=40.0, fov_axis="y", max_depth=1):
    T = mi.ScalarTransform4f
    return {
        "type": "scene",
        "integrator": {"type": "path", "max_depth": max_depth},
        "sensor": {
            "type": "perspective",
            "fov": fov,
            "fov_axis": fov_axis,
            "near_clip": 0.01,
            "far_clip": 100.0,
            "to_world": T().look_at(origin=EYE, target=TARGET, up=[0, 1, 0]),
            "sampler": {"type": sampler, "sample_count": spp},
            "film": {
                "type": "hdrfilm",
                "width": width,
                "height": height,
                "pixel_format": "rgb",
                "rfilter": {"type": "box"},
            },
        },
        "knot": {
            "type": "ply",
            "filename": PLY,
            "face_normals": True,
            "bsdf": {"type": "diffuse", "reflectance": {"type": "rgb", "value": [0.0, 0.0, 0.0]}},
            "emitter": {
                "type": "area",
                "radiance": {
                    "type": "bitmap",
                    "filename": TEX,
                    "filter_type": filter_type,
                    "wrap_mode": "repeat",
                    "raw": True,
                    # v = 1 - v: the mesh's v = 0 is the image's bottom row, Mitsuba's its top.
                    "to_uv": T().translate([0, 1, 0]) @ T().scale([1, -1, 1]),
                },
            },
        },
    }
