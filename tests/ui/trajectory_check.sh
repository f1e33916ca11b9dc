#!/usr/bin/env bash
# Usage: trajectory_check.sh SONARSIM DIR
# DIR/traj.csv was saved by the viewer and played back with one snapshot per pose (DIR/traj.csv.K.npy):
# every pose rendered by `sonarsim render --pose`, and every frame of `sonarsim batch --trajectory` on that CSV,
# must give the same raw image byte for byte.
set -euo pipefail
sonarsim=$1
dir=$2
rows=0
while IFS=, read -r t x y z roll pitch yaw; do
  [ "$t" = "t" ] && continue
  "$sonarsim" render --pose "$x,$y,$z,$roll,$pitch,$yaw" --out "$dir/render.$rows" >/dev/null
  cmp "$dir/render.$rows.npy" "$dir/traj.csv.$rows.npy"
  rows=$((rows + 1))
done <"$dir/traj.csv"
rm -rf "$dir/batch"
"$sonarsim" batch --trajectory "$dir/traj.csv" --out "$dir/batch" >/dev/null
for ((k = 0; k < rows; k++)); do
  cmp "$dir/batch/frames/$(printf %06d "$k").npy" "$dir/traj.csv.$k.npy"
done
echo "$rows poses: the viewer's playback equals render --pose and batch --trajectory"
[ "$rows" -ge 3 ] || { echo "FAIL: expected at least 3 recorded poses, got $rows"; exit 1; }
