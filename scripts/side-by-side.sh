#!/usr/bin/env bash
# texplore against Mitsuba 3 on the peer scene, side by side on this machine (issue 15).
#
# Runs the two renderers ALTERNATELY, ROUNDS times, each on THREADS threads (default 2), on the
# peer scene (presets/peer-sphere.ron; shared/peers/ for Mitsuba's scene and harness), and prints
# a table of time, RMSE against Mitsuba's 16384-spp reference (linear, over all 640 x 480 x 3
# values) and the ratios. Only ratios measured side by side mean anything on a noisy machine.
#
#   scripts/side-by-side.sh                # 3 rounds, 5 timed renders per configuration
#   ROUNDS=5 REPEATS=7 scripts/side-by-side.sh
#   MI_SAMPLERS="stratified-nojitter" scripts/side-by-side.sh   # one Mitsuba sampler only
#
# Environment: PEERS_DIR (default ../shared/peers beside the repository), VENV (default
# target/peers-venv: created with mitsuba, numpy and pillow from PyPI when absent), WORK (default
# target/side-by-side), TEXPLORE (default target/release/texplore, built when absent).
# Mitsuba's llvm_ad_rgb variant needs LLVM 19: installed with apt-get when absent (as root).
set -euo pipefail

ROOT=$(cd "$(dirname "$0")/.." && pwd)
PEERS_DIR=${PEERS_DIR:-$ROOT/../shared/peers}
VENV=${VENV:-$ROOT/target/peers-venv}
WORK=${WORK:-$ROOT/target/side-by-side}
TEXPLORE=${TEXPLORE:-$ROOT/target/release/texplore}
ROUNDS=${ROUNDS:-3}
REPEATS=${REPEATS:-5}
THREADS=${THREADS:-2}
MI_SPP=${MI_SPP:-1,4,9,16,25,36,64}
# Every Mitsuba sampler that could be its fastest to a target: jittered strata, the cell centres
# (`stratified-nojitter`, the same points as texplore's `regular`), independent and
# multi-jittered. The table compares texplore against the fastest of them for each target.
MI_SAMPLERS=${MI_SAMPLERS:-stratified stratified-nojitter independent multijitter}
TX_SPP=${TX_SPP:-1,4,9,16,25,36,64}
TX_MODES=${TX_MODES:-bilinear/jittered,bilinear/regular}
# Modes that need few samples: their own (short) spp list.
TX_FAST_MODES=${TX_FAST_MODES:-footprint/regular,footprint/regular+adaptive,ewa/regular+adaptive}
TX_FAST_SPP=${TX_FAST_SPP:-1,2,4}

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
cp "$PEERS_DIR"/*.py "$PEERS_DIR"/ref_bilinear_16384spp.* "$WORK"/
chmod u+w "$WORK"/*
export PEERS_DIR=$WORK
(cd "$WORK" && "$VENV/bin/python" make_texture.py >/dev/null)
"$VENV/bin/python" - "$WORK" "$ROOT/assets/tex_checker_2048x1024.png" <<'PY'
import sys, numpy as np
from PIL import Image
work, ours = sys.argv[1], sys.argv[2]
np.save(f"{work}/ref_bilinear.npy", np.load(f"{work}/ref_bilinear_16384spp.npz")["ref"])
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
        (cd "$ROOT" && "$TEXPLORE" report presets/peer-sphere.ron --reference "$WORK/ref_bilinear_16384spp.exr" \
            --modes "$modes" --spp "$spp" --repeat "$REPEATS" --threads "$THREADS" --no-cache --quiet -o "$out")
    done
done
"$VENV/bin/python" "$ROOT/scripts/side_by_side_table.py" "$WORK" "$ROUNDS"
