"""Do texplore and Mitsuba 3 render the mesh peer scene alike? Compares them at identical sample
points: Mitsuba's stratified sampler without jitter (the centres of k x k cells) against
texplore's `regular` sampler, which places the same points, so any difference is the renderers'
own (intersection, interpolated (u, v), the v flip, the texture lookup), not noise.

usage (from the repository, with the venv and DRJIT_LIBLLVM_PATH of scripts/side-by-side.sh):
  texplore render scripts/peers-mesh/peer-mesh.ron --spp 16 --sampler regular -o /tmp/tx.exr
  PEERS_DIR=DIR python scripts/peers-mesh/agree.py /tmp/tx.exr 16

DIR holds what the side-by-side copies into its WORK (target/side-by-side-mesh after one run of
`SCENE=mesh scripts/side-by-side.sh`): this folder's mi_scene.py, torus-knot.ply and the peers'
tex_checker_2048x1024.png. Prints the RMSE over all 640 x 480 x 3 linear values, the largest
difference and how many pixels differ by more than 0.01.
"""
import os
import sys

import numpy as np
import mitsuba as mi

mi.set_variant("llvm_ad_rgb")
sys.path.insert(0, os.environ["PEERS_DIR"])
from mi_scene import scene_dict  # noqa: E402

ours, spp = sys.argv[1], int(sys.argv[2])
d = scene_dict("bilinear", "stratified", spp)
d["sensor"]["sampler"]["jitter"] = False
theirs = np.array(mi.render(mi.load_dict(d), spp=spp), dtype=np.float64)
tx = np.array(mi.Bitmap(ours), dtype=np.float64)[..., :3]
if tx.shape != theirs.shape:
    sys.exit(f"agree: {ours} is {tx.shape[1]}x{tx.shape[0]}, Mitsuba's render 640x480")
diff = np.abs(theirs - tx)
far = diff.max(axis=2) > 0.01
print(f"{spp} spp, identical sample points: RMSE {np.sqrt((diff ** 2).mean()):.3g}, "
      f"largest difference {diff.max():.3g}, {far.sum()} pixels differ by more than 0.01 "
      f"(RMSE {np.sqrt((diff[~far] ** 2).mean()):.3g} without them)")
