#!/usr/bin/env bash
# End to end on a real Slurm cluster started on loopback: munged, slurmctld
# and two slurmd daemons emulating two nodes (n1, n2: one CPU each) on this
# machine, with every path (config, keys, sockets, pids, logs, spool, state)
# in a fresh temporary folder, unique ports, and no systemd. The daemons are
# stopped by PID when the script exits, whatever happened.
#
#   tests/farm/slurm_e2e.sh [SKYBAKE]     (default: build/skybake)
#   tests/farm/slurm_e2e.sh --with-cluster CMD [ARGS...]   (just the cluster, for CMD)
#
# Checks:
#  1. a catalog of 20 presets (23 when a dependent product is registered) baked
#     through `plan --emit ninja --edges product --launcher "srun ..."` and `ninja -j 2` inside
#     `salloc -N2`: exit 0, every edge ran as a job step, outputs, stamps and
#     manifests byte-identical to a local `skybake bake`;
#  2. the steps ran on both nodes (a wrapper after srun records
#     $SLURMD_NODENAME for each step);
#  3. a second run does no work (ninja "no work to do", no new step);
#     the default scene edges through srun: one step per scene, the same
#     bytes, no work the second time;
#  4. a product made to fail (a folder squatting on its output path) fails its
#     step: ninja exits non-zero through salloc and names it, its dependents
#     (when a product with dependencies is registered) do not run, and with
#     -k 0 the independent products complete;
#  5. `plan --emit slurm --chunk 3` submitted with `sbatch`: every array
#     task succeeds, tasks ran on both nodes, outputs byte-identical to the
#     local bake, and plan then finds nothing stale.
#
# Needs the packages of scripts/install-deps.sh (slurmctld slurmd
# slurm-client munge ninja-build; missing ones fail the test) and root, or a
# cluster that starts as this user; otherwise it exits 77 (skip) saying why.
# Exit 0 pass, 1 fail, 77 skip.
set -euo pipefail

here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
repo="$(cd "$here/../.." && pwd)"
with_cluster=()
if [ "${1:-}" = "--with-cluster" ]; then
  # `slurm_e2e.sh --with-cluster CMD ARGS...`: start the cluster, run CMD with
  # SLURM_CONF pointing at it (e.g. bench/farm_bench.sh, or `bash` to play),
  # stop the cluster, exit with CMD's status. SKYBAKE names the executable.
  shift
  [ $# -ge 1 ] || { echo "usage: $0 --with-cluster CMD [ARGS...]" >&2; exit 2; }
  with_cluster=("$@")
  set --
fi
skybake="${1:-${SKYBAKE:-$repo/build/skybake}}"
skybake="$(cd "$(dirname "$skybake")" && pwd)/$(basename "$skybake")"
[ -x "$skybake" ] || { echo "slurm_e2e: no skybake executable at $skybake" >&2; exit 1; }
export PATH="$PATH:/usr/sbin:/sbin"
# Not part of any outer Slurm job: our clients talk to our cluster only.
for v in $(compgen -e | grep -E '^(SLURM_|SBATCH_|SALLOC_|SRUN_)' || true); do unset "$v"; done

skip() { echo "slurm_e2e: SKIP: $*"; exit 77; }

# --- packages ------------------------------------------------------------------
# scripts/install-deps.sh installs slurmctld slurmd slurm-client munge
# ninja-build; a test never installs packages itself.
commands=(slurmctld slurmd srun salloc sbatch scontrol sinfo munged munge ninja)
missing_commands() { local c; for c in "${commands[@]}"; do command -v "$c" >/dev/null || echo "$c"; done; }
if [ -n "$(missing_commands)" ]; then
  echo "slurm_e2e: FAIL: missing $(missing_commands | tr '\n' ' ')(run scripts/install-deps.sh)" >&2
  exit 1
fi

# --- the cluster -----------------------------------------------------------------
T="$(mktemp -d /tmp/skybake-slurm-e2e.XXXXXX)"
chmod 755 "$T"  # munged wants every folder above its socket searchable by all
pids=()          # daemons we started, stopped in reverse order
cluster_up=0
ran_command=0    # --with-cluster: CMD's own failure needs no daemon logs

print_logs() {
  local f
  # The .out files hold what a daemon printed before its log file was open.
  for f in "$T"/munged.out "$T"/slurmctld.out "$T"/slurmctld.log "$T"/slurmd-n1.out "$T"/slurmd-n1.log \
    "$T"/slurmd-n2.out "$T"/slurmd-n2.log; do
    [ -s "$f" ] || continue
    case "$f" in *.out) [ -s "${f%.out}.log" ] && continue ;; esac
    echo "----- $f (last 30 lines)" >&2
    tail -n 30 "$f" >&2
  done
}

cleanup() {
  local rc=$? p i
  [ "$rc" -eq 0 ] || [ "$rc" -eq 77 ] || [ "$ran_command" -eq 1 ] || print_logs
  if [ "$cluster_up" -eq 1 ]; then
    timeout 10 scancel --quiet --user="$(id -un)" 2>/dev/null || true
    # Let slurmd reap the steps of cancelled jobs before it goes away.
    for ((i = 0; i < 50; i++)); do
      [ -z "$(timeout 5 squeue -h -o %i 2>/dev/null)" ] && break
      sleep 0.2
    done
  fi
  for ((i = ${#pids[@]} - 1; i >= 0; i--)); do kill -TERM "${pids[i]}" 2>/dev/null || true; done
  for p in "${pids[@]}"; do
    for ((i = 0; i < 50; i++)); do kill -0 "$p" 2>/dev/null || break; sleep 0.1; done
    kill -KILL "$p" 2>/dev/null || true
    wait "$p" 2>/dev/null || true
  done
  if [ "$rc" -eq 0 ] || [ "$rc" -eq 77 ]; then
    rm -rf "$T"
  else
    echo "slurm_e2e: FAILED; files kept in $T" >&2
  fi
  exit "$rc"
}
trap cleanup EXIT
trap 'exit 130' INT TERM

fail() { echo "slurm_e2e: FAIL: $*" >&2; exit 1; }
ok() { echo "ok   $*"; }

# Polls a command until it succeeds; $1 seconds at most.
poll() {
  local timeout="$1" i
  shift
  for ((i = 0; i < timeout * 5; i++)); do
    "$@" >/dev/null 2>&1 && return 0
    sleep 0.2
  done
  return 1
}
port_free() { ! (exec 3<>"/dev/tcp/127.0.0.1/$1") 2>/dev/null; }
started() {  # name pid: the daemon has not exited
  kill -0 "$2" 2>/dev/null || fail "$1 exited at start"
}
# As root a failed start is a failure; as another user, a reason to skip.
cannot_start() {
  if [ "$(id -u)" -ne 0 ]; then print_logs; skip "$* (not root)"; fi
  fail "$*"
}

# Four free ports: slurmctld, the (unused) default slurmd port, n1, n2.
ports=""
for ((try = 0; try < 50; try++)); do
  base=$((20000 + RANDOM % 30000))
  if port_free $base && port_free $((base + 1)) && port_free $((base + 2)) && port_free $((base + 3)); then
    ports=$base
    break
  fi
done
[ -n "$ports" ] || fail "no four free ports found"

user="$(id -un)"
host="$(hostname -s 2>/dev/null || uname -n)"
host="${host%%.*}"
mkdir -p "$T/munge" "$T/state" "$T/spool/n1" "$T/spool/n2" "$T/tasks"
chmod 755 "$T/munge"
head -c 1024 /dev/urandom >"$T/munge/munge.key"
chmod 600 "$T/munge/munge.key"
: >"$T/plugstack.conf"
cat >"$T/slurm.conf" <<EOF
# Generated by tests/farm/slurm_e2e.sh: two emulated nodes on loopback.
ClusterName=skybake-e2e
SlurmctldHost=$host(127.0.0.1)
SlurmctldPort=$ports
SlurmdPort=$((ports + 1))
AuthType=auth/munge
AuthInfo=socket=$T/munge/munge.sock
CredType=cred/munge
SlurmUser=$user
SlurmdUser=$user
StateSaveLocation=$T/state
SlurmdSpoolDir=$T/spool/%n
SlurmctldPidFile=$T/slurmctld.pid
SlurmdPidFile=$T/slurmd-%n.pid
SlurmctldLogFile=$T/slurmctld.log
SlurmdLogFile=$T/slurmd-%n.log
SlurmctldDebug=info
SlurmdDebug=info
PlugStackConfig=$T/plugstack.conf
MailProg=/bin/true
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
SelectType=select/cons_tres
SelectTypeParameters=CR_CPU
SchedulerParameters=batch_sched_delay=0,sched_min_interval=0
SlurmdParameters=config_overrides
MpiDefault=none
ReturnToService=2
KillWait=2
MinJobAge=600
AccountingStorageType=accounting_storage/none
JobAcctGatherType=jobacct_gather/none
JobCompType=jobcomp/none
NodeName=n1 NodeAddr=127.0.0.1 NodeHostname=$host Port=$((ports + 2)) CPUs=1 State=UNKNOWN
NodeName=n2 NodeAddr=127.0.0.1 NodeHostname=$host Port=$((ports + 3)) CPUs=1 State=UNKNOWN
PartitionName=farm Nodes=n1,n2 Default=YES MaxTime=INFINITE State=UP
EOF
export SLURM_CONF="$T/slurm.conf"

t_start=$(date +%s.%N)
munged -F --key-file="$T/munge/munge.key" --socket="$T/munge/munge.sock" \
  --pid-file="$T/munge/munged.pid" --seed-file="$T/munge/munged.seed" \
  --log-file="$T/munge/munged.log" >"$T/munged.out" 2>&1 &
pids+=($!)
poll 10 munge -S "$T/munge/munge.sock" -n || cannot_start "munged did not come up"

slurmctld -D -f "$T/slurm.conf" >"$T/slurmctld.out" 2>&1 &
pids+=($!)
cluster_up=1
started slurmctld "${pids[-1]}"
poll 30 bash -c 'scontrol ping | grep -q "is UP"' || cannot_start "slurmctld did not come up"
for n in n1 n2; do
  slurmd -D -N "$n" -f "$T/slurm.conf" >"$T/slurmd-$n.out" 2>&1 &
  pids+=($!)
done
nodes_idle() { [ "$(sinfo -h -N -o '%N %t' | sort -u | tr '\n' ' ')" = "n1 idle n2 idle " ]; }
poll 30 nodes_idle || cannot_start "the two slurmd did not register as idle: $(sinfo -N 2>&1 | tr '\n' ' ')"
ok "0. cluster up in $(awk "BEGIN{printf \"%.1f\", $(date +%s.%N) - $t_start}") s: munged, slurmctld :$ports, slurmd n1 :$((ports + 2)), n2 :$((ports + 3)) ($T)"
if [ ${#with_cluster[@]} -gt 0 ]; then
  rc=0
  ran_command=1
  SKYBAKE="$skybake" "${with_cluster[@]}" || rc=$?
  exit "$rc"
fi

# --- helpers shared with ninja_e2e.sh ------------------------------------------
. "$here/e2e_checks.sh"  # same_outputs, edges_run, find_dependent_product
# Runs ninja inside a 2-node allocation; output in $nlog, exit code in $rc.
salloc_ninja() {
  rc=0
  nlog="$(timeout 120 salloc -Q -N2 -n2 ninja "$@" 2>&1)" || rc=$?
}

# --- the catalog and a local reference -------------------------------------------
cat="$T/catalog"
"$here/make_catalog.sh" -s 64x32 20 "$cat" >/dev/null
dep="$(find_dependent_product)"
dep_scene=""
if [ -n "$dep" ]; then
  "$here/make_catalog.sh" -s 64x32 -i 20 -p "transmittance,$dep" 3 "$cat" >/dev/null
  dep_scene=earth_021
fi
scenes=$(find "$cat" -maxdepth 1 -name '*.json' | wc -l)
nodes=$scenes
[ -z "$dep" ] || nodes=$((scenes + 3))
"$skybake" bake "$cat"/*.json -o "$T/ref" --threads 2 --quiet

# Each step records the node it ran on, then runs the edge's command.
cat >"$T/on_node.sh" <<EOF
#!/bin/sh
echo "\${SLURMD_NODENAME:-none} \$*" >"$T/tasks/\${SLURM_JOB_ID}.\${SLURM_STEP_ID}.\$\$"
exec "\$@"
EOF
chmod +x "$T/on_node.sh"
# -N1: inside a 2-node allocation srun would otherwise default to both nodes
# and warn "can't run 1 processes on 2 nodes" for every edge.
launcher="srun -N1 -n1 -c1 --exact --quiet $T/on_node.sh"

# 1. ninja + srun inside salloc.
"$skybake" plan "$cat" --emit ninja --edges product --launcher "$launcher" -o "$T/out" --emit-file "$T/build.ninja" 2>/dev/null
grep -q "^launcher = srun " "$T/build.ninja" || fail "build.ninja has no srun launcher"
t0=$(date +%s.%N)
salloc_ninja -f "$T/build.ninja" -j 2
t1=$(date +%s.%N)
[ "$rc" -eq 0 ] || fail "salloc ninja exited $rc:
$nlog"
[ "$(edges_run "$nlog")" -eq "$nodes" ] || fail "ninja ran $(edges_run "$nlog") edges, expected $nodes:
$nlog"
steps=$(find "$T/tasks" -type f | wc -l)
[ "$steps" -eq "$nodes" ] || fail "$steps job steps recorded for $nodes edges"
# Named <job>.<step>.<pid>: a task outside a job step would have no step id.
[ "$(find "$T/tasks" -type f -regex '.*/[0-9]+\.[0-9]+\.[0-9]+' | wc -l)" -eq "$steps" ] ||
  fail "edges ran outside job steps: $(ls "$T/tasks")"
grep -L ' bake ' "$T"/tasks/* | grep -q . && fail "a job step did not run skybake bake"
same_outputs "$T/ref" "$T/out"
ok "1. ninja -j 2 + srun in salloc: $nodes edges as $steps job steps in $(awk "BEGIN{printf \"%.1f\", $t1 - $t0}") s, byte-identical to a local bake"

# 2. Both nodes did work.
on_n1=$(cat "$T"/tasks/* | grep -c '^n1 ' || true)
on_n2=$(cat "$T"/tasks/* | grep -c '^n2 ' || true)
[ "$on_n1" -ge 1 ] && [ "$on_n2" -ge 1 ] && [ $((on_n1 + on_n2)) -eq "$nodes" ] ||
  fail "steps per node: n1 $on_n1, n2 $on_n2 (expected both, $nodes in all)"
ok "2. steps ran on both nodes: n1 $on_n1, n2 $on_n2"

# 3. A second run does no work.
salloc_ninja -f "$T/build.ninja" -j 2
[ "$rc" -eq 0 ] && grep -q 'no work to do' <<<"$nlog" || fail "second run did work (exit $rc):
$nlog"
[ "$(find "$T/tasks" -type f | wc -l)" -eq "$steps" ] || fail "second run launched job steps"
ok "3. second run: no work to do, no job step"

# 3b. The default scene edges through srun: one job step per scene.
"$skybake" plan "$cat" --emit ninja --launcher "$launcher" -o "$T/out_scene" --emit-file "$T/scene.ninja" 2>/dev/null
steps_before=$(find "$T/tasks" -type f | wc -l)
salloc_ninja -f "$T/scene.ninja" -j 2
[ "$rc" -eq 0 ] && [ "$(edges_run "$nlog")" -eq "$scenes" ] || fail "scene edges through srun: exit $rc, expected $scenes edges:
$nlog"
scene_steps=$(($(find "$T/tasks" -type f | wc -l) - steps_before))
[ "$scene_steps" -eq "$scenes" ] || fail "$scene_steps job steps for $scenes scene edges"
same_outputs "$T/ref" "$T/out_scene"
salloc_ninja -f "$T/scene.ninja" -j 2
[ "$rc" -eq 0 ] && grep -q 'no work to do' <<<"$nlog" || fail "second run of scene edges did work:
$nlog"
ok "3b. scene edges (the default) through srun: $scene_steps job steps for $scenes scenes, byte-identical to a local bake, then no work"

# 4. A failing product stops its dependents and is reported; -k 0 completes the rest.
entries=("$cat/*_00[0-5].json")
fnodes=6
if [ -n "$dep" ]; then entries+=("$cat/*_02[0-2].json"); fnodes=12; fi
"$skybake" plan "${entries[@]}" --emit ninja --edges product --launcher "$launcher" -o "$T/outf" --emit-file "$T/fail.ninja" 2>/dev/null
bad=${dep_scene:-earth_000}
mkdir -p "$T/outf/$bad/transmittance.exr"
salloc_ninja -f "$T/fail.ninja" -j 2 -k 0
[ "$rc" -ne 0 ] || fail "the run succeeded although $bad/transmittance cannot be written:
$nlog"
grep -q "^FAILED: .*$bad/.stamps/transmittance.stamp" <<<"$nlog" || fail "ninja does not name the failed edge:
$nlog"
grep -q "skybake: error: .*$bad/transmittance.exr" <<<"$nlog" || fail "skybake's error is not reported:
$nlog"
expected_ok=$((fnodes - 1))
if [ -n "$dep" ]; then
  expected_ok=$((fnodes - 2))
  grep -q "bake $bad/$dep" <<<"$nlog" && fail "the dependent $bad/$dep ran after its input failed:
$nlog"
  [ ! -e "$T/outf/$bad/.stamps/$dep.stamp" ] || fail "the dependent $bad/$dep was baked"
fi
[ ! -e "$T/outf/$bad/.stamps/transmittance.stamp" ] || fail "a failed product got a stamp"
done_stamps=$(find "$T/outf" -path '*/.stamps/*.stamp' | wc -l)
[ "$done_stamps" -eq "$expected_ok" ] || fail "with -k 0, $done_stamps of $expected_ok independent products completed:
$nlog"
for s in $(cd "$T/outf" && find . -path '*/.stamps/*.stamp'); do
  cmp -s "$T/outf/$s" "$T/ref/$s" || fail "stamp $s differs from the local bake"
done
if [ -n "$dep" ]; then note="dependent $dep not run"; else note="no dependent product registered yet"; fi
ok "4. failing $bad/transmittance: salloc/ninja exit $rc, edge named, $note, $expected_ok independent products done"

# 5. The job-array script.
"$skybake" plan "$cat" --emit slurm --chunk 3 -o "$T/outs" --emit-file "$T/bake.sbatch" 2>/dev/null
tasks=$(((scenes + 2) / 3))
grep -q "^#SBATCH --array=0-$((tasks - 1))\$" "$T/bake.sbatch" || fail "bake.sbatch should have $tasks array tasks:
$(grep SBATCH "$T/bake.sbatch")"
mkdir -p "$T/sbatch"
t0=$(date +%s.%N)
job="$(cd "$T/sbatch" && sbatch --parsable "$T/bake.sbatch" 2>&1)" || fail "sbatch failed: $job"
[[ "$job" =~ ^[0-9]+$ ]] || fail "sbatch --parsable printed '$job', not a job id"
# `sbatch --wait` polls every few seconds; squeue every 0.2 s is quicker.
job_done() { [ -z "$(squeue -h -j "$job" -o %i 2>/dev/null)" ]; }
poll 120 job_done || fail "the job array $job did not finish in 120 s: $(squeue -j "$job" 2>&1)"
t1=$(date +%s.%N)
logs=$(find "$T/sbatch" -name "skybake-${job}_*.log" | wc -l)
[ "$logs" -eq "$tasks" ] || fail "$logs array task logs for $tasks tasks"
info="$(scontrol show job -o "$job")"
[ "$(grep -c 'JobState=COMPLETED' <<<"$info")" -eq "$tasks" ] || fail "not every array task completed:
$info
$(cat "$T"/sbatch/*.log 2>/dev/null)"
grep -q 'NodeList=n1 ' <<<"$info" && grep -q 'NodeList=n2 ' <<<"$info" ||
  fail "the array tasks did not use both nodes:
$(grep -oE 'ArrayTaskId=[0-9]+|NodeList=[^ ]+' <<<"$info" | paste - -)"
same_outputs "$T/ref" "$T/outs"
plan="$("$skybake" plan "$cat" -o "$T/outs" --json)"
grep -q '^  "nodes": \[\],$' <<<"$plan" || fail "plan finds stale products after the job array"
ok "5. --emit slurm --chunk 3: $tasks array tasks on n1 and n2 in $(awk "BEGIN{printf \"%.1f\", $t1 - $t0}") s, byte-identical to a local bake, nothing stale after"

echo "slurm_e2e: PASS"
