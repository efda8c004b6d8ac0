#!/bin/sh
# Checkpoint and restart (docs/checkpoint.md): a run stopped by SIGINT or SIGTERM mid-run, or killed
# outright after a periodic checkpoint, and then continued with --restart writes the same bytes into every
# output file (frames, pictures, pvd, every CSV log) as the same run never stopped; cmp decides, nothing is
# tolerated. Cases: explicit MUSL Mohr-Coulomb with probes and pictures on two threads, sources and sinks,
# implicit Newmark dynamics, implicit friction (each contact node's force carries over steps), explicit
# friction sides (the touching points' impulses and the wall profiles carry over steps), two
# bodies in contact (contact_pairs), MPM with LME (each particle's kept stencil), APIC (each particle's
# affine matrix) and XPIC, GMM with MLS and with
# LME, RKPM and implicit GMM (the node cloud, its cell list, the nodes' velocity and acceleration history).
# What is not covered (a strength reduction, another case, a damaged file, another layout version) is refused
# with exit 2.
# usage: restart_test.sh PMECH SOURCE_DIR WORK_DIR
set -u
PMECH=$1; SRC=$2; WORK=$3
. "$SRC/tests/cli/test_lib.sh"
export OMP_WAIT_POLICY=passive
# every file of the uninterrupted run but run.json (wall times), checkpoint.h5 and the lock, byte for byte
same_outputs() {
  a=$1; b=$2; bad=0
  [ -f "$a/particles.pvd" ] && [ -f "$b/particles.pvd" ] || return 1
  for f in $(cd "$a" && ls -A); do
    case $f in run.json|checkpoint.h5|.pmech.lock) continue;; esac
    if ! cmp -s "$a/$f" "$b/$f"; then echo "     differs: $f"; bad=1; fi
  done
  for f in $(cd "$b" && ls -A); do
    [ -e "$a/$f" ] || { echo "     not in the uninterrupted run: $f"; bad=1; }
  done
  return $bad
}
# case name, signal, frame to wait for, exit status[, threads]: a
# full run, a run stopped by the signal once that frame exists, its continuation; then the two directories
# compared
stop_and_continue() {
  name=$1; sig=$2; frame=$3; code=$4; threads=${5:-1}
  "$PMECH" run "$name.json" -o "$name.full" --quiet --threads $threads >/dev/null 2>&1
  check "$name: the uninterrupted run" [ $? -eq 0 ]
  "$PMECH" run "$name.json" -o "$name.part" --quiet --threads $threads >/dev/null 2>err.txt & pid=$!
  i=0; while [ ! -f "$name.part/$frame" ] && [ $i -lt 3000 ]; do sleep 0.02; i=$((i + 1)); done
  kill -"$sig" $pid; wait $pid; rc=$?
  check "$name: SIG$sig stops the run mid-way (exit $rc)" [ $rc -eq "$code" ]
  check "$name: a checkpoint was written" [ -f "$name.part/checkpoint.h5" ]
  cp "$name.part/checkpoint.h5" "$name.stop.h5" 2>/dev/null
  "$PMECH" run "$name.json" --restart "$name.part" --quiet --threads $threads >/dev/null 2>err.txt
  rc=$?
  check "$name: the restart runs to the end (exit $rc)" [ $rc -eq 0 ]
  [ $rc -eq 0 ] || cat err.txt
  check "$name: every output file is identical to the uninterrupted run's" same_outputs "$name.full" "$name.part"
  check "$name: run.json counts the steps of both parts" python3 -c "
import json, sys
a = json.load(open('$name.full/run.json')); b = json.load(open('$name.part/run.json'))
sys.exit(0 if a['steps'] == b['steps'] and a['end_time'] == b['end_time'] and b['exit_status'] == 0 else 1)"
}

# explicit MUSL, Mohr-Coulomb: a small cohesive column collapse with probes and a picture per frame
python3 - "$SRC" <<'PY'
import json, sys
src = sys.argv[1]
c = json.load(open(src + "/examples/column_collapse/case.json"))
c["analysis"]["end_time"] = 0.6
c["grid"]["cells"] = [30, 21]
c["output"] = {"directory": "x.out", "interval": 0.02, "pictures": "plastic_strain", "picture_width": 200}
json.dump(c, open("musl_mc.json", "w"), indent=1)
# sources and sinks: the bin fed from above and emptied through its outlet
c = json.load(open(src + "/tests/verification/cases/bin_feed.json"))
c["output"] = {"interval": c["analysis"]["end_time"] / 50}
json.dump(c, open("flow.json", "w"), indent=1)
# implicit Newmark dynamics (newton.log, reactions.csv): the Dyka bar, four times as long
c = json.load(open(src + "/tests/verification/cases/implicit_dyka_bar.json"))
c["analysis"]["end_time"] = 0.1
c["output"] = {"interval": 0.002}
json.dump(c, open("implicit.json", "w"), indent=1)
# implicit friction: a block sliding on a friction side, each contact node's force kept between steps
c = json.load(open(src + "/tests/verification/cases/implicit_sliding_block.json"))
c["boundary_conditions"][0]["coefficient"] = 0.1
c["analysis"]["end_time"] = 0.04
c["output"] = {"interval": 0.004}
json.dump(c, open("implicit_friction.json", "w"), indent=1)
# explicit friction sides: each step's sweeps at the touching points start from the last step's impulses
c = json.load(open(src + "/tests/verification/cases/janssen_bin.json"))
c["analysis"]["end_time"] = 0.4
c["output"] = {"interval": 0.02}
json.dump(c, open("explicit_friction.json", "w"), indent=1)
# a checkpoint every 0.1 s of a 0.6 s run: killed outright (SIGKILL, no checkpoint of its own) after
# the frame at 0.3 s, the run continues from the last checkpoint and replaces what was written after it
c = json.load(open("musl_mc.json"))
c["output"]["checkpoint_interval"] = 0.1
json.dump(c, open("periodic.json", "w"), indent=1)
# contact_pairs: a block dropped on another, contact_forces.csv averaging impulses between its rows
c = json.load(open(src + "/tests/verification/cases/block_drop.json"))
c["output"] = {"interval": c["analysis"]["end_time"] / 50}
json.dump(c, open("contact_pairs.json", "w"), indent=1)
# GMM (MLS, LME) and RKPM: the node cloud moves with the material and its cell list is rebuilt as nodes
# move past the skin; the column collapse on a coarse grid, long enough for rebuilds on both sides of the
# stop. RKPM's nodes are its particles, with Kronecker-delta rows on the fixed sides.
for name, method, shape in (("gmm_mls", "gmm", "mls"), ("gmm_lme", "gmm", "lme"), ("rkpm", "rkpm", "rk_cubic")):
    c = json.load(open(src + "/examples/column_collapse/case_gmm_mls.json"))
    c["method"], c["shape_function"] = method, shape
    c["analysis"]["end_time"] = 0.3 if method == "rkpm" else 0.6  # RKPM's steps are twice as many
    c["grid"]["cells"] = [30, 21]
    c["output"] = {"interval": 0.02}
    json.dump(c, open(name + ".json", "w"), indent=1)
# implicit GMM: the Dyka bar with its nodes keeping their velocity and acceleration for the next predictor
c = json.load(open("implicit.json"))
c["method"], c["shape_function"] = "gmm", "mls"
c["analysis"]["end_time"] = 0.05
json.dump(c, open("implicit_gmm.json", "w"), indent=1)
# MPM with lme: each particle keeps its last stencil and lambda, the start of the next evaluation
c = json.load(open("musl_mc.json"))
c["shape_function"] = "lme"
c["output"] = {"interval": 0.02}
json.dump(c, open("mpm_lme.json", "w"), indent=1)
# APIC: each particle's affine matrix, the only particle field of its own; XPIC: nothing beyond the
# velocities (its filter is rebuilt every step)
for t in ("apic", "xpic"):
    c = json.load(open("musl_mc.json"))
    c["analysis"]["transfer"] = t
    json.dump(c, open("musl_" + t + ".json", "w"), indent=1)
PY
# two threads: the colour blocks of the parallel scatter decide the order of additions into shared nodes
stop_and_continue musl_mc INT particles_000004.vtu 130 2
stop_and_continue flow TERM particles_000005.vtu 143
stop_and_continue implicit INT particles_000005.vtu 130
stop_and_continue implicit_friction INT particles_000004.vtu 130
stop_and_continue explicit_friction INT particles_000010.vtu 130
stop_and_continue contact_pairs INT particles_000010.vtu 130
stop_and_continue periodic KILL particles_000016.vtu 137
stop_and_continue mpm_lme INT particles_000012.vtu 130 2
stop_and_continue musl_apic INT particles_000004.vtu 130 2
stop_and_continue musl_xpic INT particles_000004.vtu 130 2
# the meshfree runs, with the number of cell-list builds: some before the stop and more after it, so the
# continued run goes on from a restored cell list and rebuilds it as the uninterrupted run did
builds() { h5dump -a /meshfree/builds "$1" 2>/dev/null | sed -n 's/.*(0): \([0-9]*\).*/\1/p'; }
for m in gmm_mls:12 gmm_lme:12 rkpm:08 implicit_gmm:10; do
  frame=${m#*:}; m=${m%:*}
  stop_and_continue $m INT particles_0000$frame.vtu 130 2
  b0=$(builds $m.stop.h5); b1=$(builds $m.full/checkpoint.h5)
  check "$m: the cell list was rebuilt before the stop (${b0:-?} builds) and after it (${b1:-?})" \
    [ "${b0:-0}" -gt 1 -a "${b1:-0}" -gt "${b0:-0}" ]
done

# ---- the layout of docs/checkpoint.md, read by HDF5's own h5dump (hdf5-tools)
n=$(python3 -c "import json; print(json.load(open('musl_mc.full/run.json'))['particles'])")
check "h5dump reads /particles/x as $n x 2" sh -c \
  "h5dump -H -d /particles/x musl_mc.full/checkpoint.h5 | grep -q 'SIMPLE { ( $n, 2 ) / ( $n, 2 ) }'"
check "h5dump reads /particles/C as $n x 4 with APIC" sh -c \
  "h5dump -H -d /particles/C musl_apic.full/checkpoint.h5 | grep -q 'SIMPLE { ( $n, 4 ) / ( $n, 4 ) }'"
check "h5dump reads /particles/C as $n x 0 with FLIP (no affine matrices)" sh -c \
  "h5dump -H -d /particles/C musl_mc.full/checkpoint.h5 | grep -q 'SIMPLE { ( $n, 0 ) / ( $n, 0 ) }'"
check "h5dump reads /particles/v_grid as $n x 2" sh -c \
  "h5dump -H -d /particles/v_grid musl_mc.full/checkpoint.h5 | grep -q 'SIMPLE { ( $n, 2 ) / ( $n, 2 ) }'"
check "h5dump reads /time/t as the end time" sh -c \
  "h5dump -a /time/t musl_mc.full/checkpoint.h5 | grep -q '(0): 0.6\$'"

# ---- refusals: exit 2, a message that says why, nothing in the directory touched
expect_refusal() { # description, text the message must hold, command...
  d=$1; text=$2; shift 2
  "$@" >out.txt 2>err.txt; rc=$?
  check "$d: exit 2 (got $rc)" [ $rc -eq 2 ]
  check "$d: says '$text'" grep -q -- "$text" err.txt
}
cp -r musl_mc.part kept.part
sed 's/"friction_angle": 25/"friction_angle": 26/' musl_mc.json > changed.json
expect_refusal "another case" "belongs to another case" "$PMECH" run changed.json --restart musl_mc.part --quiet
check "another case: the outputs are untouched" same_outputs kept.part musl_mc.part
mkdir -p empty.dir
expect_refusal "no checkpoint" "there is no checkpoint.h5" "$PMECH" run musl_mc.json --restart empty.dir --quiet
head -c 3000 musl_mc.part/checkpoint.h5 > cut.h5 && mv cut.h5 musl_mc.part/checkpoint.h5
expect_refusal "a damaged checkpoint" "checkpoint.h5" "$PMECH" run musl_mc.json --restart musl_mc.part --quiet
check "a damaged checkpoint: the outputs are untouched" same_outputs kept.part musl_mc.part
# a checkpoint of the previous layout (3: a Gmsh lattice's nodes in the mesh's numbering), its attribute
# rewritten with HDF5's own library, as pmech links it
cp -r kept.part older.part
python3 - older.part/checkpoint.h5 <<'PY'
import ctypes, ctypes.util, sys
lib = ctypes.CDLL(ctypes.util.find_library("hdf5_serial") or ctypes.util.find_library("hdf5"))
lib.H5open()
for f_, r in (("H5Fopen", ctypes.c_int64), ("H5Aopen", ctypes.c_int64)):
    getattr(lib, f_).restype = r
lib.H5Fopen.argtypes = [ctypes.c_char_p, ctypes.c_uint, ctypes.c_int64]
lib.H5Aopen.argtypes = [ctypes.c_int64, ctypes.c_char_p, ctypes.c_int64]
lib.H5Awrite.argtypes = [ctypes.c_int64, ctypes.c_int64, ctypes.c_void_p]
lib.H5Aclose.argtypes = [ctypes.c_int64]
lib.H5Fclose.argtypes = [ctypes.c_int64]
f = lib.H5Fopen(sys.argv[1].encode(), 1, 0)  # H5F_ACC_RDWR, H5P_DEFAULT
a = lib.H5Aopen(f, b"format_version", 0) if f >= 0 else -1
v = ctypes.c_int32(3)
ok = a >= 0 and lib.H5Awrite(a, ctypes.c_int64.in_dll(lib, "H5T_NATIVE_INT_g").value, ctypes.byref(v)) >= 0
sys.exit(0 if ok and lib.H5Aclose(a) >= 0 and lib.H5Fclose(f) >= 0 else 1)
PY
check "the layout version rewritten to 3" [ $? -eq 0 ]
expect_refusal "an older layout" "layout version 3" "$PMECH" run musl_mc.json --restart older.part --quiet
expect_refusal "a strength reduction" "a strength reduction is a search of many runs" \
  "$PMECH" run "$SRC/examples/slope_fos/case.json" --restart empty.dir --quiet
expect_refusal "--restart with -o elsewhere" "cannot name another directory" \
  "$PMECH" run musl_mc.json --restart musl_mc.part -o other.out --quiet

finish "all checkpoint and restart checks passed"
