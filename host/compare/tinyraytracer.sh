#!/usr/bin/env bash
# Times ssloy's tinyraytracer and obscura on tinyraytracer's own scene (host/scenes/tinyraytracer.toml),
# 1024x768, one thread each, on this machine, and prints each obscura format's time as a ratio
# to tinyraytracer's.
#
#   host/compare/tinyraytracer.sh [TINYRAYTRACER_CPP] [RUNS]
#
# TINYRAYTRACER_CPP defaults to a download of tinyraytracer.cpp at the commit the scene file
# describes. It is built as its CMakeLists builds it (C++17, release: -O3), without OpenMP, so it
# runs on one thread; its time is the whole process, the median of RUNS (7), and includes
# writing its 2.3 MB PPM. obscura's is `obscura bench --threads 1` (the median render of RUNS).
set -euo pipefail

commit=ce6b7852b7de11d485c017e16a9b990b94a66322
source=${1:-}
runs=${2:-7}
root=$(cd "$(dirname "$0")/../.." && pwd)
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

if [[ -z $source ]]; then
    source=$work/tinyraytracer.cpp
    curl -fsSL "https://raw.githubusercontent.com/ssloy/tinyraytracer/$commit/tinyraytracer.cpp" -o "$source"
fi
g++ -std=c++17 -O3 -DNDEBUG -o "$work/tinyraytracer" "$source"
cargo build --release --locked -q -p obscura-host --manifest-path "$root/Cargo.toml"

times=()
for _ in $(seq "$runs"); do
    start=$(date +%s%N)
    (cd "$work" && ./tinyraytracer)
    times+=($((($(date +%s%N) - start) / 1000)))
done
tiny_ms=$(printf '%s\n' "${times[@]}" | sort -n | awk -v n="$runs" 'NR == int((n + 1) / 2) { printf "%.1f", $1 / 1000 }')
echo "tinyraytracer, 1024x768, 1 thread: $tiny_ms ms (median of $runs)"

"$root/target/release/obscura" bench "$root/host/scenes/tinyraytracer.toml" --size 1024x768 \
    --formats f32,i16f16 --threads 1 --runs "$runs" --json "$work/bench.json" >/dev/null
python3 - "$work/bench.json" "$tiny_ms" <<'PY'
import json, sys
bench = json.load(open(sys.argv[1]))
tiny = float(sys.argv[2])
print("| program | format | ms/frame (1 thread) | time ÷ tinyraytracer |")
print("|---|---|---:|---:|")
print(f"| tinyraytracer | float | {tiny:.1f} | 1.00 |")
for row in bench["formats"]:
    print(f"| obscura | {row['format']} | {row['ms_per_frame']:.1f} | {row['ms_per_frame'] / tiny:.2f} |")
PY
