#!/bin/bash
# Renders every scene of WORK/scenes.json with Cycles: each reference variant as two renders of
# SPP samples with seeds 1 and 2 (compare.py averages them and takes their difference as the
# noise estimate); a scene's cycles_spp_scale multiplies SPP (the rough metal: Multiscatter GGX's
# stochastic evaluation is its noise). Metals have no diffuse lobe: one render serves the three
# variants.
# usage: render_cycles.sh WORK [SPP]
set -euo pipefail
work=$1
spp=${2:-256}
here=$(cd "$(dirname "$0")" && pwd)
out=$work/out/cycles
mkdir -p "$out"
scenes=$(/usr/bin/python3 -c "import json,sys; d=json.load(open(sys.argv[1])); print(' '.join(s['name']+':'+str(s['material'].get('metalness',0))+':'+str(s.get('cycles_spp_scale',1)) for s in d['scenes']))" "$work/scenes.json")
for entry in $scenes; do
  IFS=: read -r name metal scale <<< "$entry"
  n_spp=$((spp * scale))
  variants="principled lambert_add lambert_scaled"
  [ "$metal" != "0" ] && [ "$metal" != "0.0" ] && variants=principled
  for v in $variants; do
    for seed in 1 2; do
      f=$out/${name}__${v}__s${seed}.exr
      [ -f "$f" ] && continue
      nice -n 10 blender -b --factory-startup --python "$here/cycles_scene.py" -- \
        "$work/scenes.json" "$name" "$v" "$n_spp" "$seed" "$f" "$work/etables" 2>&1 | grep CYCLES_DONE \
        || { echo "cycles: $name $v seed $seed failed" >&2; exit 1; }
    done
  done
done
