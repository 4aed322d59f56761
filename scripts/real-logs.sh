#!/usr/bin/env bash
# The gap diagnosis on two public real-robot logs, read from the files as
# recorded (README, "Real logs"):
#   - Franka Panda, exciting trajectory of Gaz et al. 2019 (1 kHz, joint torque
#     sensors, no hand): marcocognetti/FrankaEmikaPandaDynModel;
#   - KUKA LWR4+ (200 Hz, joint torque sensors): kjyv/FloBaRoID, the three
#     records of 2016 (LFS pointers at HEAD, real files in the history).
#
# Usage: [HOLD_LINKS=1 | JUDGE_LINKS=1] [BASELINE_LINKS=moments] bash scripts/real-logs.sh PANDA_REPO FLOBAROID_REPO [WORKDIR]
#   HOLD_LINKS=1: diagnose as `dynamics diagnose --hold-links` does;
#   JUDGE_LINKS=1: as `--judge-links` does.
#   BASELINE_LINKS=moments: the least-squares baseline with each link's mass
#   and first moments alone instead of all ten parameters.
#   PANDA_REPO, FLOBAROID_REPO: git clones (bare or not) of the two
#   repositories; WORKDIR (default $TMPDIR/dynamics-real-logs) receives the
#   extracted files, a throwaway crate with the two robots (the KUKA from its
#   URDF by absolute path: nothing of it enters this repository), the JSON
#   reports, and the table printed at the end.
#
# Splits: Panda, one 21 s record: train on 0-10.5 s, hold out 10.5-21 s,
# against the arm as logged and against the model WITH the hand and fingers
# (robots/data/urdf/panda.urdf), which the log does not carry.
# KUKA, three 25 s records: train on 1, hold out 2 (same trajectory), 3
# (another one); train on 3, hold out 1; each with the CAD URDF as it is
# and without its friction.
set -euo pipefail

[ $# -ge 2 ] || { sed -n 2,20p "$0"; exit 2; }
ROOT=$(cd "$(dirname "$0")/.." && pwd)
PANDA_REPO=$(cd "$1" && pwd)
KUKA_REPO=$(cd "$2" && pwd)
WORK=${3:-${TMPDIR:-/tmp}/dynamics-real-logs}
mkdir -p "$WORK"
WORK=$(cd "$WORK" && pwd)

# The commits the README names.
PANDA_COMMIT=24d85ce4e648e2e894c832bfeee9b16711eb1a1a
KUKA_DATA_COMMIT=e6c077ea5c09bceb49840f49e83450bb5979029b
KUKA_MODEL_COMMIT=9c0680445e874947bac4056cd86ff9e26bdd7fcb

show() { # repo commit path out
    git -C "$1" show "$2:$3" > "$4" 2>/dev/null || {
        echo "real-logs: $1 has no $3 at commit $2 (fetch the full history: git fetch --unshallow)" >&2
        exit 1
    }
}

echo "extracting into $WORK" >&2
mkdir -p "$WORK/panda" "$WORK/kuka"
for f in time positions velocity torques; do
    show "$PANDA_REPO" "$PANDA_COMMIT" \
        "matlab/data/Exciting_Traj/Trajectory_1/rbt_log/exciting_traj_$f.txt" \
        "$WORK/panda/exciting_traj_$f.txt"
done
show "$PANDA_REPO" "$PANDA_COMMIT" matlab/dyn_model_panda/get_FrictionTorque.m "$WORK/panda/get_FrictionTorque.m"
for i in 1 2 3; do
    show "$KUKA_REPO" "$KUKA_DATA_COMMIT" "data/KUKA/HW/measurements_$i.npz" "$WORK/kuka/measurements_$i.npz"
done
show "$KUKA_REPO" "$KUKA_MODEL_COMMIT" model/kuka_lwr4.urdf "$WORK/kuka/kuka_lwr4.urdf"
show "$KUKA_REPO" "$KUKA_MODEL_COMMIT" model/kuka_lwr4_identified.urdf "$WORK/kuka/kuka_lwr4_identified.urdf"
# The CAD file's <dynamics damping friction> are placeholders (0.2-1.2 N m
# s/rad, 0.05-0.8 N m); most URDFs carry no friction at all. The same file
# without them is the second nominal model the KUKA is diagnosed with.
sed 's#<dynamics [^>]*/>##' "$WORK/kuka/kuka_lwr4.urdf" > "$WORK/kuka/kuka_lwr4_no_friction.urdf"

# The throwaway crate: the robots by absolute URDF path, and a runner.
CRATE="$WORK/crate"
mkdir -p "$CRATE/src"
cat > "$CRATE/Cargo.toml" <<EOF
[package]
name = "real-logs"
version = "0.1.0"
edition = "2021"
publish = false

[dependencies]
dynamics-macros = { path = "$ROOT/dynamics-macros" }
dynamics-runtime = { path = "$ROOT/dynamics-runtime" }
dynamics-sim2real = { path = "$ROOT/dynamics-sim2real" }
serde_json = "1"
nalgebra = "0.34"

[workspace]
EOF
cat > "$CRATE/src/robots.rs" <<EOF
dynamics_macros::robot! {
    /// KUKA LWR4+, FloBaRoID's CAD model (model/kuka_lwr4.urdf).
    pub robot Kuka;
    gravity = [0.0, 0.0, -9.81];
    urdf = "$WORK/kuka/kuka_lwr4.urdf";
}

dynamics_macros::robot! {
    /// The same without its <dynamics damping friction>.
    pub robot KukaNoFriction;
    gravity = [0.0, 0.0, -9.81];
    urdf = "$WORK/kuka/kuka_lwr4_no_friction.urdf";
}

dynamics_macros::robot! {
    /// The Panda without its hand (as logged by Gaz et al.).
    pub robot PandaArm;
    gravity = [0.0, 0.0, -9.81];
    urdf = "$ROOT/robots/data/urdf/panda_arm.urdf";
}

dynamics_macros::robot! {
    /// The Panda WITH its hand and fingers (0.76 kg the log does not carry):
    /// the diagnosis should find that mass missing at the flange.
    pub robot PandaHand;
    gravity = [0.0, 0.0, -9.81];
    urdf = "$ROOT/robots/data/urdf/panda.urdf";
}
EOF
cp "$ROOT/scripts/real-logs/main.rs" "$ROOT/scripts/real-logs/baseline.rs" "$CRATE/src/"

echo "building the throwaway crate (first time: a few minutes)" >&2
cargo build --release --quiet --manifest-path "$CRATE/Cargo.toml" --target-dir "$WORK/target"
RUN="$WORK/target/release/real-logs"

P="$WORK/panda"
PANDA_MAP="t=exciting_traj_time.txt,q=exciting_traj_positions.txt,qd=exciting_traj_velocity.txt,tau=exciting_traj_torques.txt"
KUKA_MAP="t=times,q=positions,qd=velocities,tau=torques"
K="$WORK/kuka"
{
    "$RUN" panda-arm "$PANDA_MAP" "$P" 0:10.5 "$P" 10.5:21 "$WORK/panda.json" "$P/get_FrictionTorque.m"
    "$RUN" panda-hand "$PANDA_MAP" "$P" 0:10.5 "$P" 10.5:21 "$WORK/panda-hand.json" "$P/get_FrictionTorque.m"
    "$RUN" kuka "$KUKA_MAP" "$K/measurements_1.npz" - "$K/measurements_2.npz" - "$WORK/kuka-1-2.json" "$K/kuka_lwr4_identified.urdf"
    "$RUN" kuka "$KUKA_MAP" "$K/measurements_1.npz" - "$K/measurements_3.npz" - "$WORK/kuka-1-3.json" "$K/kuka_lwr4_identified.urdf"
    "$RUN" kuka "$KUKA_MAP" "$K/measurements_3.npz" - "$K/measurements_1.npz" - "$WORK/kuka-3-1.json" "$K/kuka_lwr4_identified.urdf"
    "$RUN" kuka-no-friction "$KUKA_MAP" "$K/measurements_1.npz" - "$K/measurements_2.npz" - "$WORK/kuka-no-friction-1-2.json" "$K/kuka_lwr4_identified.urdf"
    "$RUN" kuka-no-friction "$KUKA_MAP" "$K/measurements_1.npz" - "$K/measurements_3.npz" - "$WORK/kuka-no-friction-1-3.json" "$K/kuka_lwr4_identified.urdf"
    "$RUN" kuka-no-friction "$KUKA_MAP" "$K/measurements_3.npz" - "$K/measurements_1.npz" - "$WORK/kuka-no-friction-3-1.json" "$K/kuka_lwr4_identified.urdf"
} | tee "$WORK/table.md"
