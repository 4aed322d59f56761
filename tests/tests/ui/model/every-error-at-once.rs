use dynamics_macros::robot;

robot! {
    pub robot Arm;
    gravity = [0.0, -9.81];
    link base;
    link l1 { mass = -1.0; com = [x, 0.0, 0.0]; }
    link l1;
    joint j1 = telescopic(base -> l1) { transfer = [rot_z(q)]; }
    joint j2 = revolute(base -> l9) { axis = [0, 0, 0]; }
}

fn main() {}
