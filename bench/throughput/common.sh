# shellcheck shell=bash
# Sourced by the bench/throughput scripts: what they share.

# median FILE: the median of the numbers in FILE, one a line (of an even count, the lower middle
# one: a value that was measured, not an average of two).
median() { sort -g "$1" | awk '{ v[NR] = $1 } END { print v[int((NR + 1) / 2)] }'; }
