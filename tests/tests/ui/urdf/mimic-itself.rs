use dynamics_macros::robot;

robot! {
    pub robot Arm;
    gravity = [0.0, 0.0, -9.81];
    urdf = "urdf-fixtures/mimic-itself.urdf";
}

fn main() {}
