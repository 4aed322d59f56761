use dynamics_macros::robot;

robot! {
    pub robot Gripper;
    gravity = [0.0, 0.0, -9.81];
    const GEAR = 1.0 / 0.0;
    link base;
    link palm { mass = 0.5; }
    link left { mass = 0.05; }
    link right { mass = 0.05; }
    link thumb { mass = 0.05; }
    link tip { mass = 0.05; }
    link pad { mass = 0.05; }
    joint wrist = revolute(base -> palm) { axis = [0.0, 0.0, 1.0]; }
    joint finger_left = prismatic(palm -> left) { axis = [0.0, 1.0, 0.0]; mimic = wrist; multiplier = wrist; }
    joint finger_right = prismatic(palm -> right) { axis = [0.0, 1.0, 0.0]; mimic = wrist; multiplier = GEAR; }
    joint thumb_joint = revolute(palm -> thumb) { axis = [1.0, 0.0, 0.0]; mimic = [wrist]; }
    joint tip_joint = revolute(thumb -> tip) { axis = [1.0, 0.0, 0.0]; offset = 0.1; }
    joint pad_joint = fixed(tip -> pad) { mimic = wrist; }
}

fn main() {}
