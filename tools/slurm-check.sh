#!/bin/sh
# slurm-check.sh - a one-node Slurm on this machine, for developers (not
# CI; tools/slurm/README.md): munged, slurmctld and slurmd from a generated
# slurm.conf in a temporary directory, then render-array.sbatch (4 parts of
# the Cornell box) and merge.sbatch after it (--dependency=afterok); the
# merged EXR must be the bytes of a single render; then frames.sbatch over
# 3 frames of scenes/anim/orbit.scn, one per task, and again in 2 parts
# per frame with frames-merge.sbatch after it (afterok): every frame the
# bytes of svet render --frame K. Installs nothing: it
# needs Debian's slurm-wlm and munge (apt-get install -y slurm-wlm munge).
# Everything it starts it stops, by pid file, and the directory goes.
# Usage: sh tools/slurm-check.sh SVET   (make slurm-check)
set -u
S=${1:?usage: slurm-check.sh SVET}
case $S in /*) ;; *) S=$PWD/$S ;; esac
for c in munged slurmctld slurmd sbatch squeue sinfo; do
    command -v $c >/dev/null 2>&1 || {
        echo "slurm-check: no $c: apt-get install -y slurm-wlm munge" >&2
        exit 2
    }
done
D=$(mktemp -d /tmp/svet-slurm.XXXXXX)
stop() {
    for p in slurmd slurmctld munged; do
        [ -f $D/$p.pid ] && kill "$(cat $D/$p.pid)" 2>/dev/null
    done
    sleep 1
    rm -rf "$D"
}
trap stop EXIT
trap 'exit 1' INT TERM
fail() { echo "slurm-check: $*" >&2; for l in $D/*.log; do echo "--- $l" >&2; tail -20 "$l" >&2; done; exit 1; }
mkdir -p $D/state $D/spool $D/out
chmod 700 $D
# munge: a fresh key, its own socket
dd if=/dev/urandom of=$D/munge.key bs=1024 count=1 2>/dev/null
chmod 400 $D/munge.key
munged --force --key-file=$D/munge.key --socket=$D/munge.socket \
    --pid-file=$D/munged.pid --log-file=$D/munged.log \
    --seed-file=$D/munge.seed || fail "munged did not start"
H=$(hostname -s)
U=$(id -un)
cat > $D/slurm.conf <<CONF
ClusterName=svetcheck
SlurmctldHost=$H
SlurmUser=$U
SlurmdUser=$U
SlurmctldPort=16817
SlurmdPort=16818
AuthType=auth/munge
CredType=cred/munge
AuthInfo=socket=$D/munge.socket
StateSaveLocation=$D/state
SlurmdSpoolDir=$D/spool
SlurmctldPidFile=$D/slurmctld.pid
SlurmdPidFile=$D/slurmd.pid
SlurmctldLogFile=$D/slurmctld.log
SlurmdLogFile=$D/slurmd.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
SwitchType=switch/none
MpiDefault=none
SelectType=select/cons_tres
SelectTypeParameters=CR_Core
ReturnToService=2
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
NodeName=$H CPUs=$(nproc) State=UNKNOWN
PartitionName=check Nodes=ALL Default=YES MaxTime=INFINITE State=UP
CONF
export SLURM_CONF=$D/slurm.conf
slurmctld -f $D/slurm.conf || fail "slurmctld did not start"
slurmd -f $D/slurm.conf || fail "slurmd did not start"
i=0
until sinfo -h -o %T 2>/dev/null | grep -q idle; do
    i=$((i + 1)); [ $i -gt 60 ] && fail "the node is not idle after 30 s"
    sleep 0.5
done
export PARTS=4 SPP=64 SCENE=scenes/cbox.scn OUT=$D/out/cbox SVET=$S
a=$(sbatch --parsable --array=0-3 --export=ALL --chdir="$PWD" \
    -o $D/part-%a.log tools/slurm/render-array.sbatch) || fail "sbatch array"
m=$(sbatch --parsable --dependency=afterok:$a --export=ALL --chdir="$PWD" \
    -o $D/merge.log tools/slurm/merge.sbatch) || fail "sbatch merge"
i=0
while squeue -h -j "$a,$m" 2>/dev/null | grep -q .; do
    i=$((i + 1)); [ $i -gt 600 ] && fail "the jobs did not end in 300 s"
    sleep 0.5
done
[ -f $D/out/cbox.exr ] || fail "no merged image"
$S render scenes/cbox.scn --spp 64 -q -o $D/single.exr || fail "single render"
cmp $D/out/cbox.exr $D/single.exr || fail "merged image differs from the single render"
echo "slurm-check: 4 array tasks and a dependent merge: the single render's bits"
# an animation: 3 frames, one per task; then 2 parts per frame and a merge
# array after them
wait_jobs() {
    i=0
    while squeue -h -j "$1" 2>/dev/null | grep -q .; do
        i=$((i + 1)); [ $i -gt 600 ] && fail "the jobs $1 did not end in 300 s"
        sleep 0.5
    done
}
unset PARTS
export SCENE=scenes/anim/orbit.scn OUT="$D/out/orbit-%04d.exr" FIRST=5 \
    RENDER_OPTS="--set resolution=64x64 --spp 16"
f=$(sbatch --parsable --array=0-2 --export=ALL --chdir="$PWD" \
    -o $D/frame-%a.log tools/slurm/frames.sbatch) || fail "sbatch frames"
wait_jobs "$f"
export PARTS=2 SPP=16 OUT="$D/out/orbitp-%04d.exr"
f=$(sbatch --parsable --array=0-5 --export=ALL --chdir="$PWD" \
    -o $D/framepart-%a.log tools/slurm/frames.sbatch) || fail "sbatch frame parts"
m=$(sbatch --parsable --array=0-2 --dependency=afterok:$f --export=ALL \
    --chdir="$PWD" -o $D/framemerge-%a.log tools/slurm/frames-merge.sbatch) ||
    fail "sbatch frame merges"
wait_jobs "$f,$m"
for k in 5 6 7; do
    $S render $SCENE $RENDER_OPTS --frame $k -q -o $D/one.exr || fail "frame $k"
    n=$(printf %04d $k)
    cmp $D/out/orbit-$n.exr $D/one-$n.exr || fail "frame $k of the array differs"
    cmp $D/out/orbitp-$n.exr $D/one-$n.exr || fail "frame $k in 2 parts differs"
done
echo "slurm-check: 3 frames, one per task, and in 2 parts each merged per frame: the bits of svet render --frame K"
