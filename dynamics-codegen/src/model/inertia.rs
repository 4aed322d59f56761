//! Physical checks of mass properties given as numbers.

/// True when the symmetric matrix [ixx, iyy, izz, ixy, ixz, iyz] is positive
/// definite (Sylvester's criterion on the leading minors).
pub fn positive_definite(i: [f64; 6]) -> bool {
    let [xx, yy, zz, xy, xz, yz] = i;
    let m1 = xx;
    let m2 = xx * yy - xy * xy;
    let m3 = xx * (yy * zz - yz * yz) - xy * (xy * zz - yz * xz) + xz * (xy * yz - yy * xz);
    m1 > 0.0 && m2 > 0.0 && m3 > 0.0
}

#[cfg(test)]
mod tests {
    use super::positive_definite;

    #[test]
    fn diagonal_and_off_diagonal() {
        assert!(positive_definite([1.0, 2.0, 3.0, 0.0, 0.0, 0.0]));
        assert!(!positive_definite([1.0, 0.0, 3.0, 0.0, 0.0, 0.0]));
        assert!(!positive_definite([1.0, 1.0, 1.0, 2.0, 0.0, 0.0]));
        assert!(positive_definite([2.0, 2.0, 2.0, 0.5, 0.5, 0.5]));
        assert!(!positive_definite([1.0, 1.0, 1.0, 0.0, 0.0, -1.0]));
    }
}
