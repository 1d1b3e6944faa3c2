#!/bin/sh
# Learns the weights of the room rules (rooms.mln: which units with no wall between them are
# one room) from the chain's own worlds of synthetic floors, and writes
# samples/knowledge/rooms-learned.mln. Run from the repository root; set KSMCMC to the binary
# (default: ksmcmc on the PATH, e.g. KSMCMC=target/release/ksmcmc). The same binary version
# gives the same bytes: synth, the chain (fixed seed), evidence and learning are deterministic.
#
# Each line below is one synthetic floor (seed, then `ksmcmc synth` options), in seven kinds:
# the default office floor, floors with halls, with two corridors, cluttered (furnished)
# floors, rotated floors, floors with many storage units, and floors with wide openings
# (open.json: doorways 2.2 to 2.8 m wide, as wide as a narrow room, so that rooms open onto
# corridors and halls with no wall between them; the generator's other floors have 0.8 to
# 1.2 m doors, and their chain worlds have almost no open pair of two different rooms to learn
# from). The seeds (2001 on) are not those of `ksmcmc evaluate` (100-105, 200-205, 300-305)
# nor of learn-indoor.sh (1001-1035).
#
# For each floor the chain explains the map (`ksmcmc floorplan`, seed 1, knowledge mode, the
# defaults), and `ksmcmc mln evidence --rooms` turns its world into a training world: the
# evidence the room layer gives the rules (Open, Flush, the unit types) and SameRoom for every
# open pair whose two units lie mostly in the same truth room (truth_labels.pgm). The truth
# worlds themselves would teach nothing: their units are already the rooms.
set -eu
KSMCMC=${KSMCMC:-ksmcmc}
OUT=${OUT:-target/rooms-train}
LEARNED=${LEARNED:-samples/knowledge/rooms-learned.mln}
mkdir -p "$OUT"
cat >"$OUT/open.json" <<JSON
{"door_width": [2.2, 2.8], "room_width": [3.0, 5.0], "corridor_width": [2.5, 3.0], "other_width": [3.0, 3.5]}
JSON
dbs=""
while read -r seed opts; do
    # shellcheck disable=SC2086 # the options are meant to split
    "$KSMCMC" synth --seed "$seed" $opts --out "$OUT/$seed" >/dev/null
    "$KSMCMC" floorplan "$OUT/$seed/map.yaml" --seed 1 --out "$OUT/$seed/run" >/dev/null
    "$KSMCMC" mln evidence --rooms --world "$OUT/$seed/run/world.json" --map "$OUT/$seed/map.yaml" \
        --truth-labels "$OUT/$seed/truth_labels.pgm" --mln samples/knowledge/rooms.mln --out "$OUT/$seed.db"
    dbs="$dbs --db $OUT/$seed.db"
done <<SEEDS
2001
2002
2003
2011 --halls 1 --width 600
2012 --halls 1 --width 600
2013 --halls 2 --others 2 --width 700
2021 --corridors 2 --width 500 --height 400
2022 --corridors 2 --width 500 --height 400
2023 --corridors 2 --width 520 --height 400 --halls 1
2031 --clutter 0.1
2032 --clutter 0.1 --width 500
2033 --clutter 0.15 --halls 1 --width 600
2034 --clutter 0.1 --corridors 2 --width 500 --height 400
2041 --rotation 20
2042 --rotation 30 --width 500
2043 --rotation 12 --clutter 0.1
2044 --rotation 35 --halls 1 --width 600
2051 --others 6 --width 500
2052 --others 6 --width 500 --clutter 0.1
2053 --others 4 --corridors 2 --width 500 --height 400
2061 --config $OUT/open.json --width 500
2062 --config $OUT/open.json --width 600 --halls 1
2063 --config $OUT/open.json --width 600 --halls 1 --clutter 0.1
2064 --config $OUT/open.json --width 500 --height 400 --corridors 2
2065 --config $OUT/open.json --width 600 --halls 2 --rotation 20
2066 --config $OUT/open.json --width 500 --clutter 0.1 --rotation 10
SEEDS
# shellcheck disable=SC2086
"$KSMCMC" mln learn --mln samples/knowledge/rooms.mln $dbs --query SameRoom \
    --method discriminative --iterations 200 --prior-sigma 2 \
    --out "$LEARNED"
