#!/bin/sh
# Issue 35 item 2: the averaged-pressure puncture law under frictional surface contact (mu = 0.3) on the three §6.2
# needles and three tip meshes (40, 28, 20 um), one run at a time on one thread; docs/indentation.md ("Averaged
# pressure under friction") has the table this prints.
#   bench/averaged_pressure_friction.sh [NEEDLEKIT] [OUTDIR]   (defaults: build/bin/needlekit, /tmp/ap_friction)
set -eu
here=$(dirname "$0")
needlekit=${1:-build/bin/needlekit}
out=${2:-/tmp/ap_friction}
mkdir -p "$out"
for needle in sharp_bevel blunt_bevel cylinder; do
  for size in 40 28 20; do
    start=$(date +%s.%N)
    status=0
    OMP_NUM_THREADS=1 timeout 720 nice -n 19 "$needlekit" indent "$here/cases/averaged_pressure_friction/$needle.toml" \
      --json --size-at-tip "$size um" > "$out/${needle}_$size.json" 2> "$out/${needle}_$size.err" || status=$?
    end=$(date +%s.%N)
    echo "$needle $size um: exit $status, wall $(echo "$end - $start" | bc) s"
    echo "$end - $start" | bc > "$out/${needle}_$size.wall"
  done
done
python3 - "$out" <<'PY'
import json, sys, pathlib
out = pathlib.Path(sys.argv[1])
print("| needle | mesh at the tip | tets | reached | puncture depth | force at puncture | p̄_l at 400 µm | F(400 µm) | wall |")
print("|---|---|---|---|---|---|---|---|---|")
for needle in ("sharp_bevel", "blunt_bevel", "cylinder"):
    for size in (40, 28, 20):
        wall = float((out / f"{needle}_{size}.wall").read_text())
        try:
            j = json.loads((out / f"{needle}_{size}.json").read_text())
        except ValueError:
            print(f"| {needle} | {size} µm | — | — | — | — | — | — | {wall:.0f} s (no result) |")
            continue
        depth = j["puncture_depth_um"]
        force = j["puncture_force_N"]
        print(f"| {needle} | {size} µm | {j['elements']} | {j['depth_um'][-1]:.1f} µm | "
              + (f"{depth:.1f} µm | {force * 1e3:.3f} mN" if depth is not None else "none within 400 µm | —")
              + f" | {j['averaged_pressure_MPa'][-1]:.3f} MPa | {j['force_N'][-1] * 1e3:.3f} mN | {wall:.0f} s |")
for needle in ("sharp_bevel", "blunt_bevel", "cylinder"):
    for size in (40, 28, 20):
        try:
            j = json.loads((out / f"{needle}_{size}.json").read_text())
        except ValueError:
            continue
        print(f"{needle} {size} um p̄_l (MPa) per step:", " ".join(f"{p:.3f}" for p in j["averaged_pressure_MPa"]))
PY
