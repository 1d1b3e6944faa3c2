#!/bin/sh
# Learns the weights of the indoor rules (indoor-rules.mln: Tab. 3.5 and more) from synthetic floor plans and writes
# samples/knowledge/indoor-learned.mln. Run from the repository root; set KSMCMC to the
# binary (default: ksmcmc on the PATH, e.g. KSMCMC=target/debug/ksmcmc). The same binary
# version gives the same bytes: synth, evidence and learning are all deterministic.
#
# Each line below is one synthetic floor (seed, then `ksmcmc synth` options), in four kinds:
# the default office floor (one corridor, offices, one storage unit), floors with halls,
# floors with two corridors, and floors with several "other" units (three, and six on a
# 500-cell floor: storage rows of narrow units beside offices of about the same width, which
# only the doors' count and the spaces they link tell apart).
#
# Discriminative learning (the types and SaLe given the geometry evidence), not
# pseudo-likelihood: PLL scores each atom with its neighbours held at the truth, and learned a
# negative weight for "Other beside Room => not SaLe" that, at inference, types a corridor
# beside eight rooms Other to collect eight same-length rewards.
set -eu
KSMCMC=${KSMCMC:-ksmcmc}
OUT=${OUT:-target/indoor-train}
mkdir -p "$OUT"
dbs=""
while read -r seed opts; do
    # shellcheck disable=SC2086 # the options are meant to split
    "$KSMCMC" synth --seed "$seed" $opts --out "$OUT/$seed" >/dev/null
    "$KSMCMC" mln evidence --world "$OUT/$seed/truth.json" --map "$OUT/$seed/map.yaml" --truth --out "$OUT/$seed.db"
    dbs="$dbs --db $OUT/$seed.db"
done <<SEEDS
1001
1002
1003
1011 --halls 1 --width 560
1012 --halls 1 --width 560
1013 --halls 2 --others 2 --width 700
1021 --corridors 2 --width 520 --height 400
1022 --corridors 2 --width 520 --height 400
1023 --corridors 2 --width 520 --height 400 --halls 1
1031 --others 3
1032 --others 3 --width 480
1033 --others 3 --halls 1 --width 600
1034 --others 6 --width 500
1035 --others 6 --width 500
SEEDS
# shellcheck disable=SC2086
"$KSMCMC" mln learn --mln samples/knowledge/indoor-rules.mln $dbs --query Room,Corr,Hall,Other,SaLe \
    --method discriminative --iterations 50 --samples 500 --prior-sigma 2 \
    --out samples/knowledge/indoor-learned.mln
