#!/usr/bin/env bash
# The gallery's story: its introduction and the order of its sections
# ("folder/: Heading - intro" lines of $OUT/README.txt, read by legwork gallery).
set -euo pipefail
cat > "$OUT/README.txt" <<'TXT'
legwork gives VR and game characters bodies. This page shows what the demo made from the sample motion capture in data/cmu, in the order of the story: the data, legs for walking in place, generated walk cycles, a full body from a headset and two controllers (accentuation), its evaluation, and the live path through a browser.
Under every result is the command that made it (run from the repository root; demo-out/ is the output folder). In every figure the character's left side is blue and the right side orange.
foundation/: Data - a CMU walk read, described, drawn and converted to glTF and back
render/: Drawing motion - contact sheets, joint paths and videos of CMU clips
wip/: Walking in place - legs for an avatar from two ankle trackers, compared with a key-frame baseline and evaluated on real walking
walkcycle/: Walk cycle - walks generated from five key poses along any path, without foot slip, and key poses extracted from mocap
accent/: Accentuation - a full body from the head and hands only (CoolMoves nearest-neighbour synthesis), on a walk the database never saw
eval/: Evaluation - the accentuation engine against a full-body IK baseline, with the source document's figures beside ours
live/: Live - legwork serve and the browser viewer replaying a trial's head and hands through a WebSocket
TXT
