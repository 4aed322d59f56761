use dynamics_macros::robot;

robot! {
    pub robot Arm;
    gravity = [0.0, -9.81, 0.0];
    link base;
    link l1 { mass = 1.0; com = [0.5, 0.0, 0.0]; inertia = [1e-3, 0.1, 0.1]; }
    joint j1 = revolute(base -> l1) { transfer = [rot_z(q)]; }
    constraint circle = sin(j1) + cos(j2);
}

fn main() {}
