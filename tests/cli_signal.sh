#!/usr/bin/env bash
# Interrupted runs leave no temporary files: a run stopped by SIGTERM, SIGINT or SIGHUP while it writes its
# outputs removes the BASE.<ext>.tmp<pid> files it was writing (src/sys/file.c). Runs are stopped the moment a
# temporary file appears, while an HDF5 file or a PNG plot (gnuplot) is written (the CSV and XDMF files are
# written too fast to be caught), on 1 and 2 ranks, and at a spread of delays over a whole run; a normal run
# leaves none either. On 2 ranks the signal goes to the ranks, as a batch system sends it (mpiexec itself
# forwards a SIGTERM only after a delay, by which time the files are mostly written).
cd "$(dirname "$0")/.."
. tests/cli_lib.sh
set -m # background runs get SIGINT's default action, not the ignored one of a script's background jobs
osc="-options_file runs/oscillator_frf.opts -cont_monitor 0"
modes="-task modes -model_type brb -model_mesh_h 0.01 -modes_nev 10"
left() { (cd "$1" && ls | grep '\.tmp' | tr '\n' ' '); } # the temporary files in directory $1
mkfifo "$tmp/tick"
exec 9<> "$tmp/tick" # read -t on it: a pause without a process
n=0

# a normal run: its outputs and no temporary file
d="$tmp/normal"; mkdir -p "$d"
$J $osc -frf_output_file "$d/osc" > /dev/null 2>&1
check "[ -s '$d/osc.csv' ] && [ -s '$d/osc.h5' ] && [ -z \"\$(left '$d')\" ]" "a normal run writes its outputs and leaves no temporary file"

# signal SIGNAL PID: send SIGNAL to the run PID: to its ranks if it is mpiexec (once they are started)
signal() {
  local k
  k=$(pgrep -P "$2" -x jointrom | tr '\n' ' ')
  kill -"$1" ${k:-$2} 2> /dev/null
}
# catch DIR SIGNAL PATTERN COMMAND...: run COMMAND in the background, send SIGNAL the moment a file matching
# PATTERN appears in DIR (looked for every 2 ms), wait for it (and 1 s for anything it started); prints
# "caught|finished STATUS"
catch() {
  local d=$1 sig=$2 pat=$3 seen=finished pid rc
  shift 3
  # the run starts with the default actions, whatever this script inherited (a background job, or a make run from
  # one, starts with SIGINT ignored, and a signal ignored at the start stays ignored: in the script and in jointrom)
  env --default-signal=INT,TERM,HUP "$@" > "$d/log" 2>&1 &
  pid=$!
  while kill -0 $pid 2> /dev/null; do
    if compgen -G "$d/$pat" > /dev/null; then
      signal "$sig" $pid
      seen=caught
      break
    fi
    read -r -t 0.002 -u 9 || true
  done
  wait $pid
  rc=$?
  sleep 1
  echo "$seen $rc"
}
# stopped SIGNAL PATTERN RANKS ARGS...: a run stopped while it writes a file matching PATTERN leaves no temporary file
stopped() {
  local sig=$1 pat=$2 np=$3 d r
  shift 3
  n=$((n + 1))
  d="$tmp/c$n"
  mkdir -p "$d"
  local o=-frf_output_file
  case " $* " in *" -task modes "*) o=-modes_output_file ;; esac # each task takes only its own output option
  # a run that ends (exit 0) between the file's appearance and the signal was not stopped: tried again, up to 5 times
  for try in 1 2 3 4 5; do
    rm -f "$d"/*
    if [ "$np" = 1 ]; then r=$(catch "$d" "$sig" "$pat" $J "$@" $o "$d/out")
    else r=$(catch "$d" "$sig" "$pat" mpiexec -n "$np" $J "$@" $o "$d/out"); fi
    [ "$r" = "caught 0" ] || break
  done
  check "[ '${r% *}' = caught ] && [ '${r#* }' != 0 ] && [ -z \"\$(left '$d')\" ]" "SIG$sig on $np rank(s) while writing $pat (run ${r% *}, exit ${r#* }): temporary files left: [$(left "$d")]"
}
stopped TERM '*.h5.tmp*' 1 $modes
stopped TERM '*.png.tmp*' 1 $modes
stopped TERM '*.h5.tmp*' 2 $modes
stopped TERM '*.png.tmp*' 1 $osc
stopped TERM '*.png.tmp*' 2 $osc
stopped INT '*.png.tmp*' 1 $osc
stopped HUP '*.png.tmp*' 1 $osc

# SIGTERM at delays spread over a whole run of the oscillator on 2 ranks (outputs at its end): none left, ever
d="$tmp/delays"; mkdir -p "$d"
t0=$(date +%s%N)
mpiexec -n 2 $J $osc -frf_output_file "$d/full" > /dev/null 2>&1
T=$((($(date +%s%N) - t0) / 1000000))
bad=""; stop=0
for i in $(seq 1 8); do
  mpiexec -n 2 $J $osc -frf_output_file "$d/out" > /dev/null 2>&1 &
  pid=$!
  sleep "$(awk -v t=$T -v i=$i 'BEGIN{printf "%.3f", (0.5 + 0.08 * i) * t / 1000}')"
  signal TERM $pid
  wait $pid || stop=$((stop + 1))
  sleep 1
  bad="$bad$(left "$d")"
  rm -f "$d"/out.*
done
check "[ -z '$bad' ]" "SIGTERM at 8 delays from 58% to 114% of a $T ms run on 2 ranks ($stop stopped): temporary files left: [$bad]"
