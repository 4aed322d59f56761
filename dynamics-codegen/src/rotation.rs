//! Constant rotations in plain arrays: Rodrigues' formula, URDF's
//! roll-pitch-yaw, products, and an inertia tensor rotated. Used where the
//! model folds constants (welding fixed links) and where the URDF reader
//! rotates an inertial frame into its link frame.

/// The rotation by `a` about the unit axis `u` (Rodrigues' formula).
pub fn rodrigues(u: [f64; 3], a: f64) -> [[f64; 3]; 3] {
    let (s, c) = a.sin_cos();
    let cross = [[0.0, -u[2], u[1]], [u[2], 0.0, -u[0]], [-u[1], u[0], 0.0]];
    let mut r = [[0.0; 3]; 3];
    for i in 0..3 {
        for j in 0..3 {
            r[i][j] = if i == j { c } else { 0.0 } + s * cross[i][j] + (1.0 - c) * u[i] * u[j];
        }
    }
    r
}

/// `m v`.
pub fn mat_vec(m: &[[f64; 3]; 3], v: [f64; 3]) -> [f64; 3] {
    std::array::from_fn(|i| (0..3).map(|k| m[i][k] * v[k]).sum())
}

/// `a b`.
pub fn mat_mat(a: &[[f64; 3]; 3], b: &[[f64; 3]; 3]) -> [[f64; 3]; 3] {
    std::array::from_fn(|i| std::array::from_fn(|j| (0..3).map(|k| a[i][k] * b[k][j]).sum()))
}

/// The symmetric matrix of a tensor [ixx, iyy, izz, ixy, ixz, iyz].
fn full(t: [f64; 6]) -> [[f64; 3]; 3] {
    let [xx, yy, zz, xy, xz, yz] = t;
    [[xx, xy, xz], [xy, yy, yz], [xz, yz, zz]]
}

/// `R I R^T` for a tensor [ixx, iyy, izz, ixy, ixz, iyz].
pub fn rotate_tensor(t: [f64; 6], r: &[[f64; 3]; 3]) -> [f64; 6] {
    let i = full(t);
    let mut out = [[0.0; 3]; 3];
    for a in 0..3 {
        for b in 0..3 {
            for k in 0..3 {
                for l in 0..3 {
                    out[a][b] += r[a][k] * i[k][l] * r[b][l];
                }
            }
        }
    }
    [
        out[0][0], out[1][1], out[2][2], out[0][1], out[0][2], out[1][2],
    ]
}

/// The rotation of URDF's `rpy`: Rz(yaw) Ry(pitch) Rx(roll).
pub fn rpy_matrix(rpy: [f64; 3]) -> [[f64; 3]; 3] {
    let rz = rodrigues([0.0, 0.0, 1.0], rpy[2]);
    let ry = rodrigues([0.0, 1.0, 0.0], rpy[1]);
    let rx = rodrigues([1.0, 0.0, 0.0], rpy[0]);
    mat_mat(&mat_mat(&rz, &ry), &rx)
}
