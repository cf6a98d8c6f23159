#!/usr/bin/env bash
# texplore against Mitsuba 3 on the peer scene, side by side on this machine (issue 15), or on the
# mesh peer scene with SCENE=mesh (issue 35).
#
# Runs the two renderers ALTERNATELY, ROUNDS times, each on THREADS threads (default 2), on the
# peer scene (presets/peer-sphere.ron; shared/peers/ for Mitsuba's scene and harness), and prints
# a table of time, RMSE against Mitsuba's 16384-spp reference (linear, over all 640 x 480 x 3
# values) and the ratios. Only ratios measured side by side mean anything on a noisy machine.
#
#   scripts/side-by-side.sh                # 3 rounds, 5 timed renders per configuration
#   ROUNDS=5 REPEATS=7 scripts/side-by-side.sh
#   MI_SAMPLERS="stratified-nojitter" scripts/side-by-side.sh   # one Mitsuba sampler only
#   SCENE=mesh scripts/side-by-side.sh     # the torus knot (scripts/peers-mesh/), see below
#
# SCENE=mesh: the shipped torus knot (assets/torus-knot.ply) with its own (u, v) under the same
# checker, emissive, read raw: scripts/peers-mesh/peer-mesh.ron for texplore, Mitsuba's `ply`
# shape with the bitmap's `to_uv` flipping v in scripts/peers-mesh/mi_scene.py (copied over the
# peers' sphere scene beside their mi_bench.py). Its reference is Mitsuba's, stratified, 8192
# spp, in MESH_REF_DIR (default ../shared/peers-mesh beside the repository), rendered there
# (a few minutes) when absent. Longer spp lists by default: the checker is minified on the knot.
#
# Environment: PEERS_DIR (default ../shared/peers beside the repository), VENV (default
# target/peers-venv: created with mitsuba, numpy and pillow from PyPI when absent), WORK (default
# target/side-by-side, or target/side-by-side-mesh), TEXPLORE (default
# target/release/texplore, built when absent).
# Mitsuba's llvm_ad_rgb variant needs LLVM 19: installed with apt-get when absent (as root).
set -euo pipefail

ROOT=$(cd "$(dirname "$0")/.." && pwd)
SCENE=${SCENE:-sphere}
PEERS_DIR=${PEERS_DIR:-$ROOT/../shared/peers}
VENV=${VENV:-$ROOT/target/peers-venv}
TEXPLORE=${TEXPLORE:-$ROOT/target/release/texplore}
ROUNDS=${ROUNDS:-3}
REPEATS=${REPEATS:-5}
THREADS=${THREADS:-2}
case $SCENE in
sphere)
    WORK=${WORK:-$ROOT/target/side-by-side}
    PRESET=$ROOT/presets/peer-sphere.ron
    REF_DIR=$PEERS_DIR
    REF=ref_bilinear_16384spp
    DEFAULT_SPP=1,4,9,16,25,36,64
    DEFAULT_FAST_SPP=1,2,4
    ;;
mesh)
    WORK=${WORK:-$ROOT/target/side-by-side-mesh}
    PRESET=$ROOT/scripts/peers-mesh/peer-mesh.ron
    REF_DIR=${MESH_REF_DIR:-$ROOT/../shared/peers-mesh}
    REF=ref_bilinear_8192spp
    # Square counts (Mitsuba's stratified sampler rounds up to a square); 0.003 takes 100-256.
    DEFAULT_SPP=1,4,9,16,25,36,64,144,256
    DEFAULT_FAST_SPP=1,2,4,9,16
    ;;
*)
    echo "side-by-side: SCENE is sphere or mesh, not '$SCENE'" >&2
    exit 1
    ;;
esac
MI_SPP=${MI_SPP:-$DEFAULT_SPP}
# Every Mitsuba sampler that could be its fastest to a target: jittered strata, the cell centres
# (`stratified-nojitter`, the same points as texplore's `regular`), independent and
# multi-jittered. The table compares texplore against the fastest of them for each target.
MI_SAMPLERS=${MI_SAMPLERS:-stratified stratified-nojitter independent multijitter}
TX_SPP=${TX_SPP:-$DEFAULT_SPP}
TX_MODES=${TX_MODES:-bilinear/jittered,bilinear/regular}
# Modes that need few samples: their own (short) spp list.
TX_FAST_MODES=${TX_FAST_MODES:-footprint/regular,footprint/regular+adaptive,ewa/regular+adaptive}
TX_FAST_SPP=${TX_FAST_SPP:-$DEFAULT_FAST_SPP}

if [ ! -f "$PEERS_DIR/mi_bench.py" ]; then
    echo "side-by-side: no Mitsuba harness in $PEERS_DIR (set PEERS_DIR to shared/peers)" >&2
    exit 1
fi
if [ ! -x "$VENV/bin/python" ]; then
    echo "side-by-side: installing Mitsuba into $VENV" >&2
    python3 -m venv "$VENV"
    "$VENV/bin/pip" install -q mitsuba numpy pillow
fi
if ! LLVM=$(dpkg -L libllvm19 2>/dev/null | grep -m1 'libLLVM.so.19'); then
    echo "side-by-side: installing LLVM 19 (Mitsuba's llvm variant needs it)" >&2
    apt-get install -y -qq libllvm19 >&2
    LLVM=$(dpkg -L libllvm19 | grep -m1 'libLLVM.so.19')
fi
export DRJIT_LIBLLVM_PATH=$LLVM
if [ ! -x "$TEXPLORE" ]; then
    echo "side-by-side: building texplore (release)" >&2
    (cd "$ROOT" && cargo build --release --quiet)
fi

# The harness writes beside itself: work on a copy.
mkdir -p "$WORK"
cp "$PEERS_DIR"/*.py "$WORK"/
if [ "$SCENE" = mesh ]; then
    cp "$ROOT/scripts/peers-mesh/mi_scene.py" "$ROOT/assets/torus-knot.ply" "$WORK"/
fi
chmod u+w "$WORK"/*
export PEERS_DIR=$WORK
(cd "$WORK" && "$VENV/bin/python" make_texture.py >/dev/null)
if [ ! -f "$REF_DIR/$REF.exr" ]; then
    # Only the mesh's reference is made here; the sphere's comes with the peers' harness.
    if [ "$SCENE" != mesh ]; then
        echo "side-by-side: no $REF.exr in $REF_DIR" >&2
        exit 1
    fi
    echo "side-by-side: rendering Mitsuba's 8192-spp reference into $REF_DIR (a few minutes)" >&2
    mkdir -p "$REF_DIR"
    (cd "$WORK" && "$VENV/bin/python" mi_bench.py ref llvm_ad_rgb bilinear stratified 256 32 >&2)
    "$VENV/bin/python" - "$WORK/ref_bilinear.npy" "$REF_DIR/$REF" <<'PY'
import sys, numpy as np, mitsuba as mi
mi.set_variant("scalar_rgb")
ref = np.load(sys.argv[1]).astype(np.float32)
np.savez_compressed(sys.argv[2] + ".npz", ref=ref)
mi.Bitmap(ref).write(sys.argv[2] + ".exr")
PY
fi
cp "$REF_DIR/$REF".* "$WORK"/
"$VENV/bin/python" - "$WORK" "$ROOT/assets/tex_checker_2048x1024.png" "$REF" <<'PY'
import sys, numpy as np
from PIL import Image
work, ours, ref = sys.argv[1:4]
np.save(f"{work}/ref_bilinear.npy", np.load(f"{work}/{ref}.npz")["ref"])
a = np.asarray(Image.open(f"{work}/tex_checker_2048x1024.png"))
b = np.asarray(Image.open(ours))
if a.shape != b.shape or (a != b).any():
    sys.exit(f"side-by-side: {ours} differs from the peers' texture: run scripts/make_peer_texture.py")
PY

rm -f "$WORK"/round-*.json
rm -rf "$WORK"/tx-round-*
for r in $(seq 1 "$ROUNDS"); do
    for sampler in $MI_SAMPLERS; do
        echo "round $r of $ROUNDS: Mitsuba, $sampler" >&2
        # mi_bench.py renders each spp once untimed before timing it, so no kernel compiles
        # inside the timing.
        (cd "$WORK" && THREADS=$THREADS "$VENV/bin/python" mi_bench.py bench llvm_ad_rgb bilinear "$sampler" "$MI_SPP" "$REPEATS" >/dev/null)
        mv "$WORK/res_llvm_ad_rgb_bilinear_${sampler}_t$THREADS.json" "$WORK/round-$r-mitsuba-$sampler.json"
    done
    echo "round $r of $ROUNDS: texplore" >&2
    for set in "$TX_MODES:$TX_SPP" "$TX_FAST_MODES:$TX_FAST_SPP"; do
        modes=${set%%:*}
        spp=${set#*:}
        out="$WORK/tx-round-$r-$(echo "$modes" | tr -c 'a-z0-9\n' '_')"
        (cd "$ROOT" && "$TEXPLORE" report "$PRESET" --reference "$WORK/$REF.exr" \
            --modes "$modes" --spp "$spp" --repeat "$REPEATS" --threads "$THREADS" --no-cache --quiet -o "$out")
    done
done
"$VENV/bin/python" "$ROOT/scripts/side_by_side_table.py" "$WORK" "$ROUNDS"
