# shellcheck shell=bash
# Statistics over lists of rates (numbers separated by spaces), shared by the benchmark scripts,
# which source it:
#   median                          reads a list on stdin, prints its median
#   run_by_run BEFORE AFTER SCALE FORMAT
#                                   prints SCALE * after / before for each position of the two
#                                   lists (a run against the run just before it), in FORMAT
median() { tr ' ' '\n' | grep -v '^$' | sort -g | awk '{a[NR]=$1} END {print a[int((NR+1)/2)]}'; }
run_by_run() {
  paste <(tr ' ' '\n' <<< "$1" | grep -v '^$') <(tr ' ' '\n' <<< "$2" | grep -v '^$') |
    awk -v scale="$3" -v format="$4 " '{printf format, scale * $2 / $1}'
}
