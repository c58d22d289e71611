#!/usr/bin/env bash
# Evaluation demo: the CoolMoves section 4.1 protocol (--quick subset of the
# repo's sample trials): accentuation engine vs the full-body IK baseline,
# with the document's figures beside ours.
# Env: LEGWORK (CLI binary), OUT (demo output dir), DATA (repo data/cmu).
set -euo pipefail
out="$OUT/eval"
mkdir -p "$out"
video=""
command -v ffmpeg >/dev/null 2>&1 && video="--video"
"$LEGWORK" eval accent --data "$DATA" --quick $video --out "$out" | tee "$out/summary.txt"
cat > "$out/README.txt" <<'TXT'
body_parts.png: mean joint error per body part (like the document's Figure 4 A), engine vs IK baseline, document's figures beside ours
classes.png: full-body error per activity class, both protocols
ablation.png: nearest neighbour only -> + rotation alignment -> + smoothing (cross-subject), with the document's 16.5 / 13.2 / 11.4 cm
compare.mp4: a held-out trial: ground truth, the accent engine and the IK baseline side by side (driven by its head and hands only)
report.md: tables and the targets met or not, computed from this run (quick subset of the sample data)
report.json: every figure per protocol, method, class and fold
TXT
